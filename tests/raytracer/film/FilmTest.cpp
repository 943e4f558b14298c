// The film (raytracer/rill/rt/film/), per backend: the device's 8-bit sRGB encoding gives
// the host's bytes for every kind of float, samples add up on the device without losing
// small ones, and a render reads back only the outputs asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/film/Film.h"
#include "rill/rt/film/Srgb8.h"
#include "rill/rt/scene/Image.h"

namespace rt {
namespace {

using namespace rill;

class FilmTest : public ::testing::TestWithParam<std::string> {};

// The values where encodings change (each threshold and its neighbours), the ends of the
// range and the special values, and random values over [0, 1.25).
std::vector<float> hard_linear_values() {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> v{0.0f,          -0.0f,  -1.0f,  1.0f,       1.5f, inf,  -inf,
                       std::nanf(""), 1e-45f, 1e-40f, 0.0031308f, 0.5f, 2e38f};
  for (float t : srgb8_thresholds())
    v.insert(v.end(), {std::nextafter(t, 0.0f), t, std::nextafter(t, 2.0f)});
  // The first and last float of every bucket of the encoder's table.
  for (size_t b = 1; b < srgb8_tables().buckets.size(); ++b) {
    const uint32_t first = static_cast<uint32_t>(b + kSrgb8FirstBucket) << kSrgb8BucketShift;
    v.insert(v.end(), {std::bit_cast<float>(first), std::bit_cast<float>(first - 1)});
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.25f);
  for (int i = 0; i < 20000; ++i) v.push_back(u(rng));
  return v;
}

TEST(Srgb8Thresholds, AreWhereTheHostEncodingSteps) {
  const auto& t = srgb8_thresholds();
  for (int level = 1; level <= 255; ++level) {
    const float at = t[static_cast<size_t>(level - 1)];
    EXPECT_EQ(to_srgb8(at), level) << "threshold " << level;
    EXPECT_EQ(to_srgb8(std::nextafter(at, 0.0f)), level - 1) << "below threshold " << level;
  }
}

// The encoder's rule (Srgb8.h) on the host, over every 61st float of [0, 1]: a bucket's
// count and two comparisons give the host's level, both from the thresholds and from the
// two the bucket's entry holds.
TEST(Srgb8Tables, TheBucketsCountTheThresholdsBelowEveryValue) {
  const Srgb8Tables& t = srgb8_tables();
  ASSERT_EQ(t.thresholds.size(), 257u);
  size_t differ = 0;
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 61) {
    const float c = std::bit_cast<float>(bits);
    const int bucket = std::max(static_cast<int>(bits >> kSrgb8BucketShift) - kSrgb8FirstBucket, 0);
    const glm::ivec3 entry = t.buckets[static_cast<size_t>(bucket)];
    const auto below = static_cast<size_t>(entry.x);
    const int level = entry.x + (t.thresholds[below] <= c) + (t.thresholds[below + 1] <= c);
    const int device_level =
        entry.x + (std::bit_cast<float>(entry.y) <= c) + (std::bit_cast<float>(entry.z) <= c);
    if ((level != to_srgb8(c) || device_level != level) && differ++ < 5)
      ADD_FAILURE() << c << ": " << level << " from the buckets, " << device_level
                    << " from the device's table, " << int{to_srgb8(c)};
  }
  EXPECT_EQ(differ, 0u);
}

TEST_P(FilmTest, DeviceSrgb8EqualsTheHostsForEveryKindOfFloat) {
  RT_REQUIRE_BACKEND(GetParam());
  const std::vector<float> all = hard_linear_values();
  const Srgb8Encoder srgb8;
  Program p = program("srgb8_test", [&] {
    Input<Float> linear("linear");
    Output<Int> level("level");
    level = srgb8.encode(linear);
  });
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast}) {
    CompileOptions opt;
    opt.accuracy = a;
    Kernel k = compile(p, GetParam(), opt);
    // fast may assume that no value is NaN or infinite (-ffinite-math-only): finite ones only.
    std::vector<float> values = all;
    if (a == Accuracy::Fast) std::erase_if(values, [](float x) { return !std::isfinite(x); });
    Stream<Float> in(values);
    Stream<Int> out(static_cast<int64_t>(values.size()));
    k.inputs(in).outputs(out);
    k.execute();
    const std::vector<int32_t> got = out.download();
    size_t differ = 0;
    for (size_t i = 0; i < values.size(); ++i)
      if (got[i] != to_srgb8(values[i]) && differ++ < 5)
        ADD_FAILURE() << accuracy_name(a) << ": " << values[i] << " encodes to " << got[i]
                      << " on the device, " << int{to_srgb8(values[i])} << " on the host";
    EXPECT_EQ(differ, 0u) << accuracy_name(a);
  }
}

