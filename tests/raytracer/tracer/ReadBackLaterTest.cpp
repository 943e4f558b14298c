// Frames whose read-back overlaps the next frame's trace (RenderSettings::read_back_later), on
// every backend: a sequence rendered as rill-trace's --frames does it with --overlap on (frame
// n's read-back in flight while frame n + 1 renders into another result) gives each frame the
// bytes of that frame rendered on its own: colour, 8-bit image, AOVs, albedo, with frames that
// differ (a dynamic scene, a moving camera) and with one and several samples.
//
// OpenCL and glsl-compute leave the read-back in flight (checked). glsl-compute maps its copy
// at the wait, after the next frame has traced; RILL_OPENCL_READBACK=late holds OpenCL's
// transfer until then too: a read-back that did not keep its own copy of the outputs
// (rill/ReadBack.h), or a frame that wrote the streams or the memory still being read, would
// then give the next frame's bytes, which differ from its own (checked too). The other
// backends read back before render returns.
#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::expect_identical;

class ReadBackLater : public ::testing::TestWithParam<std::string> {};

// RILL_OPENCL_READBACK for one block (the backend reads it at each read-back).
struct OpenClReadBack {
  explicit OpenClReadBack(const char* mode) { setenv("RILL_OPENCL_READBACK", mode, 1); }
  ~OpenClReadBack() { unsetenv("RILL_OPENCL_READBACK"); }
  OpenClReadBack(const OpenClReadBack&) = delete;
  OpenClReadBack& operator=(const OpenClReadBack&) = delete;
};

// The camera of frame i, after moving the tracer's scene to it.
using FrameAt = std::function<Camera(Tracer&, int)>;

// Frames 0..n-1, each on its own: rendered, read back, then the next.
std::vector<RenderResult> one_at_a_time(Tracer& t, const RenderSettings& rs, const FrameAt& at,
                                        int n) {
  std::vector<RenderResult> frames;
  for (int i = 0; i < n; ++i) frames.push_back(t.render(rs, at(t, i)));
  return frames;
}

// Frames 0..n-1 as a sequence with overlap renders them: frame i's read-back is waited for
// after frame i + 1 has rendered, into the other of two results.
std::vector<RenderResult> overlapped(Tracer& t, RenderSettings rs, const FrameAt& at, int n) {
  rs.read_back_later = true;
  // The backends that read back asynchronously.
  const bool in_flight = rs.backend == "opencl" || rs.backend == "glsl-compute";
  RenderResult results[2];
  std::vector<RenderResult> frames;
  for (int i = 0; i < n; ++i) {
    RenderResult& r = results[i % 2];
    t.render(rs, at(t, i), r);
    EXPECT_EQ(r.in_flight != nullptr, in_flight) << "frame " << i;
    if (i > 0) {
      RenderResult& before = results[(i + 1) % 2];
      before.wait_outputs();
      EXPECT_EQ(before.in_flight, nullptr);
      frames.push_back(before);
    }
  }
  results[(n + 1) % 2].wait_outputs();
  frames.push_back(results[(n + 1) % 2]);
  return frames;
}

// Each overlapped frame is its frame rendered alone, and consecutive frames differ (so that
// a frame read after the next one overwrote its outputs would show).
void expect_same_frames(const std::vector<RenderResult>& want, const std::vector<RenderResult>& got,
                        const std::string& what) {
  ASSERT_EQ(want.size(), got.size());
  for (size_t i = 0; i < want.size(); ++i) {
    const std::string frame = what + ", frame " + std::to_string(i);
    ASSERT_FALSE(want[i].rgb8.empty()) << frame;
    expect_identical(want[i], got[i], frame);
    EXPECT_EQ(want[i].rgb8, got[i].rgb8) << frame;
    EXPECT_EQ(want[i].albedo.size(), got[i].albedo.size()) << frame;
    EXPECT_TRUE(want[i].albedo == got[i].albedo) << frame;
    EXPECT_EQ(want[i].rays, got[i].rays) << frame;
    if (i > 0) {
      EXPECT_NE(want[i - 1].rgb8, want[i].rgb8) << frame << ": the same as the one before";
    }
  }
}

