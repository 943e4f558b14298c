// The vulkan backend's disk cache entries, looked into (the generic checks of every backend
// are DiskCacheTest.cpp's): an entry holds each pass's SPIR-V and the driver's pipeline cache
// data (VulkanBackend.cpp, pack()); a compile as a new process would do it (the in-process
// cache emptied, the same RILL_CACHE_DIR) loads it, which the kernel's origin says, and
// computes the same bits. Entries that pass the cache's checksum but not the backend's checks
// (stored again with the right key and a payload of the wrong shape, a SPIR-V module without
// its magic number, driver data of another device) are rejected: the kernel is compiled from
// source to the same bits and the same SPIR-V, or, for the driver data, made from the cached
// SPIR-V alone, and the entry is written anew.
#include <unistd.h>

#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "BackendTest.h"
#include "cache/DiskCache.h"

#include "vulkan/VkContext.h"  // the header layout, rill::vk::hex

namespace rill::testing {
namespace {

namespace fs = std::filesystem;

constexpr uint32_t kSpirvMagic = 0x07230203;
constexpr size_t kEntryHeader = 32;  // DiskCache.h: magic, version, lengths, checksum

// The parts of a vulkan entry.
struct Parsed {
  std::string key;                           // the entry's key text
  std::vector<std::vector<uint32_t>> spirv;  // per pass
  std::string driver_data;                   // vkGetPipelineCacheData's bytes
};

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Reads an entry file back; the layout is DiskCache.h's and pack()'s.
std::optional<Parsed> parse(const fs::path& file) {
  const std::string bytes = read_bytes(file);
  if (bytes.size() < kEntryHeader) return std::nullopt;
  uint32_t key_length = 0;
  uint64_t payload_length = 0;
  std::memcpy(&key_length, bytes.data() + 12, 4);
  std::memcpy(&payload_length, bytes.data() + 16, 8);
  if (bytes.size() != kEntryHeader + key_length + payload_length) return std::nullopt;
  Parsed out;
  out.key = bytes.substr(kEntryHeader, key_length);
  const std::string payload = bytes.substr(kEntryHeader + key_length);
  size_t at = 0;
  auto word = [&](uint32_t& w) {
    if (payload.size() - at < 4) return false;
    std::memcpy(&w, payload.data() + at, 4);
    at += 4;
    return true;
  };
  uint32_t passes = 0;
  if (!word(passes)) return std::nullopt;
  for (uint32_t i = 0; i < passes; ++i) {
    uint32_t words = 0;
    if (!word(words) || words > (payload.size() - at) / 4) return std::nullopt;
    std::vector<uint32_t> m(words);
    for (uint32_t& w : m) word(w);
    out.spirv.push_back(std::move(m));
  }
  out.driver_data = payload.substr(at);
  return out;
}

// pack()'s payload for these parts.
std::string pack(const std::vector<std::vector<uint32_t>>& spirv, const std::string& driver_data) {
  std::string out;
  auto put = [&](uint32_t w) { out.append(reinterpret_cast<const char*>(&w), 4); };
  put(static_cast<uint32_t>(spirv.size()));
  for (const auto& m : spirv) {
    put(static_cast<uint32_t>(m.size()));
    for (uint32_t w : m) put(w);
  }
  return out + driver_data;
}

std::vector<std::string> vulkan_if_built() {
  std::vector<std::string> v;
  for (const std::string& b : backend_names())
    if (b == "vulkan") v.push_back(b);
  return v;
}

class VulkanDiskCacheTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (IsSkipped()) return;
    dir_ = fs::temp_directory_path() / ("rill-vulkan-cache-test-" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    env_.emplace("RILL_CACHE_DIR", dir_.string());
    no_profile_.emplace("RILL_PROFILE_DIR", "");  // profiling would bypass the cache
    clear_kernel_cache();
  }
  void TearDown() override {
    clear_kernel_cache();
    env_.reset();
    no_profile_.reset();
    if (!dir_.empty()) fs::remove_all(dir_);
  }

  // Three outputs with a division and a square root, so that strict kernels carry the
  // helpers; a loop, so that it is not trivial for any compiler.
  static Program kernel() {
    return program("vulkan_cache_kernel", [] {
      Input<Float> x("x");
      Output<Float> a("a"), b("b"), c("c");
      Float acc = 0.5f;
      RILL_FOR(Int i = 0, i < 4, i = i + 1) {
        acc = acc * x + 1.25f;
      }
      RILL_ENDFOR;
      a = acc;
      b = 1.0f / (x * x + 3.0f);
      c = sqrt(x * x + 2.0f);
    });
  }
  static std::vector<float> inputs() {
    std::vector<float> xs;
    for (int i = -40; i < 40; ++i) xs.push_back(static_cast<float>(i) * 0.375f);
    return xs;
  }

  // Compiles as a new process would and returns where the kernel came from and its outputs.
  KernelOrigin compile_fresh(std::vector<float>& out) {
    clear_kernel_cache();
    Kernel k = compile(kernel());
    auto [a, b, c] =
        run_kernel<Float, Float, Float>(k, static_cast<int64_t>(inputs().size()), inputs());
    out = a;
    out.insert(out.end(), b.begin(), b.end());
    out.insert(out.end(), c.begin(), c.end());
    EXPECT_EQ(k.info().from_disk_cache, k.info().origin == KernelOrigin::DiskCache);
    return k.info().origin;
  }

  // The one vulkan entry, parsed.
  Parsed entry() {
    std::vector<cache::Entry> mine;
    for (cache::Entry& e : cache::list())
      if (e.backend == "vulkan") mine.push_back(e);
    EXPECT_EQ(mine.size(), 1u) << "entries in " << dir_;
    if (mine.empty()) return {};
    std::optional<Parsed> p = parse(mine.front().path);
    EXPECT_TRUE(p.has_value()) << mine.front().path << " is not an entry of the layout known";
    return p ? *p : Parsed{};
  }