// One large sample and small ones: a plain float sum drops the small ones (1 + 3e-8 == 1),
// the film's compensated sum keeps them, and its mean is the exact mean rounded once.
TEST_P(FilmTest, SamplesAddUpWithoutLosingSmallOnes) {
  RT_REQUIRE_BACKEND(GetParam());
  rt::Film film;
  const int spp = 4;
  film.begin(GetParam(), Accuracy::Strict, 2, 1, spp);
  Stream<Float3> sample(2, 1, "sample");
  for (int s = 0; s < spp; ++s) {
    const float x = s == 0 ? 1.0f : 3e-8f;
    sample.upload(std::vector<glm::vec3>{glm::vec3(x, 0.5f, 0.0f), glm::vec3(x * 2.0f)});
    film.add_sample(sample, s);
  }
  RenderResult r;
  FrameOutputs want;
  want.depth = want.prim = want.normal = false;
  film.finish(want, r);
  ASSERT_EQ(r.color.size(), 2u);
  EXPECT_TRUE(r.depth.empty() && r.prim.empty() && r.normal.empty() && r.rgb8.empty());
  auto exact_mean = [&](double first, double rest) {
    return static_cast<float>((first + (spp - 1) * rest) / spp);
  };
  EXPECT_EQ(r.color[0].x, exact_mean(1.0, 3e-8f));
  EXPECT_NE(r.color[0].x, 0.25f);  // what a plain float sum gives
  EXPECT_EQ(r.color[0].y, 0.5f);
  EXPECT_EQ(r.color[0].z, 0.0f);
  EXPECT_EQ(r.color[1].x, exact_mean(2.0, 6e-8f));
}

// The 8-bit image's bytes, 4 pixels to an element, straight from colour streams whose
// pixels all differ: widths 1 to 5 (a group of 4 spans up to four rows), pixel counts 0 to 3
// over a multiple of 4, two different streams of one size in a row (the encoder follows the
// stream it is given), and one sample then the mean of two at the same size.
TEST_P(FilmTest, TheEightBitImageIsEveryPixelsBytesInOrder) {
  RT_REQUIRE_BACKEND(GetParam());
  rt::Film film;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> U(0.0f, 1.0f);
  RenderResult r;
  FrameOutputs want;
  want.color = want.depth = want.prim = want.normal = false;
  want.rgb8 = true;
  for (int w = 1; w <= 5; ++w)
    for (int h : {1, 2, 3, 7}) {
      for (int spp : {1, 1, 2}) {
        const std::string what = std::to_string(w) + "x" + std::to_string(h) + ", spp " +
                                 std::to_string(spp) + " on " + GetParam();
        film.begin(GetParam(), Accuracy::Strict, w, h, spp);
        std::vector<glm::vec3> mean(static_cast<size_t>(w * h), glm::vec3(0.0f));
        for (int s = 0; s < spp; ++s) {
          std::vector<glm::vec3> px(static_cast<size_t>(w * h));
          for (glm::vec3& c : px) c = glm::vec3(U(rng), U(rng), U(rng));
          Stream<Float3> sample(w, h, "sample");  // a new stream each time
          sample.upload(px);
          film.add_sample(sample, s);
          for (size_t p = 0; p < px.size(); ++p) mean[p] += px[p];
        }
        film.finish(want, r);
        ASSERT_EQ(r.rgb8.size(), static_cast<size_t>(w * h * 3)) << what;
        for (size_t p = 0; p < mean.size(); ++p)
          for (int c = 0; c < 3; ++c) {
            // Two samples: the film's compensated mean of two floats is their rounded mean.
            const float m = spp == 1 ? mean[p][c] : mean[p][c] / 2.0f;
            ASSERT_EQ(r.rgb8[p * 3 + static_cast<size_t>(c)], to_srgb8(m))
                << "pixel " << p << " channel " << c << ", " << what;
          }
      }
    }
}

// A render reads back what FrameOutputs asks for and nothing else; its 8-bit image is the
// host's encoding of its colour.
TEST_P(FilmTest, RendersReadBackOnlyWhatIsAskedFor) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("thesis-b");
  Grid g = build_grid(s, 8);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  // The 8-bit image comes back 4 pixels to an element: sizes with 0 to 3 pixels over a
  // multiple of 4, rows of 1 to 3 pixels (a group spans several rows), one sample (the
  // strategy's colour) and two (the film's mean), both strategies, and one result reused
  // across sizes.
  RenderResult png;
  for (glm::ivec3 size_spp : {glm::ivec3(20, 14, 2), glm::ivec3(7, 5, 1), glm::ivec3(9, 3, 2),
                              glm::ivec3(2, 5, 1), glm::ivec3(1, 7, 2), glm::ivec3(3, 1, 1)})
    for (Strategy strategy : {Strategy::Megakernel, Strategy::Multipass}) {
      rs.width = size_spp.x;
      rs.height = size_spp.y;
      rs.spp = size_spp.z;
      rs.strategy = strategy;
      rs.outputs = FrameOutputs{true, false, true, true, true};  // colour and the AOVs
      const RenderResult all = t.render(rs, s.camera);
      rs.outputs = FrameOutputs{false, true, false, false, false};
      t.render(rs, s.camera, png);
      EXPECT_TRUE(png.color.empty() && png.depth.empty() && png.prim.empty() && png.normal.empty());
      ASSERT_EQ(png.rgb8.size(), all.color.size() * 3);
      for (size_t p = 0; p < all.color.size(); ++p)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(png.rgb8[p * 3 + static_cast<size_t>(c)], to_srgb8(all.color[p][c]))
              << "pixel " << p << " of " << rs.width << "x" << rs.height;
      EXPECT_EQ(png.rays, all.rays);
      rs.outputs = FrameOutputs{false, false, false, true, false};
      const RenderResult prim = t.render(rs, s.camera);
      EXPECT_EQ(prim.prim, all.prim);
      EXPECT_TRUE(prim.color.empty() && prim.rgb8.empty() && prim.depth.empty());
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, FilmTest, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
