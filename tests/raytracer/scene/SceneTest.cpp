// Scenes: the built-ins, the OBJ + MTL loader (fanning, numbering, materials) and the JSON
// scene format.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "MaterialValues.h"
#include "TestUtil.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"

namespace rt {
namespace {

using testing::color_of;
using testing::number_of;
using testing::TempDir;

TEST(Scene, BuiltinTriangleCounts) {
  EXPECT_EQ(builtin_scene("thesis-a").triangle_count(), 36u);
  EXPECT_EQ(builtin_scene("thesis-b").triangle_count(), 2064u);
  EXPECT_EQ(builtin_scene("thesis-c").triangle_count(), 61562u);
  EXPECT_EQ(builtin_scene("cornell").triangle_count(), 30u);
  EXPECT_EQ(builtin_scene("empty").triangle_count(), 0u);
  for (const std::string& name : builtin_scene_names()) {
    SCOPED_TRACE(name);
    Scene s = builtin_scene(name);
    EXPECT_NO_THROW(s.validate());
    EXPECT_TRUE(s.has_camera);
  }
  EXPECT_THROW(builtin_scene("nope"), SceneError);
}

TEST(Scene, BuiltinScenesAreDeterministic) {
  Scene a = builtin_scene("thesis-b"), b = builtin_scene("thesis-b");
  ASSERT_EQ(a.positions.size(), b.positions.size());
  EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(),
                           a.positions.size() * sizeof(glm::vec3)));
}

TEST(Scene, GlassSceneHasGlassAndMirrors) {
  Scene s = builtin_scene("glass");
  bool glass = false, mirror = false;
  for (const Material& m : s.materials) {
    glass = glass || (m.shader == "glass" && number_of(m, "transmit") > 0.5f);
    mirror = mirror || number_of(m, "reflect") > 0.5f;
  }
  EXPECT_TRUE(glass);
  EXPECT_TRUE(mirror);
}

TEST(Scene, TeapotTessellation) {
  Scene s;
  s.add_material(Material{});
  add_teapot(s, 3, 0);
  EXPECT_EQ(s.triangle_count(), 64u * 9u);
  glm::vec3 lo, hi;
  ASSERT_TRUE(scene_bounds(s, lo, hi));
  EXPECT_NEAR(lo.y, 0.0f, 1e-5f);  // base on y = 0
  EXPECT_NEAR(hi.y, 3.15f, 1e-4f);
  EXPECT_NEAR(lo.x, -3.0f, 1e-4f);  // handle
  EXPECT_GT(hi.x, 3.4f);            // spout
  EXPECT_LT(hi.x, 3.53f);
  // Smooth normals point outwards (glass needs to know inside from outside): on the body,
  // away from the vertical axis.
  ASSERT_EQ(s.normals.size(), s.positions.size());
  int body = 0;
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const glm::vec3& p = s.positions[i];
    if (std::fabs(p.y - 1.2f) > 0.3f || std::fabs(p.x) > 1.0f)
      continue;  // body, away from spout/handle
    ++body;
    EXPECT_GT(p.x * s.normals[i].x + p.z * s.normals[i].z, 0.0f) << "vertex " << i;
  }
  EXPECT_GT(body, 0);
  // The lid's knob points up, the bottom down.
  for (size_t i = 0; i < s.positions.size(); ++i) {
    const glm::vec3& p = s.positions[i];
    if (p.y > 3.1f) {
      EXPECT_GT(s.normals[i].y, 0.5f) << "knob vertex " << i;
    }
    if (p.y < 1e-3f && std::fabs(p.x) < 0.5f && std::fabs(p.z) < 0.5f) {
      EXPECT_LT(s.normals[i].y, -0.5f) << "bottom vertex " << i;
    }
  }
  // The winding agrees with the normals (counter-clockwise seen from outside).
  int agree = 0, total = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    glm::vec3 g = glm::cross(s.positions[3 * t + 1] - s.positions[3 * t],
                             s.positions[3 * t + 2] - s.positions[3 * t]);
    if (glm::length(g) < 1e-6f) continue;
    ++total;
    agree += glm::dot(g, s.normals[3 * t] + s.normals[3 * t + 1] + s.normals[3 * t + 2]) > 0;
  }
  EXPECT_GT(agree, total * 98 / 100);
}

// Polygons are fanned (v0, vk, vk+1); triangles numbered shape by shape, face by face.
TEST(Scene, ObjFansPolygonsInFileOrder) {
  TempDir dir;
  std::string obj = dir.file("fan.obj",
                             "# two shapes\n"
                             "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\n"
                             "o first\n"
                             "f 1 2 3 4\n"    // quad: (1,2,3) (1,3,4)
                             "f 1 2 3 4 5\n"  // pentagon: (1,2,3) (1,3,4) (1,4,5)
                             "o second\n"
                             "f -1 -4 -3\n");  // relative: (5,2,3)
  Scene s = load_obj(obj);
  ASSERT_EQ(s.triangle_count(), 6u);
  const int expect[6][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {4, 1, 2}};
  const glm::vec3 v[5] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0.5f, 0}};
  for (int t = 0; t < 6; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(s.positions[3 * t + k], v[expect[t][k]]) << "triangle " << t;
  EXPECT_TRUE(s.normals.empty());
  EXPECT_TRUE(s.colors.empty());
}

