// The library's documented defaults, each tested as a default: what RenderSettings,
// FrameOutputs and TracerOptions (render/RenderSettings.h, kernel/Options.h) and the Tracer's
// methods (Tracer.h) say a value left alone means, one test per claim. A render with a
// setting left at its default is compared, bit for bit, with one that spells out what the
// comment says the default stands for, and with one that does not, where that differs.
// On the cpu backend, the default; a small scene with reflection and refraction (so that the
// depth matters) at a size, depth and sample count of its own (so that "the scene's" is seen).
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "RenderCompare.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

using testing::expect_identical;

// builtin:glass (a glass sphere over a mirror-like floor) at 12 x 8 pixels, 2 samples per
// pixel and depth 3: none of them RenderSettings' own values.
class Defaults : public ::testing::Test {
 protected:
  static Scene small_glass() {
    Scene s = builtin_scene("glass");
    s.width = 12;
    s.height = 8;
    s.options.spp = 2;
    s.options.max_depth = 3;
    return s;
  }
  Scene scene_ = small_glass();
  Grid grid_ = build_grid_for(scene_);
  Tracer tracer_{scene_, grid_};

  RenderResult render(const RenderSettings& rs) { return tracer_.render(rs, scene_.camera); }
  // The settings with the scene's size, depth and samples spelt out.
  RenderSettings explicit_settings() const {
    RenderSettings rs;
    rs.width = scene_.width;
    rs.height = scene_.height;
    rs.max_depth = scene_.options.max_depth;
    rs.spp = scene_.options.spp;
    return rs;
  }
};

// RenderSettings::width, height: "0: the scene's" (Tracer.h's example sets them; a program
// that does not gets the scene's image size). It threw "render: image size not set".
TEST_F(Defaults, SizeZeroIsTheScenesSize) {
  RenderSettings rs;
  EXPECT_EQ(rs.width, 0);
  EXPECT_EQ(rs.height, 0);
  const RenderResult r = render(rs);
  EXPECT_EQ(r.width, 12);
  EXPECT_EQ(r.height, 8);
  expect_identical(r, render(explicit_settings()), "the default size against 12x8");
  // One side given: the other is the scene's.
  rs.width = 6;
  const RenderResult half = render(rs);
  EXPECT_EQ(half.width, 6);
  EXPECT_EQ(half.height, 8);
  EXPECT_EQ(half.color.size(), 48u);
}

// Any other size is held to the image limits (ImageLimits.h), with a message saying so.
TEST_F(Defaults, ASizeOutsideTheLimitsIsAnError) {
  for (const auto& [w, h] : {std::pair{-1, 8}, std::pair{16385, 1}, std::pair{8192, 8192}}) {
    RenderSettings rs;
    rs.width = w;
    rs.height = h;
    try {
      render(rs);
      ADD_FAILURE() << w << "x" << h << " rendered";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()),
                "render: image size " + std::to_string(w) + "x" + std::to_string(h) +
                    " is out of range (1..16384 per side, at most 33554432 pixels; 0 for the "
                    "scene's)");
    }
  }
}

// RenderSettings::max_depth: "-1: the scene's".
TEST_F(Defaults, DepthMinusOneIsTheScenesDepth) {
  RenderSettings rs;
  EXPECT_EQ(rs.max_depth, -1);
  const RenderResult r = render(rs);
  expect_identical(r, render(explicit_settings()), "the default depth against 3");
  RenderSettings shallow = explicit_settings();
  shallow.max_depth = 0;  // no reflection or refraction: other colours, fewer rays
  EXPECT_LT(render(shallow).rays, r.rays);
}

// RenderSettings::spp: "0: the scene's".
TEST_F(Defaults, SamplesZeroAreTheScenesSamples) {
  RenderSettings rs;
  EXPECT_EQ(rs.spp, 0);
  const RenderResult r = render(rs);
  EXPECT_EQ(r.spp, 2);
  expect_identical(r, render(explicit_settings()), "the default samples against 2");
}

// RenderSettings::backend: "cpu".
TEST_F(Defaults, TheBackendIsCpu) {
  RenderSettings rs;
  EXPECT_EQ(rs.backend, "cpu");
  EXPECT_EQ(render(rs).backend, "cpu");
}

// RenderSettings::strategy: the megakernel, whose loop (MegakernelLoop::Auto, "Segment on cpu
// and simd") the result names; multipass names none.
TEST_F(Defaults, TheStrategyIsTheMegakernelWithTheAutoLoop) {
  RenderSettings rs;
  EXPECT_EQ(rs.strategy, Strategy::Megakernel);
  EXPECT_EQ(rs.loop, MegakernelLoop::Auto);
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "cpu"), MegakernelLoop::Segment);
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "opencl"), MegakernelLoop::Ray);
  const RenderResult r = render(rs);
  EXPECT_EQ(r.loop, "segment");
  EXPECT_TRUE(r.passes.empty());
}