  // Compiles once (Built) and returns the outputs and the entry stored.
  std::pair<std::vector<float>, Parsed> built() {
    std::vector<float> out;
    EXPECT_EQ(compile_fresh(out), KernelOrigin::Built);
    return {out, entry()};
  }

  fs::path dir_;
  std::optional<ScopedEnv> env_, no_profile_;
};

TEST_P(VulkanDiskCacheTest, EntryHoldsSpirvAndDriverDataAndANewProcessLoadsIt) {
  auto [first, stored] = built();
  ASSERT_FALSE(stored.spirv.empty());
  for (const auto& m : stored.spirv) {
    ASSERT_GE(m.size(), 5u) << "a SPIR-V module has a five-word header";
    EXPECT_EQ(m[0], kSpirvMagic);
  }
  // The driver's data is what vkGetPipelineCacheData wrote for this device: its header names
  // the pipelineCacheUUID that the key names.
  VkPipelineCacheHeaderVersionOne h{};
  ASSERT_GE(stored.driver_data.size(), sizeof h) << "no driver data was kept";
  std::memcpy(&h, stored.driver_data.data(), sizeof h);
  EXPECT_EQ(h.headerVersion, VK_PIPELINE_CACHE_HEADER_VERSION_ONE);
  const std::string uuid = vk::hex(h.pipelineCacheUUID, VK_UUID_SIZE);
  EXPECT_NE(stored.key.find("pipeline-cache=" + uuid + "\n"), std::string::npos) << stored.key;

  std::vector<float> again;
  EXPECT_EQ(compile_fresh(again), KernelOrigin::DiskCache);
  EXPECT_TRUE(bits_equal(again, first));
  Kernel in_process = compile(kernel());
  EXPECT_EQ(in_process.info().origin, KernelOrigin::ProcessCache);
}

// Payloads of the wrong shape, stored under the right key (so the cache's own checks pass),
// are rejected by the backend: compiled again from source to the same SPIR-V and bits.
TEST_P(VulkanDiskCacheTest, ForgedPayloadIsRejectedAndRecompiledToTheSameBits) {
  auto [first, good] = built();
  ASSERT_FALSE(good.spirv.empty());
  struct Forgery {
    const char* what;
    std::string payload;
  };
  auto spirv = good.spirv;
  std::vector<Forgery> forgeries;
  auto more_passes = spirv;
  more_passes.push_back(spirv.front());
  forgeries.push_back({"one pass more", pack(more_passes, good.driver_data)});
  auto no_magic = spirv;
  no_magic.front()[0] ^= 0x00ff0000u;
  forgeries.push_back({"a module without the SPIR-V magic number", pack(no_magic, {})});
  std::string truncated = pack(spirv, {});
  truncated.resize(truncated.size() - 8);
  forgeries.push_back({"the last module cut short", truncated});
  auto empty_module = spirv;
  empty_module.back().clear();
  forgeries.push_back({"an empty module", pack(empty_module, good.driver_data)});
  forgeries.push_back({"an empty payload", std::string()});
  for (const Forgery& f : forgeries) {
    SCOPED_TRACE(f.what);
    ASSERT_TRUE(cache::store("vulkan", good.key, f.payload));
    std::vector<float> out;
    EXPECT_EQ(compile_fresh(out), KernelOrigin::Built);
    EXPECT_TRUE(bits_equal(out, first));
    const Parsed rewritten = entry();
    EXPECT_EQ(rewritten.key, good.key);
    EXPECT_EQ(rewritten.spirv, good.spirv) << "glslang compiles the same source to the same SPIR-V";
    EXPECT_EQ(compile_fresh(out), KernelOrigin::DiskCache);
    EXPECT_TRUE(bits_equal(out, first));
  }
}

// Driver data of another device (its UUID changed), or none, is not handed to the driver:
// the pipelines are made from the cached SPIR-V alone, and the entry gets the driver's data.
TEST_P(VulkanDiskCacheTest, DriverDataOfAnotherDeviceIsDropped) {
  auto [first, good] = built();
  ASSERT_GE(good.driver_data.size(), sizeof(VkPipelineCacheHeaderVersionOne));
  std::string foreign = good.driver_data;
  foreign[offsetof(VkPipelineCacheHeaderVersionOne, pipelineCacheUUID)] ^= 0x5a;
  std::string garbage(good.driver_data.size(), '\x7f');
  for (const auto& [what, data] : {std::pair<const char*, std::string>{"another UUID", foreign},
                                   {"no header", garbage},
                                   {"none", std::string()}}) {
    SCOPED_TRACE(what);
    ASSERT_TRUE(cache::store("vulkan", good.key, pack(good.spirv, data)));
    std::vector<float> out;
    EXPECT_EQ(compile_fresh(out), KernelOrigin::DiskCache) << "the SPIR-V is still good";
    EXPECT_TRUE(bits_equal(out, first));
    const Parsed rewritten = entry();
    EXPECT_EQ(rewritten.spirv, good.spirv);
    ASSERT_GE(rewritten.driver_data.size(), sizeof(VkPipelineCacheHeaderVersionOne));
    EXPECT_EQ(0, std::memcmp(rewritten.driver_data.data(), good.driver_data.data(),
                             sizeof(VkPipelineCacheHeaderVersionOne)))
        << "the entry holds the driver's own header again";
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, VulkanDiskCacheTest, ::testing::ValuesIn(vulkan_if_built()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return param_name(info.param);
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(VulkanDiskCacheTest);

}  // namespace
}  // namespace rill::testing
