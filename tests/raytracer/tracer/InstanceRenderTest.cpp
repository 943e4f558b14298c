// Instances with pivots, materials of their own and prototype meshes, rendered on every
// backend (docs/scene-format.md "instances"): static copies (in the grid) and animated ones
// (in the BVH) give the bits of the cpu backend, an animated frame is bit for bit the scene
// baked at that time, and the pixels of each copy show its own material.
#include <gtest/gtest.h>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::expect_identical;

// A floor, a green teapot that is only a prototype, a red copy turned about its own centre
// (static: in the grid), and a blue copy that spins about its pivot while it moves (in the
// BVH). The red and blue materials have no highlight and no reflection, so that every pixel
// of a copy is exactly its colour times its lighting: g = b = 0 on red, r = g = 0 on blue.
// The blue copy rises above the scene's bounds at rest, which sets how far secondary rays
// start off surfaces: the floor's reflections differed from the baked scene's until
// Tracer::set_time took the offset from the posed scene.
const char* kInstances = R"({
  "animation": {"start": 0, "end": 2, "fps": 12},
  "materials": {
    "green": {"diffuse": [0, 1, 0], "specular": 0.5},
    "red": {"diffuse": [0.9, 0, 0], "specular": 0, "reflect": 0},
    "blue": {"diffuse": [0, 0, 0.9], "specular": 0, "reflect": 0},
    "floor": {"diffuse": 0.6, "reflect": 0.3}
  },
  "meshes": [
    {"shape": "box", "min": [-4, -0.2, -4], "max": [4, 0, 4], "material": "floor"},
    {"name": "pot", "shape": "teapot", "subdivisions": 3, "material": "green",
     "transform": {"scale": 0.4}, "prototype": true}
  ],
  "instances": [
    {"mesh": "pot", "material": "red", "pivot": [0, 0.63, 0],
     "transform": {"rotate_y": 150, "rotate_x": 20, "translate": [-0.9, 0.3, 0]}},
    {"mesh": "pot", "material": "blue", "pivot": [0, 0.63, 0], "transform": {"translate": [1, 0, 0.3]},
     "animate": {"keys": [{"time": 0},
                          {"time": 2, "translate": [0, 0.5, -0.5], "scale": 1.3,
                           "rotate": {"axis": [0.3, 1, 0], "degrees": 170}}]}}
  ],
  "lights": [{"position": [2, 5, 4]}, {"position": [-3, 3, 2], "color": 0.5}],
  "camera": {"eye": [0, 2.2, 5], "look_at": [0, 0.5, 0], "fov_y": 40}
})";

class InstanceRender : public ::testing::TestWithParam<std::string> {};

RenderSettings settings(const std::string& backend, Strategy strategy) {
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = backend;
  rs.strategy = strategy;
  rs.width = 48;
  rs.height = 32;
  rs.max_depth = 2;
  return rs;
}

TEST_P(InstanceRender, CopiesShowTheirMaterialAndMatchCpuAndTheBakedScene) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = parse_json_scene(kInstances, ".", "instances.json");
  const size_t floor = 12, pot = 64 * 3 * 3;
  ASSERT_EQ(s.triangle_count(), floor + 2 * pot);  // no triangle of the prototype itself
  ASSERT_EQ(s.animation.objects.size(), 1u);
  const Grid g = build_grid(s, 0, kNoSubgrids);
  for (Strategy strategy : {Strategy::Megakernel, Strategy::Multipass}) {
    for (double t : {0.0, 0.9, 2.0}) {
      const std::string what =
          std::string(strategy == Strategy::Multipass ? "multipass" : "megakernel") +
          " at t = " + std::to_string(t);
      const RenderSettings rs = settings(GetParam(), strategy);
      Tracer tracer(s, g);
      tracer.set_time(t);
      const RenderResult got = tracer.render(rs, camera_at(s, t));
      // The animated copy through the BVH equals the baked scene through the grid alone.
      const Scene b = bake(s, t);
      Tracer baked(b, build_grid(b, 0, kNoSubgrids));
      expect_identical(baked.render(rs, b.camera), got, what + ": frame vs baked");
      if (GetParam() != "cpu") {
        Tracer cpu(s, g);
        cpu.set_time(t);
        expect_identical(cpu.render(settings("cpu", strategy), camera_at(s, t)), got,
                         what + ": cpu vs " + GetParam());
      }
      // Each copy's pixels are its own colour: ids [floor, floor + pot) are the red one,
      // the next pot the blue one (primitive ids: the prototype takes none).
      int red = 0, blue = 0;
      for (size_t p = 0; p < got.prim.size(); ++p) {
        const int32_t id = got.prim[p];
        const glm::vec3 c = got.color[p];
        if (id >= static_cast<int32_t>(floor) && id < static_cast<int32_t>(floor + pot)) {
          ++red;
          EXPECT_TRUE(c.r > 0.0f && c.g == 0.0f && c.b == 0.0f)
              << what << ": pixel " << p << " of the red copy is " << c.r << " " << c.g << " "
              << c.b;
        } else if (id >= static_cast<int32_t>(floor + pot)) {
          ++blue;
          EXPECT_TRUE(c.b > 0.0f && c.r == 0.0f && c.g == 0.0f)
              << what << ": pixel " << p << " of the blue copy is " << c.r << " " << c.g << " "
              << c.b;
        }
      }
      EXPECT_GT(red, 40) << what;  // both copies are in view
      EXPECT_GT(blue, 40) << what;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, InstanceRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