// RenderSettings::accuracy: strict, the same bits as asking for it.
TEST_F(Defaults, TheAccuracyIsStrict) {
  RenderSettings rs;
  EXPECT_EQ(rs.accuracy, rill::Accuracy::Strict);
  RenderSettings strict;
  strict.accuracy = rill::Accuracy::Strict;
  expect_identical(render(rs), render(strict), "the default accuracy against strict");
}

// The multipass strategy's knobs: "at least this fraction ... (thesis 5.6: 20%)", masked.
TEST_F(Defaults, MultipassWaitsForAFifthAndMasks) {
  RenderSettings rs;
  EXPECT_EQ(rs.wait_threshold, 0.2);
  EXPECT_TRUE(rs.masking);
}

// RenderSettings::window: "Empty (width or height 0): the whole image".
TEST_F(Defaults, AnEmptyWindowIsTheWholeImage) {
  RenderSettings rs;
  EXPECT_TRUE(rs.window.empty());
  const RenderResult whole = render(rs);
  rs.window = {0, 0, 12, 8};
  expect_identical(whole, render(rs), "the default window against the whole image");
  rs.window = {3, 2, 0, 5};  // a zero side is empty too, wherever it is
  EXPECT_EQ(render(rs).color.size(), 96u);
}

// RenderSettings::resume and after_pass: none, so every sample is taken, from the first.
TEST_F(Defaults, NoResumeAndNoPassCallback) {
  RenderSettings rs;
  EXPECT_EQ(rs.resume, nullptr);
  EXPECT_FALSE(rs.after_pass);
  EXPECT_EQ(render(rs).spp, 2);
}

// FrameOutputs: "the colour image alone" comes back, the linear colour; rgb8, the AOVs,
// albedo, variance and the accumulation only when asked for. The colour is the one a render
// asking for the AOVs too gets, bit for bit.
TEST_F(Defaults, TheOutputsAreTheColourImageAlone) {
  const FrameOutputs o;
  EXPECT_TRUE(o.color);
  EXPECT_FALSE(o.rgb8);
  EXPECT_FALSE(o.depth);
  EXPECT_FALSE(o.prim);
  EXPECT_FALSE(o.normal);
  EXPECT_FALSE(o.albedo);
  EXPECT_FALSE(o.variance);
  EXPECT_FALSE(o.accumulation);
  const RenderResult r = render(RenderSettings{});
  const size_t n = 12 * 8;
  EXPECT_EQ(r.color.size(), n);
  EXPECT_TRUE(r.depth.empty());
  EXPECT_TRUE(r.prim.empty());
  EXPECT_TRUE(r.normal.empty());
  EXPECT_TRUE(r.rgb8.empty());
  EXPECT_TRUE(r.albedo.empty());
  EXPECT_TRUE(r.variance.empty());
  EXPECT_TRUE(r.accumulation.sum.empty());
  RenderSettings with_aovs;
  with_aovs.outputs.depth = with_aovs.outputs.prim = with_aovs.outputs.normal = true;
  const RenderResult a = render(with_aovs);
  ASSERT_EQ(a.prim.size(), n);
  EXPECT_EQ(0, std::memcmp(a.color.data(), r.color.data(), n * sizeof(glm::vec3)));
}

// TracerOptions: "The defaults are the recommended settings": Moller-Trumbore, the scaled
// offset, the incremental traversal, no extra features, no mutation; a tracer built without
// options has them.
TEST_F(Defaults, TracerOptionsAreTheRecommendedKnobs) {
  const TracerOptions o;
  EXPECT_EQ(o.triangle, TriangleTest::MollerTrumbore);
  EXPECT_EQ(o.offset, SelfIntersection::Scaled);
  EXPECT_EQ(o.traversal, Traversal::Incremental);
  EXPECT_EQ(o.extra_features.str(), Features{}.str());
  EXPECT_EQ(o.mutation, PathMutation::None);
  EXPECT_EQ(o.str(), "moller scaled incremental");
  EXPECT_EQ(tracer_.options().str(), "moller scaled incremental");
}

// Tracer::source: strict and the Auto loop by default; outputs and samples select no variant.
TEST_F(Defaults, SourceIsTheDefaultRendersVariant) {
  EXPECT_EQ(tracer_.source("cpu"),
            tracer_.source("cpu", rill::Accuracy::Strict, MegakernelLoop::Auto, FrameOutputs{}, 1));
  EXPECT_EQ(tracer_.source("cpu"),
            tracer_.source("cpu", rill::Accuracy::Strict, MegakernelLoop::Auto,
                           FrameOutputs{false, true, true, true, true}, 4));
  EXPECT_NE(tracer_.source("cpu"), tracer_.source("cpu", rill::Accuracy::Fast));
}

}  // namespace
}  // namespace rt
