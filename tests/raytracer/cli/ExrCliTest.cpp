// rill-trace render --exr: the linear colour and the AOVs in one OpenEXR file, the same bits
// as the PFM outputs; a file that cannot be written is a one-line error naming it.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/scene/ExrImage.h"
#include "rill/rt/scene/Image.h"

// A namespace of its own: the unity build joins this file's anonymous namespace with others'.
namespace rt::exr_cli_test {
namespace {

#ifdef RILL_TRACE_EXE

using rt::testing::run_command;
using rt::testing::TempDir;

rt::testing::Run run(const std::string& args, const TempDir& dir) {
  return run_command("'" RILL_TRACE_EXE "' " + args, dir);
}

std::vector<uint32_t> bits_of(const float* f, size_t n) {
  std::vector<uint32_t> b(n);
  if (n > 0) std::memcpy(b.data(), f, n * sizeof(float));  // a UINT channel has no floats (null)
  return b;
}

// Component c of every pixel of an image of `channels` floats per pixel.
std::vector<float> component(const std::vector<float>& v, int channels, int c) {
  std::vector<float> out;
  for (size_t i = static_cast<size_t>(c); i < v.size(); i += static_cast<size_t>(channels))
    out.push_back(v[i]);
  return out;
}

TEST(CliExr, ChannelsEqualThePfmOutputsBitForBit) {
  TempDir dir;
  const auto r =
      run("render builtin:thesis-a --size 32x24 --spp 2 --exr o.exr --pfm o.pfm --depth d.pfm "
          "--prim p.pfm --normal n.pfm",
          dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("wrote o.exr"), std::string::npos) << r.out;
  const ExrImage exr = read_exr(dir.path("o.exr"));
  ASSERT_EQ(exr.width, 32);
  ASSERT_EQ(exr.height, 24);
  const size_t n = 32 * 24;
  int w = 0, h = 0, c = 0;
  const std::vector<float> color = read_pfm(dir.path("o.pfm"), w, h, c);
  ASSERT_EQ(c, 3);
  const std::vector<float> normal = read_pfm(dir.path("n.pfm"), w, h, c);
  ASSERT_EQ(c, 3);
  const std::vector<float> depth = read_pfm(dir.path("d.pfm"), w, h, c);
  const std::vector<float> prim = read_pfm(dir.path("p.pfm"), w, h, c);
  struct Expect {
    const char* name;
    std::vector<float> want;
  };
  const Expect floats[] = {{"R", component(color, 3, 0)},    {"G", component(color, 3, 1)},
                           {"B", component(color, 3, 2)},    {"Z", depth},
                           {"N.X", component(normal, 3, 0)}, {"N.Y", component(normal, 3, 1)},
                           {"N.Z", component(normal, 3, 2)}};
  for (const Expect& e : floats) {
    SCOPED_TRACE(e.name);
    const ExrImage::Channel* ch = exr.find(e.name);
    ASSERT_NE(ch, nullptr);
    EXPECT_EQ(ch->type, ExrType::Float);
    ASSERT_EQ(ch->floats.size(), n);
    EXPECT_EQ(bits_of(ch->floats.data(), n), bits_of(e.want.data(), n));
  }
  // The scene has misses (+inf depth) and hits, and colour above 0.
  bool miss = false, hit = false;
  for (float d : depth) (d == std::numeric_limits<float>::infinity() ? miss : hit) = true;
  EXPECT_TRUE(miss && hit);
  const ExrImage::Channel* p = exr.find("prim");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->type, ExrType::Uint);
  ASSERT_EQ(p->uints.size(), n);
  for (size_t i = 0; i < n; ++i)
    ASSERT_EQ(p->uints[i], prim[i] < 0 ? 4294967295u : static_cast<uint32_t>(prim[i])) << i;
  EXPECT_EQ(exr.channels.size(), 8u);

  // --exr alone: the same file, and no default PNG beside it.
  TempDir alone;
  const auto a = run("render builtin:thesis-a --size 32x24 --spp 2 --exr a.exr", alone);
  ASSERT_EQ(a.status, 0) << a.err;
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(alone.dir()), {}), 3)
      << "a.exr, stdout.txt and stderr.txt only";
  const ExrImage b = read_exr(alone.path("a.exr"));
  ASSERT_EQ(b.channels.size(), exr.channels.size());
  for (size_t i = 0; i < b.channels.size(); ++i) {
    EXPECT_EQ(b.channels[i].name, exr.channels[i].name);
    EXPECT_EQ(bits_of(b.channels[i].floats.data(), b.channels[i].floats.size()),
              bits_of(exr.channels[i].floats.data(), exr.channels[i].floats.size()));
    EXPECT_EQ(b.channels[i].uints, exr.channels[i].uints);
  }
}

void expect_failure(const std::string& args, const std::string& needle) {
  TempDir dir;
  const auto r = run(args, dir);
  SCOPED_TRACE(args);
  EXPECT_TRUE(r.status == 1 || r.status == 2) << "status " << r.status << ": " << r.err;
  EXPECT_EQ(r.err.rfind("rill-trace: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  // Nothing left behind (no partial file): only the test's own stdout and stderr.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.dir()), {}), 2);
}

TEST(CliExr, UnwritableOrCollidingNamesAreErrors) {
  expect_failure("render builtin:thesis-a --size 8x6 --exr no/such/dir/x.exr",
                 "cannot write no/such/dir/x.exr");
  expect_failure("render builtin:thesis-a --size 8x6 --exr /dev/full",
                 "cannot write /dev/full: No space left on device");
  expect_failure("render builtin:thesis-a --size 8x6 --out o.exr --exr ./o.exr",
                 "--out o.exr: .exr names OpenEXR, but --out writes PNG");
  expect_failure("render builtin:thesis-a --size 8x6 --out /dev/null --exr o.exr --source ./o.exr",
                 "--source ./o.exr: .exr names OpenEXR, but --source writes the kernel source");
  expect_failure("render builtin:thesis-a --size 8x6 --exr ''", "--exr: an empty file name");
}

#else
TEST(CliExr, ChannelsEqualThePfmOutputsBitForBit) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(CliExr, UnwritableOrCollidingNamesAreErrors) {
  GTEST_SKIP() << "rill-trace is not built";
}
#endif

}  // namespace
}  // namespace rt::exr_cli_test
