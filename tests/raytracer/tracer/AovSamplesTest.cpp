// The AOVs of a render of several samples per pixel are sample 0's, the pixel centre's
// (Film::read_aovs), per backend and for every strategy: the megakernel's two Whitted loops,
// the multipass sequence, the path megakernel with one sample per launch and with several
// (path regeneration), and the wavefront. A render of 4 samples has the AOVs of a render of
// one, bit for bit; so does a render resumed from an earlier one's sums (which traces sample
// 0's camera rays once more for them, and only when an AOV is asked for), one resumed with no
// sample left to trace, and a window of the image resumed from its own sums (a distributed
// render's tile in its later rounds). Each resumed render's image is the uninterrupted one's.
// Both scenes at this size have pixels whose samples see other primitives than sample 0
// (before the AOVs were sample 0's, every strategy gave the last sample's, which differ).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

class AovSamples : public ::testing::TestWithParam<std::string> {};

// One way of rendering a scene: a strategy and its knobs.
struct Way {
  std::string what;
  Strategy strategy = Strategy::Megakernel;
  MegakernelLoop loop = MegakernelLoop::Auto;
  int per_launch = 0;  // the path megakernel's samples per launch
};

// Whitted's (thesis-c: mirrors, shadows, no glass, so every strategy runs it) and the path
// integrator's (the Cornell box, moved so that half the camera rays miss).
const std::vector<Way>& whitted_ways() {
  static const std::vector<Way> ways{
      {"megakernel, ray loop", Strategy::Megakernel, MegakernelLoop::Ray},
      {"megakernel, segment loop", Strategy::Megakernel, MegakernelLoop::Segment},
      {"multipass", Strategy::Multipass}};
  return ways;
}
const std::vector<Way>& path_ways() {
  static const std::vector<Way> ways{
      {"path megakernel, 1 sample per launch", Strategy::Megakernel, MegakernelLoop::Auto, 1},
      {"path megakernel, 3 samples per launch", Strategy::Megakernel, MegakernelLoop::Auto, 3},
      {"path megakernel, 16 samples per launch", Strategy::Megakernel, MegakernelLoop::Auto, 16},
      {"wavefront", Strategy::Wavefront}};
  return ways;
}

Scene whitted_scene() {
  return builtin_scene("thesis-c");
}
Scene path_scene() {
  Scene s = builtin_scene("cornell-path");
  s.camera.eye.x += 0.278f;  // half the box's width: the right half of the image looks past it
  s.camera.look_at.x += 0.278f;
  return s;
}

RenderSettings settings(const std::string& backend, const Way& way, int spp) {
  RenderSettings rs;
  rs.backend = backend;
  rs.strategy = way.strategy;
  rs.loop = way.loop;
  rs.path_samples_per_launch = way.per_launch;
  rs.width = 20;
  rs.height = 14;
  rs.max_depth = 3;
  rs.spp = spp;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = rs.outputs.albedo = true;
  return rs;
}

// The AOVs of `got` are those of `want`, byte for byte (albedo: the path integrator's).
void expect_same_aovs(const RenderResult& want, const RenderResult& got, bool path,
                      const std::string& what) {
  const size_t n = static_cast<size_t>(want.width) * static_cast<size_t>(want.height);
  ASSERT_EQ(want.depth.size(), n) << what;
  EXPECT_EQ(want.albedo.size(), path ? n : 0u) << what;
  EXPECT_TRUE(testing::same_bytes(want.depth, got.depth)) << what << ": depth";
  EXPECT_TRUE(testing::same_bytes(want.prim, got.prim)) << what << ": prim";
  EXPECT_TRUE(testing::same_bytes(want.normal, got.normal)) << what << ": normal";
  EXPECT_TRUE(testing::same_bytes(want.albedo, got.albedo)) << what << ": albedo";
}

