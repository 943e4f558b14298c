// The megakernel's two loops (megakernel/Megakernel.h): Ray and Segment give the same bits on
// every backend, over scenes that between them take the loop's branches (shadow rays through
// the light buffer and through the grid, blocked by static and by moving objects; lights
// without shadow rays; textures; reflection, refraction with a ray stack that fills up;
// vertex normals and colours; no geometry); Auto picks Segment on cpu and simd, Ray on the
// others; the names parse.
#include <gtest/gtest.h>

#include <stdexcept>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::expect_identical;

class MegakernelLoopRender : public ::testing::TestWithParam<std::string> {};

// Thesis A with a mirror and a cube that move: shadow rays blocked through the BVH.
const char* kMoving = R"({
  "builtin": "thesis-a",
  "animation": {"start": 0, "end": 1},
  "materials": {"mirror": {"diffuse": [0.1, 0.1, 0.1], "reflect": 0.6}},
  "meshes": [
    {"shape": "quad", "vertices": [[-3, 0, -2], [3, 0, -2], [3, 3, -2], [-3, 3, -2]],
     "material": "mirror",
     "animate": {"keys": [{"time": 0, "translate": [-1, 0, 0]}, {"time": 1, "translate": [1, 0, 0]}]}},
    {"shape": "box", "min": [-0.4, 0, -0.4], "max": [0.4, 0.8, 0.4], "material": "mirror",
     "animate": {"keys": [{"time": 0, "translate": [-1.5, 0.5, 0.6]}, {"time": 1, "translate": [0.4, 1.2, 0.2]}]}}
  ]
})";

struct Case {
  std::string what;
  Scene scene;
  TracerOptions options;
  int max_depth = 3;
  double time = -1;  // a dynamic scene's time
};

// Few scenes keep the compiles (two per scene and backend) few.
std::vector<Case> cases() {
  std::vector<Case> out;
  // Every effect's code in the kernel (specular, reflection, refraction, vertex normals and
  // colours), shadow rays through the light buffer (and the grid where a cell of it falls
  // back); depth 5 fills the ray stack (3 entries).
  TracerOptions all;
  all.extra_features.specular = all.extra_features.reflection = all.extra_features.refraction =
      all.extra_features.vertex_normals = all.extra_features.vertex_colors = true;
  out.push_back({"glass with every effect", builtin_scene("glass"), all, 5});
  // Shadow rays through the static grid and the moving objects' BVH.
  Scene moving = parse_json_scene(kMoving, ".", "moving.json");
  moving.options.light_buffer = kLightBufferOff;
  out.push_back({"moving objects, no light buffer", moving, {}, 3, 0.6});
  // Textured materials, lights without shadow rays.
  Scene textured = builtin_scene("textured");
  textured.options.shadows = false;
  out.push_back({"textured, no shadows", textured, {}});
  out.push_back({"empty", builtin_scene("empty"), {}});
  return out;
}

TEST_P(MegakernelLoopRender, RayAndSegmentGiveTheSameBits) {
  RT_REQUIRE_BACKEND(GetParam());
  for (Case& c : cases()) {
    SCOPED_TRACE(c.what);
    const Grid g = build_grid(c.scene, 0);
    Tracer t(c.scene, g, c.options);
    // What each case is there for.
    const Features& f = t.features();
    if (c.what == "glass with every effect") {
      EXPECT_TRUE(f.shadows && f.refraction && f.stack > 0 && t.light_buffer().res > 0);
    }
    if (c.time >= 0) {
      EXPECT_TRUE(f.dynamic && f.shadows && t.light_buffer().res == 0);
    }
    if (c.what == "textured, no shadows") {
      EXPECT_TRUE(f.lights && f.texcoords && !f.shadows);
    }
    if (c.what == "empty") {
      EXPECT_FALSE(f.geometry);
    }
    Camera camera = c.scene.camera;
    if (c.time >= 0) {
      t.set_time(c.time);
      camera = camera_at(c.scene, c.time);
    }
    // Two different programs, or the comparison below would prove nothing.
    ASSERT_NE(t.program(MegakernelLoop::Ray).hash(), t.program(MegakernelLoop::Segment).hash());
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.backend = GetParam();
    rs.width = 24;
    rs.height = 18;
    rs.max_depth = c.max_depth;
    rs.loop = MegakernelLoop::Ray;
    const RenderResult ray = t.render(rs, camera);
    EXPECT_EQ(ray.loop, "ray");
    rs.loop = MegakernelLoop::Segment;
    const RenderResult segment = t.render(rs, camera);
    EXPECT_EQ(segment.loop, "segment");
    if (f.geometry && (f.shadows || f.reflection)) {  // some shadow or secondary rays
      EXPECT_GT(segment.rays, int64_t{rs.width} * rs.height);
    }
    expect_identical(ray, segment, c.what + ": ray vs segment loop");
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, MegakernelLoopRender,
                         ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

// Auto: Segment on Rill's C backends, Ray on OpenCL and GLSL on any device (PoCL and llvmpipe
// too, so that CI runs the program a GPU runs).
TEST(MegakernelLoop, AutoIsSegmentOnTheCBackendsAndRayOnOpenClAndGlsl) {
  for (const std::string& name : testing::backend_names()) {
    SCOPED_TRACE(name);
    const MegakernelLoop want =
        name == "cpu" || name == "simd" ? MegakernelLoop::Segment : MegakernelLoop::Ray;
    EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, name), want);
    // A loop named explicitly is kept.
    EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Ray, name), MegakernelLoop::Ray);
    EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Segment, name), MegakernelLoop::Segment);
  }
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "cpu"), MegakernelLoop::Segment);
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "simd"), MegakernelLoop::Segment);
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "opencl"), MegakernelLoop::Ray);
  EXPECT_EQ(megakernel_loop_for(MegakernelLoop::Auto, "glsl"), MegakernelLoop::Ray);
}

TEST(MegakernelLoop, NamesParseAndABadNameIsNamed) {
  for (MegakernelLoop l : {MegakernelLoop::Auto, MegakernelLoop::Ray, MegakernelLoop::Segment})
    EXPECT_EQ(parse_megakernel_loop(megakernel_loop_name(l)), l);
  try {
    parse_megakernel_loop("wavefront");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'wavefront'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("segment"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rt
