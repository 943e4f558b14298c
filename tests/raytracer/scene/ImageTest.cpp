// The image files the ray tracer writes and reads back (scene/Image.h): PFM round trips and PFM
// headers that do not match their data (the image fuzzer's findings stay fixed here). How the
// files are written (whole or not at all, checked) is OutputFileTest.cpp's.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/ImageLimits.h"

namespace rt {
namespace {

using testing::TempDir;

std::string runtime_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::runtime_error";
  return {};
}

TEST(ImageTest, PfmRoundTripsBothKindsTopRowFirst) {
  TempDir dir;
  const std::vector<glm::vec3> rgb = {{1, 2, 3},         {4, 5, 6}, {7, 8, 9},
                                      {-1, 0.5f, 1e30f}, {0, 0, 0}, {1, 1, 1}};
  write_pfm(dir.path("c.pfm"), 3, 2, rgb);
  int w = 0, h = 0, c = 0;
  std::vector<float> back = read_pfm(dir.path("c.pfm"), w, h, c);
  EXPECT_EQ(w, 3);
  EXPECT_EQ(h, 2);
  EXPECT_EQ(c, 3);
  ASSERT_EQ(back.size(), 18u);
  EXPECT_EQ(std::memcmp(back.data(), rgb.data(), 18 * sizeof(float)), 0);

  const std::vector<float> grey = {0.25f, 0.5f, 0.75f, 1.0f};
  write_pfm(dir.path("g.pfm"), 1, 4, grey);
  back = read_pfm(dir.path("g.pfm"), w, h, c);
  EXPECT_EQ(w, 1);
  EXPECT_EQ(h, 4);
  EXPECT_EQ(c, 1);
  EXPECT_EQ(back, grey);
}

TEST(ImageTest, PfmHeaderLargerThanItsDataIsAnErrorBeforeAllocating) {
  // 100000 x 100000 x 3 floats would be 120 GB: refused from the header and the file size,
  // not attempted (the fuzzer ran out of memory on this before).
  const std::string huge = "PF\n100000 100000\n-1.0\n" + std::string(24, '\0');
  int w = 0, h = 0, c = 0;
  const std::string e = runtime_error_of([&] { parse_pfm(huge, "big.pfm", w, h, c); });
  EXPECT_NE(e.find("big.pfm: truncated PFM file (100000x100000 needs 120000000000 bytes of "
                   "data, the file has 24)"),
            std::string::npos)
      << e;
  // One float short.
  const std::string short_grey = "Pf\n2 1\n-1\n" + std::string(4, '\0');
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm(short_grey, "s.pfm", w, h, c);
            }).find("s.pfm: truncated PFM file"),
            std::string::npos);
  // A header and nothing after it; a size whose byte count would wrap 64 bits.
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm("Pf\n1 1\n-1", "e.pfm", w, h, c);
            }).find("e.pfm: truncated PFM file (no data after the header)"),
            std::string::npos);
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm("PF\n2147483647 2147483647\n-1\n....", "w.pfm", w, h, c);
            }).find("w.pfm: truncated PFM file"),
            std::string::npos);
  // Exactly enough.
  EXPECT_EQ(parse_pfm("Pf\n2 1\n-1\n" + std::string(8, '\0'), "ok.pfm", w, h, c).size(), 2u);
}

// A PFM whose data is all there is still held to the image limits (ImageLimits.h), checked
// from its header: the message names the file, the size and the limits.
TEST(ImageTest, PfmOverTheImageLimitsIsAnError) {
  int w = 0, h = 0, c = 0;
  const std::string wide = "Pf\n16385 1\n-1\n" + std::string(16385 * 4, '\0');
  EXPECT_EQ(runtime_error_of([&] { parse_pfm(wide, "wide.pfm", w, h, c); }),
            "wide.pfm: its header declares a 16385x1 PFM image, over the limits (1..16384 per "
            "side, at most 33554432 pixels)");
  EXPECT_EQ(parse_pfm("Pf\n16384 1\n-1\n" + std::string(16384 * 4, '\0'), "ok.pfm", w, h, c).size(),
            16384u);
}

// The limits themselves (docs/robustness.md): 16384 a side and 2^25 pixels, both included.
TEST(ImageLimits, SidesAndPixelsAreBoundedBothIncluded) {
  EXPECT_TRUE(image_size_fits(1, 1));
  EXPECT_TRUE(image_size_fits(16384, 2048));  // 2^25 pixels
  EXPECT_FALSE(image_size_fits(16384, 2049));
  EXPECT_FALSE(image_size_fits(16385, 1));
  EXPECT_FALSE(image_size_fits(1, 16385));
  EXPECT_FALSE(image_size_fits(0, 1));
  EXPECT_FALSE(image_size_fits(1, -1));
  EXPECT_FALSE(image_size_fits(INT64_MAX, INT64_MAX));
  EXPECT_EQ(image_size_limits(), "1..16384 per side, at most 33554432 pixels");
}

TEST(ImageTest, NotAPfmNamesTheFile) {
  int w = 0, h = 0, c = 0;
  for (const std::string& bad : {std::string(""), std::string("P6\n1 1\n255\n..."),
                                 std::string("PF\n0 1\n-1\n"), std::string("PF\n1 1\n1.0\n    "),
                                 std::string("PF\n-3 1\n-1\n"), std::string("PF\n1 1\nnan\n    ")})
    EXPECT_EQ(runtime_error_of([&] { parse_pfm(bad, "x.pfm", w, h, c); }),
              "x.pfm: not a little-endian PFM file")
        << bad;
}

}  // namespace
}  // namespace rt
