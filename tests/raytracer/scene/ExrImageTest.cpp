// OpenEXR files (scene/ExrImage.h): FLOAT and UINT channels round trip bit for bit, rows top
// to bottom; a failed write throws SceneError naming the file and leaves nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "rill/rt/scene/ExrImage.h"

// A namespace of its own: the unity build joins this file's anonymous namespace with others'.
namespace rt::exr_image_test {
namespace {

using rt::testing::error_of;
using rt::testing::TempDir;

uint32_t bits_of(float f) {
  uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

std::vector<uint32_t> bits_of(const std::vector<float>& v) {
  std::vector<uint32_t> b(v.size());
  for (size_t i = 0; i < v.size(); ++i) b[i] = bits_of(v[i]);
  return b;
}

TEST(ExrImage, FloatAndUintChannelsRoundTripBitForBitTopRowFirst) {
  TempDir dir;
  constexpr int w = 3, h = 2;
  const float inf = std::numeric_limits<float>::infinity();
  const float denormal = std::numeric_limits<float>::denorm_min() * 3;
  // Row 0 (the top) first; values a half float would change.
  const std::vector<float> red = {1.0f, -0.0f, inf, -inf, denormal, 0.1f};
  const std::vector<float> green = {1e30f, -1e-30f, 3.14159274f, 65504.5f, 0.0f, 1.0f / 3};
  // Interleaved (step 3), as RenderResult::color's vec3s.
  std::vector<float> rgb(w * h * 3);
  for (int i = 0; i < w * h; ++i) {
    rgb[3 * i] = static_cast<float>(i);
    rgb[3 * i + 1] = -static_cast<float>(i) * 0.25f;
    rgb[3 * i + 2] = std::nextafter(1.0f, 2.0f) * static_cast<float>(i);
  }
  const std::vector<uint32_t> ids = {0, 1, 16777217, 67108863, 4294967295u, 7};
  write_exr(
      dir.path("a.exr"), w, h,
      {ExrChannel::of_floats("R", red.data()), ExrChannel::of_floats("G", green.data()),
       ExrChannel::of_floats("N.Y", rgb.data() + 1, 3), ExrChannel::of_uints("prim", ids.data())});
  const ExrImage back = read_exr(dir.path("a.exr"));
  EXPECT_EQ(back.width, w);
  EXPECT_EQ(back.height, h);
  ASSERT_EQ(back.channels.size(), 4u);
  // Sorted by name, as OpenEXR stores them.
  EXPECT_EQ(back.channels[0].name, "G");
  EXPECT_EQ(back.channels[1].name, "N.Y");
  EXPECT_EQ(back.channels[2].name, "R");
  EXPECT_EQ(back.channels[3].name, "prim");
  const ExrImage::Channel* r = back.find("R");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->type, ExrType::Float);
  EXPECT_EQ(bits_of(r->floats), bits_of(red));
  EXPECT_EQ(bits_of(back.find("G")->floats), bits_of(green));
  std::vector<float> ny(w * h);
  for (int i = 0; i < w * h; ++i) ny[i] = rgb[3 * i + 1];
  EXPECT_EQ(bits_of(back.find("N.Y")->floats), bits_of(ny));
  const ExrImage::Channel* p = back.find("prim");
  ASSERT_NE(p, nullptr);
  EXPECT_EQ(p->type, ExrType::Uint);
  EXPECT_EQ(p->uints, ids);
  EXPECT_EQ(back.find("B"), nullptr);
  // The file's bytes do not depend on anything but the pixels.
  write_exr(
      dir.path("b.exr"), w, h,
      {ExrChannel::of_floats("R", red.data()), ExrChannel::of_floats("G", green.data()),
       ExrChannel::of_floats("N.Y", rgb.data() + 1, 3), ExrChannel::of_uints("prim", ids.data())});
  EXPECT_EQ(std::filesystem::file_size(dir.path("a.exr")),
            std::filesystem::file_size(dir.path("b.exr")));
}

// A larger image, so that ZIP compresses several blocks of lines: still exact.
TEST(ExrImage, ManyLinesRoundTrip) {
  TempDir dir;
  constexpr int w = 37, h = 53;
  std::vector<float> v(w * h);
  for (size_t i = 0; i < v.size(); ++i) v[i] = std::sin(static_cast<float>(i)) * 1e3f;
  write_exr(dir.path("big.exr"), w, h, {ExrChannel::of_floats("Z", v.data())});
  const ExrImage back = read_exr(dir.path("big.exr"));
  ASSERT_EQ(back.channels.size(), 1u);
  EXPECT_EQ(bits_of(back.channels[0].floats), bits_of(v));
}

TEST(ExrImage, AFailedWriteNamesTheFileAndLeavesNothing) {
  TempDir dir;
  const std::vector<float> v = {1.0f};
  const std::string missing = dir.path("no/such/x.exr");
  EXPECT_NE(error_of([&] {
              write_exr(missing, 1, 1, {ExrChannel::of_floats("R", v.data())});
            }).find("cannot write " + missing),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              write_exr("/dev/full", 1, 1, {ExrChannel::of_floats("R", v.data())});
            }).find("cannot write /dev/full: No space left on device"),
            std::string::npos);
  const std::string path = dir.path("x.exr");
  EXPECT_NE(error_of([&] {
              write_exr(
                  path, 1, 1,
                  {ExrChannel::of_floats("R", v.data()), ExrChannel::of_floats("R", v.data())});
            }).find("two channels named 'R'"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              write_exr(path, 0, 1, {ExrChannel::of_floats("R", v.data())});
            }).find("cannot write " + path),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              write_exr(path, 1, 1, {ExrChannel::of_floats("R", nullptr)});
            }).find("channel 'R' has no data"),
            std::string::npos);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.dir()), {}), 0)
      << "a file was left";
}

