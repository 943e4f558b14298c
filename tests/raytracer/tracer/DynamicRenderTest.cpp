// Dynamic scenes on every backend (Tracer::set_time, accel/Bvh.h): a frame of an animated
// scene is bit for bit the static scene baked at that instant (scene/Pose.h) - image, depth,
// primitive ids, normals and ray count - with both strategies, with BVH rebuilds and refits,
// at keys, between them and past the time range; instances with pivots and materials of
// their own. A scene without moving objects generates no BVH code.
#include <gtest/gtest.h>

#include <random>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::expect_identical;

class DynamicRender : public ::testing::TestWithParam<std::string> {};

// Moving objects in front of, behind and inside static ones: a mirror that slides (reflected
// rays through both accelerators), a cube that spins through the static boxes (shadows
// blocked by either), an instanced sphere that falls and shrinks, and a moving camera.
const char* kDynamicScene = R"({
  "builtin": "thesis-a",
  "animation": {"start": 0, "end": 2, "fps": 12},
  "materials": {
    "mirror": {"diffuse": [0.1, 0.1, 0.1], "reflect": 0.6},
    "gold": {"diffuse": [0.9, 0.7, 0.2], "specular": 0.5, "shininess": 30}
  },
  "meshes": [
    {"shape": "quad", "vertices": [[-3, 0, -2], [3, 0, -2], [3, 3, -2], [-3, 3, -2]],
     "material": "mirror",
     "animate": {"keys": [{"time": 0, "translate": [-1, 0, 0]}, {"time": 2, "translate": [1, 0, -0.5]}]}},
    {"name": "cube", "shape": "box", "min": [-0.4, 0, -0.4], "max": [0.4, 0.8, 0.4], "material": "gold",
     "animate": {"interpolation": "smooth", "keys": [
       {"time": 0, "translate": [-1.5, 0.5, 0.6]},
       {"time": 1, "translate": [0.4, 0.2, -0.2], "rotate": {"axis": [1, 1, 0], "degrees": 120}},
       {"time": 2, "translate": [1.8, 1.4, 0.8], "rotate": {"axis": [0, 1, 0], "degrees": 30}, "scale": [1, 2, 1]}]}},
    {"name": "ball", "shape": "sphere", "center": [0, 0, 0], "radius": 0.35, "slices": 12, "stacks": 6,
     "material": "gold"}
  ],
  "instances": [
    {"mesh": "ball", "transform": {"translate": [0.5, 2.8, 1.2]},
     "animate": {"keys": [{"time": 0}, {"time": 1.5, "translate": [0, -2.4, 0], "scale": 0.5}]}}
  ],
  "camera": {"eye": [1, 3.5, 7.5], "look_at": [0, 1, 0], "fov_y": 45,
             "keys": [{"time": 0}, {"time": 2, "eye": [-2, 4, 6.5], "fov_y": 40}]}
})";

RenderSettings settings(const std::string& backend, Strategy strategy) {
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = backend;
  rs.strategy = strategy;
  rs.width = 40;
  rs.height = 30;
  rs.max_depth = 2;
  return rs;
}

// The baked scene at `time` through the static grid alone.
RenderResult baked(const Scene& s, double time, const RenderSettings& rs) {
  const Scene b = bake(s, time);
  const Grid g = build_grid(b, 0, kNoSubgrids);
  Tracer t(b, g);
  return t.render(rs, b.camera);
}

TEST_P(DynamicRender, FramesEqualTheSceneBakedAtThatTime) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = parse_json_scene(kDynamicScene, ".", "dynamic.json");
  ASSERT_TRUE(s.animation.animated());
  const Grid g = build_grid(s, 0, kNoSubgrids);
  for (Strategy strategy : {Strategy::Megakernel, Strategy::Multipass}) {
    const RenderSettings rs = settings(GetParam(), strategy);
    Tracer rebuild(s, g), refit(s, g);
    // Keys, between keys (smooth and linear), and after the range (the last pose holds).
    for (double t : {0.0, 0.37, 1.0, 1.64, 2.0, 3.5}) {
      const std::string what =
          std::string(strategy == Strategy::Multipass ? "multipass" : "megakernel") +
          " at t = " + std::to_string(t);
      const RenderResult want = baked(s, t, rs);
      rebuild.set_time(t, BvhUpdate::Rebuild);
      expect_identical(want, rebuild.render(rs, camera_at(s, t)), what + ", rebuilt");
      const FrameUpdate u = refit.set_time(t, BvhUpdate::Refit);
      EXPECT_FALSE(u.rebuilt) << what;
      // Only the moving triangles' span goes up again: thesis A's 36 static ones come first.
      EXPECT_EQ(u.uploaded, s.triangle_count() - 36) << what;
      EXPECT_GE(u.uploaded, u.moving) << what;
      expect_identical(want, refit.render(rs, camera_at(s, t)), what + ", refitted");
    }
  }
}

