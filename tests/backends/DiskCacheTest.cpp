// Rill's disk cache of compiled kernels (backends/cache/DiskCache.h), through every backend:
// a second compile in a "new process" (the in-process cache cleared, the same RILL_CACHE_DIR)
// loads the binary from disk and computes the same; a truncated entry, a corrupted payload
// byte and an entry written for another driver version are each detected and rebuilt; the
// size bound evicts the least recently used entries; list() and clear() work.
//
// Each test runs in a private cache directory (RILL_CACHE_DIR, restored afterwards).
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>

#include "BackendTest.h"
#include "cache/DiskCache.h"

namespace rill::testing {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}
void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

class DiskCacheTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (IsSkipped()) return;
    dir_ = fs::temp_directory_path() /
           ("rill-diskcache-test-" + std::to_string(getpid()) + "-" + backend_name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    env_.emplace("RILL_CACHE_DIR", dir_.string());
    no_profile_.emplace("RILL_PROFILE_DIR", "");  // profiling would bypass the cache
    // Rill's own binaries on OpenCL, also on PoCL, where by default its kernel cache serves
    // instead (DefaultsStoreEntriesWhereTheDescriptionSays).
    binaries_.emplace("RILL_OPENCL_BINARIES", "on");
    clear_kernel_cache();
  }
  void TearDown() override {
    clear_kernel_cache();  // no kernel of this test's cache serves a later test
    env_.reset();
    no_profile_.reset();
    binaries_.reset();
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // A kernel with a loop and a branch, so that it is not trivial for any compiler.
  static Program kernel() {
    return program("diskcache_poly", [] {
      Input<Float> x("x");
      Output<Float> y("y");
      Float acc = 0.0f;
      RILL_FOR(Int i = 0, i < 3, i = i + 1) {
        acc = acc * x + 1.5f;
      }
      RILL_ENDFOR;
      RILL_IF(x < 0.0f) {
        acc = -acc;
      }
      RILL_ENDIF;
      y = acc;
    });
  }
  static std::vector<float> inputs() {
    std::vector<float> xs;
    for (int i = -50; i < 50; ++i) xs.push_back(static_cast<float>(i) * 0.25f);
    return xs;
  }
  static std::vector<float> expected() {
    return map(inputs(), [](float x) {
      float acc = 0.0f;
      for (int i = 0; i < 3; ++i) acc = acc * x + 1.5f;
      return x < 0.0f ? -acc : acc;
    });
  }

  // Compiles the kernel as a new process would (the in-process cache emptied first), checks
  // its results and returns where it came from.
  KernelOrigin compile_fresh_and_check() {
    clear_kernel_cache();
    Kernel k = compile(kernel());
    std::vector<float> got = run_kernel<Float>(k, static_cast<int64_t>(inputs().size()), inputs());
    EXPECT_TRUE(bits_equal(got, expected()));
    EXPECT_EQ(k.info().from_disk_cache, k.info().origin == KernelOrigin::DiskCache);
    return k.info().origin;
  }

  // The cache entries of this backend (compiling the kernel makes one; several for a GLSL
  // kernel drawn in several passes).
  std::vector<cache::Entry> entries() const {
    std::vector<cache::Entry> mine;
    for (cache::Entry& e : cache::list())
      if (e.backend == backend_name()) mine.push_back(e);
    return mine;
  }

  // Compiles once (Built), applies `damage` to each entry's bytes, then checks that the next
  // compile detects it and rebuilds (Built, right results) and stores a good entry again
  // (the one after loads it).
  template <class Damage>
  void expect_rebuilt_after(Damage damage) {
    EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::Built);
    std::vector<cache::Entry> stored = entries();
    ASSERT_FALSE(stored.empty()) << "no cache entry was stored in " << dir_;
    for (const cache::Entry& e : stored) {
      std::string bytes = read_bytes(e.path);
      ASSERT_EQ(bytes.size(), e.bytes);
      damage(bytes);
      write_bytes(e.path, bytes);
    }
    EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::Built);
    EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::DiskCache);
  }

  bool driver_keeps_no_binaries() const {
    return rill::backend(backend_name()).description().find("no program binary format") !=
           std::string::npos;
  }

  fs::path dir_;
  std::optional<ScopedEnv> env_, no_profile_, binaries_;
};

