// Path regeneration in the path megakernel (megakernel/Megakernel.h), per backend: however
// many samples a launch takes (RenderSettings::path_samples_per_launch), each pixel's image,
// AOVs and ray count are bitwise those of one sample per launch, where the film adds the
// samples; and the launches are as many as the setting says (so regeneration did run). The
// scenes put paths of very different lengths side by side in one lockstep group or warp:
// camera rays that miss next to paths that bounce in the Cornell box until Russian roulette
// ends them, and a thin lens (whose camera rays the kernel makes per sample). A resumed render
// and one stopped by after_pass count their samples as before.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/megakernel/Megakernel.h"

namespace rt {
namespace {

class PathRegeneration : public ::testing::TestWithParam<std::string> {};

RenderSettings settings(const std::string& backend, int width, int height, int spp,
                        int per_launch) {
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = rs.outputs.albedo = true;
  rs.backend = backend;
  rs.width = width;
  rs.height = height;
  rs.spp = spp;
  rs.path_samples_per_launch = per_launch;
  return rs;
}

// The same image, AOVs (sample 0's camera ray's) and samples, byte for byte; and the
// same rays where both traced all their samples.
void expect_same(const RenderResult& a, const RenderResult& b, const std::string& what,
                 bool rays = true) {
  ASSERT_FALSE(a.color.empty()) << what;
  ASSERT_FALSE(a.depth.empty()) << what;
  EXPECT_TRUE(testing::same_bytes(a.color, b.color)) << what << ": colour";
  EXPECT_TRUE(testing::same_bytes(a.depth, b.depth)) << what << ": depth";
  EXPECT_TRUE(testing::same_bytes(a.prim, b.prim)) << what << ": prim";
  EXPECT_TRUE(testing::same_bytes(a.normal, b.normal)) << what << ": normal";
  EXPECT_TRUE(testing::same_bytes(a.albedo, b.albedo)) << what << ": albedo";
  EXPECT_EQ(a.spp, b.spp) << what;
  if (rays) {
    EXPECT_EQ(a.rays, b.rays) << what;
  }
}

// The scene rendered with 1, 2, 3 and 7 samples per launch: the same bits, in
// ceil(spp / n) launches.
void expect_any_samples_per_launch(const Scene& s, const std::string& backend, int w, int h,
                                   const std::string& what) {
  Tracer t(s, build_grid_for(s));
  const int spp = 5;
  const RenderResult one = t.render(settings(backend, w, h, spp, 1), s.camera);
  EXPECT_EQ(one.launches, spp) << what;
  EXPECT_GT(one.rays, int64_t{w} * h * spp) << what << ": the paths bounce";
  for (const int n : {2, 3, 7}) {
    const std::string with = what + ", " + std::to_string(n) + " samples per launch";
    const RenderResult many = t.render(settings(backend, w, h, spp, n), s.camera);
    EXPECT_EQ(many.launches, (spp + n - 1) / n) << with;
    expect_same(one, many, with);
  }
}

TEST_P(PathRegeneration, CornellPathIsTheSameImageWhateverTheSamplesPerLaunch) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("cornell-path");
  ASSERT_EQ(s.options.integrator, Integrator::Path);
  // The view moved right by half the box's width: its left half looks into the box, its right
  // half past it (camera rays that miss, beside paths that bounce).
  s.camera.eye.x += 0.278f;  // (the box is 0.556 wide)
  s.camera.look_at.x += 0.278f;
  expect_any_samples_per_launch(s, GetParam(), 24, 16, "cornell-path");
}

TEST_P(PathRegeneration, ThinLensIsTheSameImageWhateverTheSamplesPerLaunch) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("cornell-path");
  s.camera.aperture = 0.2f;  // each sample's lens point comes from its sample index
  expect_any_samples_per_launch(s, GetParam(), 16, 16, "cornell-path, thin lens");
}

// A render resumed from an earlier one's sums adds its samples in its launches onto them,
// and one that after_pass stops ends after the launch it was called for.
TEST_P(PathRegeneration, ResumedAndStoppedRendersCountTheirSamples) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = builtin_scene("cornell-path");
  Tracer t(s, build_grid_for(s));
  const RenderResult whole = t.render(settings(GetParam(), 16, 12, 6, 1), s.camera);

  RenderSettings first = settings(GetParam(), 16, 12, 2, 4);
  first.outputs.accumulation = true;
  const RenderResult two = t.render(first, s.camera);
  ASSERT_EQ(two.accumulation.samples, 2);
  RenderSettings rest = settings(GetParam(), 16, 12, 6, 3);
  rest.resume = &two.accumulation;
  const RenderResult resumed = t.render(rest, s.camera);
  EXPECT_EQ(resumed.launches, 3);  // sample 0's camera rays (the AOVs), samples 2-4, then 5
  expect_same(whole, resumed, "resumed after 2 samples", false);  // (rays: its 4 samples')
  EXPECT_EQ(two.rays + resumed.rays, whole.rays);

  RenderSettings stopped = settings(GetParam(), 16, 12, 6, 2);
  std::vector<int> calls;
  stopped.after_pass = [&calls](int done) {
    calls.push_back(done);
    return done < 4;
  };
  const RenderResult four = t.render(stopped, s.camera);
  EXPECT_EQ(calls, (std::vector<int>{2, 4}));
  EXPECT_EQ(four.spp, 4);
  expect_same(t.render(settings(GetParam(), 16, 12, 4, 1), s.camera), four, "stopped after 4");
}

// With path_samples_per_launch 0 and RILL_PATH_REGENERATE unset a backend takes its own
// default: one sample per launch on simd, 16 elsewhere
// (docs/benchmarks/2026-12-08-simd-path-default.md); the variable overrides it either way; and
// the default's image is bitwise the other choice's, in the launches each choice says.
TEST_P(PathRegeneration, TheDefaultIsTheBackendsAndChangesNoBit) {
  RT_REQUIRE_BACKEND(GetParam());
  const std::string& b = GetParam();
  const bool regenerates = b != "simd";
  EXPECT_EQ(path_regeneration_default(b), regenerates) << b;
  EXPECT_EQ(path_samples_per_launch(0, b, nullptr), regenerates ? kPathSamplesPerLaunch : 1) << b;
  EXPECT_EQ(path_samples_per_launch(0, b, "on"), kPathSamplesPerLaunch) << b;
  EXPECT_EQ(path_samples_per_launch(0, b, "off"), 1) << b;
  EXPECT_EQ(path_samples_per_launch(3, b, "off"), 3) << b << ": a setting beats the variable";
  EXPECT_THROW(path_samples_per_launch(0, b, "maybe"), std::invalid_argument) << b;
  if (std::getenv("RILL_PATH_REGENERATE") != nullptr)
    GTEST_SKIP() << "RILL_PATH_REGENERATE is set: a render's default is the variable's";
  const Scene s = builtin_scene("cornell-path");
  Tracer t(s, build_grid_for(s));
  const int spp = 5;
  const RenderResult by_default = t.render(settings(b, 16, 12, spp, 0), s.camera);
  EXPECT_EQ(by_default.launches, regenerates ? 1 : spp) << b;
  const int other_choice = regenerates ? 1 : kPathSamplesPerLaunch;
  const RenderResult other = t.render(settings(b, 16, 12, spp, other_choice), s.camera);
  EXPECT_EQ(other.launches, regenerates ? spp : 1) << b;
  expect_same(by_default, other, b + ": the default against the other choice");
}

INSTANTIATE_TEST_SUITE_P(Backends, PathRegeneration, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