// With subgrids in the static grid, and a scene whose triangles all move (an empty grid).
TEST_P(DynamicRender, SubgridsAndScenesWithoutStaticTriangles) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = parse_json_scene(kDynamicScene, ".", "dynamic.json");
  const RenderSettings rs = settings(GetParam(), Strategy::Megakernel);
  const Grid sub = build_grid(s, 6, 1);
  ASSERT_GT(sub.subgrids, 0);
  Tracer t(s, sub);
  t.set_time(0.8);
  expect_identical(baked(s, 0.8, rs), t.render(rs, camera_at(s, 0.8)), "with subgrids");

  Scene only = s;
  AnimatedObject all;
  all.name = "everything";
  all.count = only.triangle_count();
  all.track = s.animation.objects[1].track;
  only.animation.objects = {all};
  const Grid empty = build_grid(only);
  ASSERT_TRUE(empty.empty());
  Tracer moving(only, empty);
  moving.set_time(1.2);
  expect_identical(baked(only, 1.2, rs), moving.render(rs, camera_at(only, 1.2)),
                   "every triangle moving");
}

// A deforming mesh (an OBJ sequence, scene/AnimationJson.h) and a copy of it that also
// moves: each frame equals its baked scene, the shapes switching between frames.
TEST_P(DynamicRender, DeformingMeshesEqualTheirBakedFrames) {
  RT_REQUIRE_BACKEND(GetParam());
  testing::TempDir dir;
  for (int k = 0; k < 3; ++k)
    dir.file("wave-" + std::to_string(k) + ".obj", testing::wave_obj(0.6f * static_cast<float>(k)));
  const Scene s = load_json(dir.file("wave.json", R"({
    "builtin": "thesis-a", "animation": {"end": 1.5, "fps": 4},
    "meshes": [{"name": "wave", "file": "wave-%d.obj", "sequence": {"last": 2, "fps": 2},
                "transform": {"translate": [-1, 0.2, 1.2]}}],
    "instances": [{"mesh": "wave", "transform": {"translate": [0, 1.5, 0]},
                   "animate": {"keys": [{"time": 0}, {"time": 1.5, "rotate": {"axis": [0, 1, 0], "degrees": 60}}]}}]
  })"));
  const Grid g = build_grid(s, 0, kNoSubgrids);
  for (Strategy strategy : {Strategy::Megakernel, Strategy::Multipass}) {
    const RenderSettings rs = settings(GetParam(), strategy);
    Tracer t(s, g);
    for (double time : {0.0, 0.5, 0.75, 1.5}) {
      t.set_time(time, BvhUpdate::Refit);
      expect_identical(baked(s, time, rs), t.render(rs, camera_at(s, time)),
                       "wave at t = " + std::to_string(time));
    }
  }
}

// Rays from far away aimed at the edges of small flat faces: their boxes are flat, and the
// slab test's rounding grows with the distance from the eye while the boxes' padding does
// not. Every face the triangle test accepts must be found through the BVH as through the
// grid of the baked scene.
TEST_P(DynamicRender, FarRaysAtTheEdgesOfFlatFaces) {
  RT_REQUIRE_BACKEND(GetParam());
  // Eyes 1000 units from a board at the origin; then eyes 3 units from a board 10^4 units
  // out (where the padding, not the widening, must cover the rounding of o - lo).
  for (const float offset : {0.0f, 1.0e4f}) {
    const float distance = offset == 0.0f ? 1000.0f : 3.0f;
    SCOPED_TRACE("board at " + std::to_string(offset) + ", eyes " + std::to_string(distance) +
                 " away");
    Scene s;
    s.add_material(Material{});
    // 8 x 8 quads of 0.1 units in the z = 0 plane, and slivers above them.
    for (int i = 0; i < 8; ++i)
      for (int j = 0; j < 8; ++j) {
        const float x = offset + 0.1f * static_cast<float>(i),
                    y = offset + 0.1f * static_cast<float>(j);
        add_quad(s, {x, y, 0.0f}, {x + 0.1f, y, 0.0f}, {x + 0.1f, y + 0.1f, 0.0f},
                 {x, y + 0.1f, 0.0f}, 0);
        s.add_triangle({x, y, 0.3f}, {x + 0.1f, y + 0.0001f, 0.3f}, {x, y + 0.0002f, 0.3f}, 0);
      }
    AnimatedObject o;
    o.name = "board";
    o.count = s.triangle_count();
    PoseKey a, b;
    b.time = 1.0;
    b.pose.translate = glm::dvec3(0.05, 0.0, 0.0);
    o.track.keys = {a, b};
    s.animation.objects = {o};
    s.animation.time = TimeRange{0.0, 1.0, 10.0};
    s.camera = Camera{{offset + 0.4f, offset + 0.4f, distance},
                      {offset + 0.4f, offset + 0.4f, 0.0f},
                      {0.0f, 1.0f, 0.0f},
                      30.0f};
    s.has_camera = true;
    const double time = 0.5;
    const Scene b_scene = bake(s, time);
    // Rays towards points on the triangles' edges, each moved by up to 1e-6 of the scale.
    std::mt19937 rng(7);
    const float scale = std::max(1.0f, offset);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f), jitter(-1e-6f * scale, 1e-6f * scale),
        eye(-0.3f * distance, 0.3f * distance);
    std::vector<glm::vec3> origins, dirs;
    for (int r = 0; r < 20000; ++r) {
      const size_t tri = static_cast<size_t>(r) % b_scene.triangle_count();
      const glm::vec3* p = &b_scene.positions[3 * tri];
      const int k = r % 3;
      const glm::vec3 on = p[k] + (p[(k + 1) % 3] - p[k]) * u01(rng) +
                           glm::vec3(jitter(rng), jitter(rng), jitter(rng));
      const glm::vec3 from(offset + eye(rng), offset + eye(rng), distance);
      origins.push_back(from);
      dirs.push_back(on - from);
    }
    Tracer moving(s, build_grid(s));
    moving.set_time(time);
    Tracer baked_tracer(b_scene, build_grid(b_scene));
    std::vector<int32_t> want_prim, got_prim;
    std::vector<float> want_t, got_t;
    baked_tracer.intersect(GetParam(), origins, dirs, want_prim, want_t);
    moving.intersect(GetParam(), origins, dirs, got_prim, got_t);
    int differ = 0, hits = 0;
    for (size_t r = 0; r < origins.size(); ++r) {
      hits += want_prim[r] >= 0;
      if (want_prim[r] != got_prim[r] || !testing::same(want_t[r], got_t[r])) {
        if (++differ <= 3)
          ADD_FAILURE() << "ray " << r << ": baked prim " << want_prim[r] << " t " << want_t[r]
                        << ", moving prim " << got_prim[r] << " t " << got_t[r];
      }
    }
    EXPECT_EQ(differ, 0);
    EXPECT_GT(hits, 10000);  // most of them hit something
  }
}