// Moving objects and a moving camera (DynamicRenderTest.cpp's scene, smaller).
const char* kMovingScene = R"({
  "builtin": "thesis-a",
  "animation": {"start": 0, "end": 2, "fps": 12},
  "materials": {"gold": {"diffuse": [0.9, 0.7, 0.2], "specular": 0.5, "shininess": 30}},
  "meshes": [
    {"name": "cube", "shape": "box", "min": [-0.4, 0, -0.4], "max": [0.4, 0.8, 0.4], "material": "gold",
     "animate": {"keys": [{"time": 0, "translate": [-1.5, 0.5, 0.6]},
                          {"time": 2, "translate": [1.8, 1.4, 0.8], "rotate": {"axis": [0, 1, 0], "degrees": 90}}]}}
  ],
  "camera": {"eye": [1, 3.5, 7.5], "look_at": [0, 1, 0], "fov_y": 45,
             "keys": [{"time": 0}, {"time": 2, "eye": [-2, 4, 6.5], "fov_y": 40}]}
})";

TEST_P(ReadBackLater, DynamicFramesEqualFramesRenderedOneAtATime) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = parse_json_scene(kMovingScene, ".", "moving.json");
  ASSERT_TRUE(s.animation.animated());
  const Grid g = build_grid(s, 0, kNoSubgrids);
  const FrameAt at = [&s](Tracer& t, int i) {
    const double time = 0.5 * i;
    t.set_time(time);
    return camera_at(s, time);
  };
  struct Case {
    Strategy strategy;
    int spp;
  };
  for (const Case& c : {Case{Strategy::Megakernel, 1}, Case{Strategy::Megakernel, 2},
                        Case{Strategy::Multipass, 1}}) {
    RenderSettings rs;
    rs.backend = GetParam();
    rs.strategy = c.strategy;
    rs.width = 40;
    rs.height = 30;
    rs.max_depth = 2;
    rs.spp = c.spp;
    rs.outputs.rgb8 = rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
    Tracer alone(s, g);
    const std::vector<RenderResult> want = one_at_a_time(alone, rs, at, 4);
    for (const char* mode : {"overlap", "late"}) {
      const OpenClReadBack setting(mode);
      Tracer t(s, g);
      expect_same_frames(want, overlapped(t, rs, at, 4),
                         c.strategy.name + ", " + std::to_string(c.spp) + " spp, " + mode);
    }
  }
}

// The path integrator's frames with its albedo AOV, through a camera that moves along a
// static scene; the variance is read before render returns.
TEST_P(ReadBackLater, PathFramesWithAlbedoEqualFramesRenderedOneAtATime) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = builtin_scene("cornell-path");
  const Grid g = build_grid_for(s);
  const FrameAt at = [&s](Tracer&, int i) {
    Camera c = s.camera;
    c.eye.x += 0.1f * static_cast<float>(i);
    return c;
  };
  for (const Strategy& strategy : {Strategy::Megakernel, Strategy::Wavefront}) {
    RenderSettings rs;
    rs.backend = GetParam();
    rs.strategy = strategy;
    rs.width = 24;
    rs.height = 20;
    rs.spp = 2;
    rs.max_depth = 3;
    rs.outputs.rgb8 = rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
    rs.outputs.albedo = true;
    Tracer alone(s, g);
    const std::vector<RenderResult> want = one_at_a_time(alone, rs, at, 3);
    const OpenClReadBack setting("late");
    Tracer t(s, g);
    expect_same_frames(want, overlapped(t, rs, at, 3), strategy.name);
    rs.outputs.variance = true;
    rs.read_back_later = true;
    const RenderResult r = t.render(rs, at(t, 0));
    EXPECT_EQ(r.in_flight, nullptr) << strategy.name << ": with the variance";
    EXPECT_FALSE(r.variance.empty());
    expect_identical(want[0], r, strategy.name + ", with the variance");
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, ReadBackLater, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
