// RILL_PROFILE_DIR (backends/cpu/SharedObjectCache.h): the CPU backends compile each kernel
// with debug information into that directory and load it from there, so that profilers map
// samples to the generated C. Checked on cpu and simd: the files are there under the
// kernel's name, the C file is the kernel's source, the shared object is the one loaded and
// maps its code to the C file's lines, results are unchanged, a second process reuses the
// files, a file the loader refuses is made again, and a directory that cannot be made is an
// error that names the variable.
#include <dlfcn.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "BackendTest.h"

namespace rill::testing {
namespace {

namespace fs = std::filesystem;

std::string hex(uintptr_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(v));
  return buf;
}

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

  fs::path c_file, so_file;
  {
    Kernel k = compile(kernel());
    EXPECT_TRUE(bits_equal(run_kernel<Float>(k, static_cast<int64_t>(inputs().size()), inputs()),
                           expected()));
    EXPECT_EQ(k.info().origin, KernelOrigin::Built);

    const std::vector<fs::path> c_files = files(".c"), so_files = files(".so");
    ASSERT_EQ(c_files.size(), 1u);
    ASSERT_EQ(so_files.size(), 1u);
    c_file = c_files[0];
    so_file = so_files[0];
    EXPECT_EQ(c_file.filename().string().rfind(backend_name() + "-profile_me-", 0), 0u) << c_file;
    EXPECT_EQ(so_file.stem(), c_file.stem());
    EXPECT_EQ(file_text(c_file), k.source());
    for (const auto& e : fs::directory_iterator(dir_ / "kernels"))
      EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos)
          << "temporary file left: " << e.path();
    // The loaded object is that file: dlopen by path finds it already loaded.
    void* loaded = dlopen(so_file.c_str(), RTLD_NOW | RTLD_NOLOAD);
    ASSERT_NE(loaded, nullptr) << "not loaded from " << so_file;
    // A profiler maps the entry point to a line of the C file, as addr2line does here.
    void* entry = dlsym(loaded, "rill_run");
    Dl_info where{};
    ASSERT_TRUE(entry != nullptr && dladdr(entry, &where) != 0);
    const auto offset =
        reinterpret_cast<uintptr_t>(entry) - reinterpret_cast<uintptr_t>(where.dli_fbase);
    dlclose(loaded);
    const std::string command = "addr2line -e '" + so_file.string() + "' " + hex(offset) + " 2>&1";
    std::string line;
    if (FILE* pipe = popen(command.c_str(), "r")) {
      char buf[512];
      while (fgets(buf, sizeof buf, pipe)) line += buf;
      pclose(pipe);
    }
    EXPECT_NE(line.find(c_file.filename().string() + ":"), std::string::npos)
        << command << ": " << line;
    EXPECT_EQ(line.find("??"), std::string::npos) << command << ": " << line;
  }

  // A new process (the kernel above unloaded, the in-process cache emptied) finds the files,
  // compiles nothing and loads them again; the results are the same.
  const auto written = fs::last_write_time(so_file);
  clear_kernel_cache();
  Kernel reused = compile(kernel());
  EXPECT_EQ(reused.info().origin, KernelOrigin::DiskCache);
  EXPECT_TRUE(bits_equal(run_kernel<Float>(reused, static_cast<int64_t>(inputs().size()), inputs()),
                         expected()));
  EXPECT_EQ(fs::last_write_time(so_file), written);
  EXPECT_EQ(files(".so").size(), 1u);
}

TEST_P(ProfileDir, AFileTheLoaderRefusesIsMadeAgain) {
  { Kernel k = compile(kernel()); }
  clear_kernel_cache();
  const std::vector<fs::path> so_files = files(".so");
  ASSERT_EQ(so_files.size(), 1u);
  std::ofstream(so_files[0], std::ios::binary | std::ios::trunc) << "not an ELF file";
  Kernel again = compile(kernel());
  EXPECT_EQ(again.info().origin, KernelOrigin::Built);
  EXPECT_TRUE(bits_equal(run_kernel<Float>(again, static_cast<int64_t>(inputs().size()), inputs()),
                         expected()));
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