TEST(Scene, ObjMaterialsNormalsAndColors) {
  TempDir dir;
  dir.file("m.mtl",
           "newmtl red\nKd 0.9 0.1 0.1\nKs 0.5 0.5 0.5\nNs 64\n"
           "newmtl mirror\nKd 0.1 0.1 0.1\nKs 0.8 0.8 0.8\nillum 3\n"
           "newmtl glass\nKd 1 1 1\nd 0.1\nNi 1.33\nillum 7\nKs 0 0 0\n");
  std::string obj = dir.file("m.obj",
                             "mtllib m.mtl\n"
                             "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\n"
                             "vn 0 0 1\n"
                             "f 1 2 3\n"
                             "usemtl red\nf 1//1 2//1 3//1\n"
                             "usemtl mirror\nf 1 2 3\n"
                             "usemtl glass\nf 1 2 3\n");
  Scene s = load_obj(obj);
  ASSERT_EQ(s.triangle_count(), 4u);
  // Face 0 has no material: the default grey.
  EXPECT_EQ(s.materials[static_cast<size_t>(s.material[0])].name, "default");
  const Material& red = s.materials[static_cast<size_t>(s.material[1])];
  EXPECT_EQ(red.name, "red");
  EXPECT_EQ(red.shader, "phong");
  EXPECT_EQ(color_of(red, "diffuse"), glm::vec3(0.9f, 0.1f, 0.1f));
  EXPECT_EQ(color_of(red, "specular"), glm::vec3(0.5f));
  EXPECT_EQ(number_of(red, "shininess"), 64.0f);
  EXPECT_EQ(number_of(red, "reflect"), 0.0f);
  const Material& mirror = s.materials[static_cast<size_t>(s.material[2])];
  EXPECT_FLOAT_EQ(number_of(mirror, "reflect"), 0.8f);
  const Material& glass = s.materials[static_cast<size_t>(s.material[3])];
  EXPECT_EQ(glass.shader, "glass");
  EXPECT_FLOAT_EQ(number_of(glass, "transmit"), 0.9f);
  EXPECT_FLOAT_EQ(number_of(glass, "ior"), 1.33f);
  // Normals: the face with vn keeps them, the others get their geometric normal.
  ASSERT_EQ(s.normals.size(), 12u);
  EXPECT_EQ(s.normals[3], glm::vec3(0, 0, 1));
  // Vertex colours.
  ASSERT_EQ(s.colors.size(), 12u);
  EXPECT_EQ(s.colors[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(s.colors[2], glm::vec3(0, 0, 1));
  EXPECT_NO_THROW(s.validate());
}

TEST(Scene, ObjWithoutMtlFileUsesDefault) {
  TempDir dir;
  std::string obj =
      dir.file("x.obj", "mtllib missing.mtl\nusemtl foo\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  Scene s = load_obj(obj);
  ASSERT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(s.materials[static_cast<size_t>(s.material[0])].name, "default");
}

TEST(Scene, ObjAloneGetsCameraAndLight) {
  TempDir dir;
  std::string obj = dir.file("t.obj", "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nf 1 2 3\n");
  Scene s = load_scene(obj);
  EXPECT_TRUE(s.has_camera);
  ASSERT_EQ(s.lights.size(), 1u);
  // The light stands above the eye and to its left (scene/Framing.h), off the view axis, so
  // that shapes cast shadows the camera sees.
  const glm::vec3 off = s.lights[0].position - s.camera.eye;
  EXPECT_GT(glm::dot(off, s.camera.up), 0.0f);
  EXPECT_GT(glm::length(glm::cross(off, s.camera.look_at - s.camera.eye)), 0.0f);
  // Every vertex is in view.
  CameraFrame f = camera_frame(s.camera, s.width, s.height);
  for (const glm::vec3& p : s.positions) {
    glm::vec3 d = normalize3(p - f.eye);
    float z = dot3(d, f.forward);
    ASSERT_GT(z, 0.0f);
    EXPECT_LT(std::fabs(dot3(d, f.right) / z), f.tan_half * f.aspect);
    EXPECT_LT(std::fabs(dot3(d, f.up) / z), f.tan_half);
  }
}

TEST(Scene, JsonDesignExample) {
  TempDir dir;
  dir.file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  std::string json = dir.file("scene.json", R"({
    "camera": {"eye": [0, 1, 5], "look_at": [0, 1, 0], "up": [0, 1, 0], "fov_y": 45},
    "image": {"width": 64, "height": 32},
    "meshes": [{"file": "tri.obj", "material": "white",
                "transform": {"translate": [1, 2, 3], "scale": 2, "rotate_y": 90}}],
    "materials": {"white": {"diffuse": [0.8, 0.8, 0.8], "specular": [0.2, 0.2, 0.2],
                            "shininess": 32, "reflect": 0, "transmit": 0, "ior": 1.5}},
    "lights": [{"position": [2, 4, 3], "color": [1, 1, 1]}],
    "background": [0.1, 0.1, 0.15]
  })");
  Scene s = load_json(json);
  EXPECT_EQ(s.width, 64);
  EXPECT_EQ(s.height, 32);
  EXPECT_EQ(s.camera.eye, glm::vec3(0, 1, 5));
  EXPECT_EQ(s.camera.fov_y, 45.0f);
  ASSERT_EQ(s.triangle_count(), 1u);
  // (1, 0, 0) scaled by 2, rotated 90 degrees about y (x -> -z), translated.
  EXPECT_NEAR(s.positions[1].x, 1.0f, 1e-6f);
  EXPECT_NEAR(s.positions[1].y, 2.0f, 1e-6f);
  EXPECT_NEAR(s.positions[1].z, 1.0f, 1e-6f);
  EXPECT_EQ(s.materials[static_cast<size_t>(s.material[0])].name, "white");
  EXPECT_EQ(color_of(s.materials[static_cast<size_t>(s.material[0])], "specular"), glm::vec3(0.2f));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].position, glm::vec3(2, 4, 3));
  EXPECT_EQ(s.background, glm::vec3(0.1f, 0.1f, 0.15f));
}

