// RILL_PROFILE_DIR (backends/cpu/SharedObjectCache.h): the CPU backends compile each kernel
// with debug information into that directory and load it from there, so that profilers map
// samples to the generated C. Checked on cpu and simd: the files are there under the
// kernel's name, the C file is the kernel's source, the shared object carries line tables
// and is the one loaded, results are unchanged, a second process reuses the files, and a
// directory that cannot be made is an error that names the variable.
#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "BackendTest.h"

namespace rill::testing {
namespace {

namespace fs = std::filesystem;

std::string file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

class ProfileDir : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (IsSkipped()) return;
    dir_ = fs::temp_directory_path() /
           ("rill-profile-test-" + std::to_string(getpid()) + "-" + backend_name());
    fs::remove_all(dir_);
    env_.emplace("RILL_PROFILE_DIR", (dir_ / "kernels").string());
    clear_kernel_cache();
  }
  void TearDown() override {
    clear_kernel_cache();  // none of this test's kernels serves a later test
    env_.reset();
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  static Program kernel() {
    return program("profile_me", [] {
      Input<Float> x("x");
      Output<Float> y("y");
      Float acc = 1.0f;
      RILL_IF(x > 0.0f) {
        acc = sqrt(x) + x * x;
      }
      RILL_ENDIF;
      y = acc;
    });
  }
  static std::vector<float> inputs() { return sweep_floats(7, 1000); }
  static std::vector<float> expected() {
    return map(inputs(), [](float x) { return x > 0.0f ? std::sqrt(x) + x * x : 1.0f; });
  }
  // The files in the profile directory whose name ends with `suffix`.
  std::vector<fs::path> files(const std::string& suffix) const {
    std::vector<fs::path> found;
    for (const auto& e : fs::directory_iterator(dir_ / "kernels")) {
      const std::string name = e.path().filename().string();
      if (name.size() >= suffix.size() &&
          name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        found.push_back(e.path());
    }
    return found;
  }

  fs::path dir_;
  std::optional<ScopedEnv> env_;
};

TEST_P(ProfileDir, KernelsAreCompiledWithLineTablesIntoTheDirectoryAndLoadedFromThere) {
  EXPECT_NE(rill::backend(backend_name()).description().find(dir_.string()), std::string::npos)
      << rill::backend(backend_name()).description();

  Kernel k = compile(kernel());
  EXPECT_TRUE(bits_equal(run_kernel<Float>(k, static_cast<int64_t>(inputs().size()), inputs()),
                         expected()));
  EXPECT_EQ(k.info().origin, KernelOrigin::Built);

  const std::vector<fs::path> c_files = files(".c"), so_files = files(".so");
  ASSERT_EQ(c_files.size(), 1u);
  ASSERT_EQ(so_files.size(), 1u);
  const std::string stem = backend_name() + "-profile_me-";
  EXPECT_EQ(c_files[0].filename().string().rfind(stem, 0), 0u) << c_files[0];
  EXPECT_EQ(so_files[0].stem(), c_files[0].stem());
  EXPECT_EQ(file_text(c_files[0]), k.source());
  // Line tables that name the C file by the path it keeps (perf and callgrind read both).
  const std::string binary = file_text(so_files[0]);
  EXPECT_NE(binary.find(".debug_line"), std::string::npos);
  EXPECT_NE(binary.find(c_files[0].filename().string()), std::string::npos);
  // The loaded object is that file: dlopen by path finds it already loaded.
  void* again = dlopen(so_files[0].c_str(), RTLD_NOW | RTLD_NOLOAD);
  EXPECT_NE(again, nullptr) << "not loaded from " << so_files[0];
  if (again) dlclose(again);

  // A new process finds the files and compiles nothing; the results are the same.
  const auto written = fs::last_write_time(so_files[0]);
  clear_kernel_cache();
  Kernel reused = compile(kernel());
  EXPECT_EQ(reused.info().origin, KernelOrigin::DiskCache);
  EXPECT_TRUE(bits_equal(run_kernel<Float>(reused, static_cast<int64_t>(inputs().size()), inputs()),
                         expected()));
  EXPECT_EQ(fs::last_write_time(so_files[0]), written);
  EXPECT_EQ(files(".so").size(), 1u);
}

TEST_P(ProfileDir, ADirectoryThatCannotBeMadeIsAnErrorNamingTheVariable) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "a-file") << "not a directory";
  ScopedEnv bad("RILL_PROFILE_DIR", (dir_ / "a-file" / "kernels").string());
  try {
    compile(kernel());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("RILL_PROFILE_DIR"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("a-file"), std::string::npos) << e.what();
  }
}

// Only the CPU backends compile C (the others' drivers keep their own binaries).
std::vector<std::string> cpu_backends() {
  std::vector<std::string> names;
  for (const std::string& b : backend_names())
    if (b == "cpu" || b == "simd") names.push_back(b);
  return names;
}
INSTANTIATE_TEST_SUITE_P(Backends, ProfileDir, ::testing::ValuesIn(cpu_backends()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return param_name(info.param);
                         });

}  // namespace
}  // namespace rill::testing