// A sequence whose first file is collapsed to a point: nothing of it can be hit at rest, and
// it must still be traced once it unfolds.
TEST_P(DynamicRender, ObjectsDegenerateAtRestAppearLater) {
  RT_REQUIRE_BACKEND(GetParam());
  testing::TempDir dir;
  dir.file("fold-0.obj",
           "v 1 1 0\nv 1 1 0\nv 1 1 0\nv 1 1 0\nv 1 1 0\nv 1 1 0\n"
           "f 1 2 5 4\nf 2 3 6 5\n");
  dir.file("fold-1.obj", testing::wave_obj(0.3f));
  const Scene s = load_json(dir.file("fold.json", R"({
    "animation": {"end": 1, "fps": 2},
    "meshes": [{"file": "fold-%d.obj", "sequence": {"last": 1}}],
    "lights": [{"position": [0, 3, 5]}],
    "camera": {"eye": [1, 0.5, 4], "look_at": [1, 0.5, 0]}
  })"));
  Tracer t(s, build_grid(s));
  EXPECT_TRUE(t.features().dynamic);
  const RenderSettings rs = settings(GetParam(), Strategy::Megakernel);
  t.set_time(0.5);
  const RenderResult got = t.render(rs, camera_at(s, 0.5));
  expect_identical(baked(s, 0.5, rs), got, "unfolded");
  int hits = 0;
  for (int32_t p : got.prim) hits += p >= 0;
  EXPECT_GT(hits, 100);
}

// Instances (docs/scene-format.md "instances") with pivots, materials of their own and a
// prototype mesh: static copies (in the grid) and animated ones (in the BVH) give the bits of
// the cpu backend and of the baked scene, and each copy's pixels show its own material.
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

TEST_P(DynamicRender, InstancesShowTheirMaterialAndMatchCpuAndTheBakedScene) {
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
      expect_identical(baked(s, t, rs), got, what + ": frame vs baked");
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

INSTANTIATE_TEST_SUITE_P(Backends, DynamicRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

// Only what the scene calls for is generated: no BVH code without moving objects.
TEST(DynamicFeatures, BvhCodeOnlyForScenesThatMove) {
  const Scene s = parse_json_scene(kDynamicScene, ".", "dynamic.json");
  Tracer moving(s, build_grid(s));
  EXPECT_TRUE(moving.features().dynamic);
  EXPECT_NE(moving.source("cpu").find("bvh_"), std::string::npos);
  const Scene still = bake(s, 0.5);
  Tracer fixed(still, build_grid(still));
  EXPECT_FALSE(fixed.features().dynamic);
  EXPECT_EQ(fixed.source("cpu").find("bvh_"), std::string::npos);
  // A static scene's tracer ignores set_time.
  const FrameUpdate u = fixed.set_time(1.0);
  EXPECT_EQ(u.moving, 0u);
}

}  // namespace
}  // namespace rt