#define SKIP_WITHOUT_BINARIES()                                                           \
  if (driver_keeps_no_binaries())                                                         \
  GTEST_SKIP() << "backend '" << backend_name()                                           \
               << "': the driver offers no program binary format, so nothing is cached (" \
               << rill::backend(backend_name()).description() << ")"

TEST_P(DiskCacheTest, SecondCompileInANewProcessLoadsFromDisk) {
  SKIP_WITHOUT_BINARIES();
  EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::Built);
  ASSERT_FALSE(entries().empty()) << "no cache entry was stored in " << dir_;
  EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::DiskCache);
  // In-process hits still report the process cache.
  Kernel again = compile(kernel());
  EXPECT_EQ(again.info().origin, KernelOrigin::ProcessCache);
}

// With the default settings a backend stores entries exactly when its description says it
// keeps kernels in Rill's disk cache. On PoCL with its kernel cache on, the opencl backend
// keeps none (asking PoCL for a binary costs a work-group function per kernel) and builds
// from source every time; a bad RILL_OPENCL_BINARIES is named.
TEST_P(DiskCacheTest, DefaultsStoreEntriesWhereTheDescriptionSays) {
  binaries_.reset();
  ScopedEnv automatic("RILL_OPENCL_BINARIES", "auto");
  ScopedEnv pocl_cache_on("POCL_KERNEL_CACHE", "1");
  const std::string description = rill::backend(backend_name()).description();
  const bool pocl = description.find("Portable Computing Language") != std::string::npos;
  const bool none = description.find("disk cache: the driver's own") != std::string::npos ||
                    driver_keeps_no_binaries();
  if (backend_name() == "opencl") {
    EXPECT_EQ(none, pocl) << description;
  }
  EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::Built);
  EXPECT_EQ(entries().empty(), none) << description << "; cache " << dir_;
  EXPECT_EQ(compile_fresh_and_check(), none ? KernelOrigin::Built : KernelOrigin::DiskCache);
  if (backend_name() != "opencl") return;
  // With PoCL's cache off (as PoCL reads the setting: on only when it starts with 1), Rill's
  // binaries come back, so that a second process still loads instead of compiling.
  if (pocl)
    for (const char* off : {"0", "off"}) {
      SCOPED_TRACE(std::string("POCL_KERNEL_CACHE=") + off);
      ScopedEnv pocl_cache_off("POCL_KERNEL_CACHE", off);
      EXPECT_NE(rill::backend(backend_name()).description().find("disk cache: program binaries"),
                std::string::npos);
      EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::Built);
      EXPECT_FALSE(entries().empty()) << "no OpenCL binary was stored in " << dir_;
      EXPECT_EQ(compile_fresh_and_check(), KernelOrigin::DiskCache);
      cache::clear();
    }
  ScopedEnv bad("RILL_OPENCL_BINARIES", "yes");
  EXPECT_NE(rill::backend(backend_name()).description().find("RILL_OPENCL_BINARIES='yes'"),
            std::string::npos)
      << "the description names the bad setting";
  clear_kernel_cache();
  try {
    compile(kernel());
    ADD_FAILURE() << "RILL_OPENCL_BINARIES=yes was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("RILL_OPENCL_BINARIES='yes'"), std::string::npos)
        << e.what();
  }
}

TEST_P(DiskCacheTest, TruncatedEntryIsRebuilt) {
  SKIP_WITHOUT_BINARIES();
  expect_rebuilt_after([](std::string& bytes) { bytes.resize(bytes.size() / 2); });
}

TEST_P(DiskCacheTest, CorruptedPayloadByteIsRebuilt) {
  SKIP_WITHOUT_BINARIES();
  // In the payload: the header and the key text come first.
  expect_rebuilt_after([](std::string& bytes) { bytes[bytes.size() * 3 / 4] ^= 0x5a; });
}

TEST_P(DiskCacheTest, EntryOfAnotherDriverVersionIsRebuilt) {
  SKIP_WITHOUT_BINARIES();
  // Same file name, same lengths, same payload: only the key text's driver differs, as in a
  // file-name collision or a file written by another driver version.
  expect_rebuilt_after([](std::string& bytes) {
    size_t at = bytes.find("driver=");
    ASSERT_NE(at, std::string::npos) << "an entry has no driver line in its key";
    char& c = bytes[at + 7];
    c = c == 'X' ? 'Y' : 'X';
  });
}