TEST(Scene, JsonShapesOptionsAndBuiltinBase) {
  Scene s = parse_json_scene(R"({
    "builtin": "empty",
    "materials": {"m": {"diffuse": 0.5}},
    "meshes": [{"shape": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "m"},
               {"shape": "sphere", "radius": 0.5, "slices": 8, "stacks": 4},
               {"shape": "teapot", "subdivisions": 2},
               {"shape": "quad", "vertices": [[0,0,0],[1,0,0],[1,0,1],[0,0,1]]},
               {"shape": "triangle", "vertices": [[0,0,0],[1,0,0],[0,0,1]]}],
    "options": {"shadows": false, "max_depth": 3, "grid": 7, "spp": 4, "ambient": 0.2,
                "smooth_normals": false, "subgrids": 30, "grid_density": 12.5}
  })",
                             ".", "inline.json");
  EXPECT_EQ(s.triangle_count(), 12u + 2u * 8u * 3u + 64u * 4u + 2u + 1u);
  EXPECT_FALSE(s.options.shadows);
  EXPECT_EQ(s.options.max_depth, 3);
  EXPECT_EQ(s.options.grid, 7);
  EXPECT_EQ(s.options.subgrid_min, 30);
  EXPECT_EQ(s.options.grid_density, 12.5);
  EXPECT_EQ(parse_json_scene("{}", ".", "default.json").options.grid_density, kGridDensityAuto);
  EXPECT_EQ(parse_json_scene(R"({"options": {"grid_density": "auto"}})", ".", "auto.json")
                .options.grid_density,
            kGridDensityAuto);
  EXPECT_EQ(
      parse_json_scene(R"({"options": {"subgrids": "off"}})", ".", "off.json").options.subgrid_min,
      kNoSubgrids);
  // Left open by default ("auto"): the renderer chooses per backend (GridTest).
  EXPECT_EQ(parse_json_scene("{}", ".", "default.json").options.subgrid_min, kSubgridsAuto);
  EXPECT_EQ(
      parse_json_scene(R"({"options": {"subgrids": "auto"}})", ".", "a.json").options.subgrid_min,
      kSubgridsAuto);
  EXPECT_EQ(s.options.spp, 4);
  EXPECT_FLOAT_EQ(s.options.ambient, 0.2f);
  EXPECT_FALSE(s.options.smooth_normals);
  EXPECT_EQ(color_of(s.materials[static_cast<size_t>(s.material[0])], "diffuse"), glm::vec3(0.5f));
  EXPECT_TRUE(s.has_camera);  // no camera given: one framing the geometry
}

TEST(Scene, JsonMeshWithoutMaterialUsesItsMtl) {
  TempDir dir;
  dir.file("c.mtl", "newmtl green\nKd 0 1 0\n");
  dir.file("c.obj", "mtllib c.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl green\nf 1 2 3\n");
  std::string json = dir.file("s.json", R"({"meshes": [{"file": "c.obj"}]})");
  Scene s = load_json(json);
  ASSERT_EQ(s.triangle_count(), 1u);
  EXPECT_EQ(color_of(s.materials[static_cast<size_t>(s.material[0])], "diffuse"),
            glm::vec3(0, 1, 0));
}

// The scene files the project ships all load and validate.
TEST(Scene, ShippedScenesLoad) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(RILL_SCENES_DIR)) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    Scene s = load_scene(e.path().string());
    EXPECT_NO_THROW(s.validate());
    EXPECT_GT(s.triangle_count(), 0u);
    ++n;
  }
  EXPECT_GE(n, 5);
  // The Cornell box OBJ: 5 walls and 2 blocks of quads, fanned.
  Scene c = load_obj(std::string(RILL_SCENES_DIR) + "/models/cornell.obj");
  EXPECT_EQ(c.triangle_count(), 30u);
  EXPECT_EQ(c.materials.size(), 3u);
}

}  // namespace
}  // namespace rt