TEST(ExrImage, NotAnExrNamesTheFile) {
  TempDir dir;
  const std::string path = dir.file("x.exr", "not an image at all");
  EXPECT_NE(error_of([&] { read_exr(path); }).find(path + ": not a readable OpenEXR file"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read_exr(dir.path("none.exr")); }).find("none.exr"), std::string::npos);
  // A whole file cut short.
  const std::vector<float> v(64 * 64, 0.5f);
  write_exr(dir.path("whole.exr"), 64, 64, {ExrChannel::of_floats("R", v.data())});
  const auto size = std::filesystem::file_size(dir.path("whole.exr"));
  std::filesystem::resize_file(dir.path("whole.exr"), size / 2);
  EXPECT_NE(error_of([&] { read_exr(dir.path("whole.exr")); }).find("whole.exr"),
            std::string::npos);
}

// The header's size and channel count are held to ImageLimits.h before any pixel is allocated:
// a file one pixel wider than the limit, or with more channels than it, is an error naming the
// file, what the header declares and the limit.
TEST(ExrImage, AHeaderOverTheLimitsIsRefusedBeforeAllocating) {
  TempDir dir;
  const std::vector<float> row(16385, 0.25f);
  const std::string wide = dir.path("wide.exr");
  write_exr(wide, 16385, 1, {ExrChannel::of_floats("Y", row.data())});
  EXPECT_EQ(error_of([&] { read_exr(wide); }),
            wide +
                ": its header declares a 16385x1 EXR image, over the limits (1..16384 per "
                "side, at most 33554432 pixels)");
  std::vector<ExrChannel> many;
  for (int c = 0; c < 65; ++c)
    many.push_back(ExrChannel::of_floats("c" + std::to_string(c), row.data()));
  const std::string deep = dir.path("deep.exr");
  write_exr(deep, 1, 1, many);
  EXPECT_EQ(error_of([&] { read_exr(deep); }),
            deep + ": its header declares 65 channels, over the limit of 64 for EXR images");
  // At the limits: read.
  many.pop_back();
  write_exr(deep, 16384, 1, many);
  EXPECT_EQ(read_exr(deep).channels.size(), 64u);
}

}  // namespace
}  // namespace rt::exr_image_test