// The cache itself, with this backend's name on the entries.
TEST_P(DiskCacheTest, DamagedEntriesAreRemovedNotReturned) {
  const std::string b = backend_name();
  const std::string payload(1000, 'p');
  auto damaged = [&](const std::string& key, auto damage) {
    EXPECT_TRUE(cache::store(b, key, payload));
    const fs::path p = cache::entry_path(b, key);
    std::string bytes = read_bytes(p);
    damage(bytes);
    write_bytes(p, bytes);
    EXPECT_FALSE(cache::load(b, key).has_value()) << key;
    EXPECT_FALSE(fs::exists(p)) << key << ": a damaged entry is removed";
  };
  damaged("backend=x\ndriver=1\n", [](std::string& s) { s.resize(s.size() - 1); });
  damaged("backend=x\ndriver=2\n", [](std::string& s) { s.resize(10); });
  damaged("backend=x\ndriver=3\n", [](std::string& s) { s.back() ^= 1; });
  damaged("backend=x\ndriver=4\n", [](std::string& s) { s[0] = 'X'; });    // magic
  damaged("backend=x\ndriver=5\n", [](std::string& s) { s[8] ^= 0x7f; });  // version
  damaged("backend=x\ndriver=6\n", [](std::string& s) { s[40] = '9'; });   // key text
  damaged("backend=x\ndriver=7\n", [](std::string& s) { s += "extra"; });  // length
  EXPECT_TRUE(cache::store(b, "backend=x\ndriver=8\n", payload));
  EXPECT_EQ(cache::load(b, "backend=x\ndriver=8\n"), payload);
}

TEST_P(DiskCacheTest, EvictionRemovesLeastRecentlyUsedFirstAndKeepsUnderTheBound) {
  const std::string b = backend_name();
  ScopedEnv bound("RILL_CACHE_MAX_MB", "1");
  const std::string payload(300 << 10, 'e');  // three fit in 1 MB, four do not
  const auto now = fs::file_time_type::clock::now();
  int age = 40;
  for (const char* key : {"a", "b", "c"}) {
    ASSERT_TRUE(cache::store(b, key, payload));
    fs::last_write_time(cache::entry_path(b, key), now - std::chrono::seconds(age -= 10));
  }
  ASSERT_TRUE(cache::load(b, "a").has_value());  // a used last: b is now the oldest
  ASSERT_TRUE(cache::store(b, "d", payload));
  EXPECT_FALSE(fs::exists(cache::entry_path(b, "b"))) << "the least recently used is evicted";
  for (const char* key : {"a", "c", "d"})
    EXPECT_TRUE(fs::exists(cache::entry_path(b, key))) << key << " was evicted too early";
  uint64_t total = 0;
  for (const cache::Entry& e : cache::list()) total += e.bytes;
  EXPECT_LE(total, cache::max_bytes());
  EXPECT_EQ(cache::max_bytes(), uint64_t{1} << 20);
}

TEST_P(DiskCacheTest, ListAndClear) {
  const std::string b = backend_name();
  ASSERT_TRUE(cache::store(b, "one", std::string(100, '1')));
  ASSERT_TRUE(cache::store("other", "two", std::string(200, '2')));
  write_bytes(dir_ / "notes.txt", "not an entry");
  std::vector<cache::Entry> all = cache::list();
  ASSERT_EQ(all.size(), 2u);
  std::map<std::string, uint64_t> sizes;
  for (const cache::Entry& e : all) sizes[e.backend] = e.bytes;
  EXPECT_GT(sizes[b], 100u);
  EXPECT_GT(sizes["other"], 200u);
  EXPECT_EQ(sizes[b] + 100, sizes["other"]) << "same header and key length, 100 more bytes";
  EXPECT_EQ(cache::clear(), 2u);
  EXPECT_TRUE(cache::list().empty());
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt")) << "clear() deletes only cache entries";
}

RILL_BACKEND_TEST_SUITE(DiskCacheTest);

}  // namespace
}  // namespace rill::testing