// 4 samples per pixel: the AOVs of the render of sample 0 alone.
void expect_sample_zeros_aovs(const Scene& s, const std::vector<Way>& ways, bool path,
                              const std::string& backend) {
  Tracer t(s, build_grid_for(s));
  for (const Way& way : ways) {
    const std::string what = s.name + ", " + way.what;
    const RenderResult one = t.render(settings(backend, way, 1), s.camera);
    const RenderResult four = t.render(settings(backend, way, 4), s.camera);
    ASSERT_EQ(four.spp, 4) << what;
    EXPECT_FALSE(testing::same_bytes(one.color, four.color)) << what << ": the samples differ";
    expect_same_aovs(one, four, path, what + ", 4 samples");
  }
}

TEST_P(AovSamples, SeveralSamplesHaveSampleZerosAovsInEveryStrategy) {
  RT_REQUIRE_BACKEND(GetParam());
  expect_sample_zeros_aovs(whitted_scene(), whitted_ways(), false, GetParam());
  expect_sample_zeros_aovs(path_scene(), path_ways(), true, GetParam());
}

// A render of `to` samples (in `window`, if not empty) resumed from one of `from`.
RenderResult resumed(Tracer& t, const Camera& camera, RenderSettings rs, int from, int to,
                     const RenderSettings::Window& window = {}) {
  rs.window = window;
  RenderSettings first = rs;
  first.spp = from;
  first.outputs.accumulation = true;
  const RenderResult earlier = t.render(first, camera);
  rs.spp = to;
  rs.resume = &earlier.accumulation;
  return t.render(rs, camera);
}

// Resumed renders: after 2 samples to 5 (whole image and a window), and from 5 to 5.
void expect_resumed_aovs(const Scene& s, const std::vector<Way>& ways, bool path,
                         const std::string& backend) {
  Tracer t(s, build_grid_for(s));
  for (const Way& way : ways) {
    const std::string what = s.name + ", " + way.what;
    const RenderSettings rs = settings(backend, way, 5);
    const RenderResult one = t.render(settings(backend, way, 1), s.camera);
    const RenderResult whole = t.render(rs, s.camera);
    const RenderResult after_two = resumed(t, s.camera, rs, 2, 5);
    EXPECT_TRUE(testing::same_bytes(whole.color, after_two.color)) << what << ": resumed colour";
    expect_same_aovs(one, after_two, path, what + ", resumed after 2 samples");

    // Without an AOV asked for, sample 0 is not traced again: one launch (Whitted
    // megakernel, path megakernel) or one pass of each of the first bounce's kernels fewer.
    RenderSettings plain = rs;
    plain.outputs.depth = plain.outputs.prim = plain.outputs.normal = false;
    plain.outputs.albedo = false;
    const RenderResult no_aovs = resumed(t, s.camera, plain, 2, 5);
    EXPECT_TRUE(testing::same_bytes(whole.color, no_aovs.color))
        << what << ": resumed colour, no AOVs";
    EXPECT_TRUE(no_aovs.depth.empty() && no_aovs.prim.empty() && no_aovs.albedo.empty()) << what;
    if (way.strategy == Strategy::Megakernel)
      EXPECT_EQ(after_two.launches, no_aovs.launches + 1) << what;
    else
      EXPECT_GT(after_two.launches, no_aovs.launches) << what;

    // Resumed from all 5 samples: nothing left to trace but sample 0's camera rays.
    const RenderResult nothing_left = resumed(t, s.camera, rs, 5, 5);
    EXPECT_EQ(nothing_left.spp, 5) << what;
    EXPECT_TRUE(testing::same_bytes(whole.color, nothing_left.color)) << what << ": colour, 5 of 5";
    expect_same_aovs(one, nothing_left, path, what + ", resumed with 5 of 5 samples");

    // A window resumed from its own sums, as a distributed render's tile in a later round.
    const RenderSettings::Window w{3, 2, 11, 9};
    expect_same_aovs(testing::crop(one, w), resumed(t, s.camera, rs, 2, 5, w), path,
                     what + ", a window resumed after 2 samples");
  }
}

TEST_P(AovSamples, AResumedRenderHasSampleZerosAovs) {
  RT_REQUIRE_BACKEND(GetParam());
  expect_resumed_aovs(whitted_scene(), whitted_ways(), false, GetParam());
  expect_resumed_aovs(path_scene(), path_ways(), true, GetParam());
}

INSTANTIATE_TEST_SUITE_P(Backends, AovSamples, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
