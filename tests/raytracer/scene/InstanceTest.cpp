// Instances of a JSON scene (scene/AnimationJson.h, docs/scene-format.md "instances"): a pivot
// that the transform's and the keys' rotations and scales act about, a material per instance,
// prototype meshes that render only through their instances, and the errors for bad values.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "TestUtil.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {
using testing::error_of;

// Bounds of triangles [first, first + count).
struct Box {
  glm::vec3 lo{INFINITY}, hi{-INFINITY};
  glm::vec3 centre() const { return (lo + hi) * 0.5f; }
};
Box bounds(const Scene& s, size_t first, size_t count) {
  Box b;
  for (size_t i = 3 * first; i < 3 * (first + count); ++i) {
    b.lo = glm::min(b.lo, s.positions[i]);
    b.hi = glm::max(b.hi, s.positions[i]);
  }
  return b;
}

void expect_near(const glm::vec3& got, const glm::dvec3& want, double tol, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << what << " [" << k << "]";
}

// The rotations of a transform in double, as docs/scene-format.md defines them: about x, then
// y, then z (right-handed).
glm::dmat3 rotation_of(double rx, double ry, double rz) {
  const double k = 3.14159265358979323846 / 180.0;
  const double cx = std::cos(rx * k), sx = std::sin(rx * k), cy = std::cos(ry * k),
               sy = std::sin(ry * k), cz = std::cos(rz * k), sz = std::sin(rz * k);
  // Column-major: glm::dmat3(col0, col1, col2).
  const glm::dmat3 x(1, 0, 0, 0, cx, sx, 0, -sx, cx);
  const glm::dmat3 y(cy, 0, -sy, 0, 1, 0, sy, 0, cy);
  const glm::dmat3 z(cz, sz, 0, -sz, cz, 0, 0, 0, 1);
  return z * y * x;
}

// Each coordinate of a placed point is rounded to binary32 at most six times (the scale, the
// three rotations, the translation and the pivot), each time by at most half an ulp of a value
// below 32 (2^-19): 3e-6 in all, and rotations, which keep lengths, do not grow those errors.
constexpr double kPlacedTol = 4e-6;

// A box with its centre at c = (1.5, 3, 4) and half sizes h = (0.5, 1, 2), an instance of it
// turned about c by a general rotation and scale, then moved: its bounds are c + t plus or
// minus |R S| h (the box's analytic bounds), whatever the rotation.
TEST(Instances, PivotedTransformGivesTheAnalyticBounds) {
  const Scene s = parse_json_scene(R"({
    "meshes": [{"name": "b", "shape": "box", "min": [1, 2, 2], "max": [2, 4, 6], "prototype": true}],
    "instances": [
      {"mesh": "b", "pivot": [1.5, 3, 4],
       "transform": {"rotate_x": 30, "rotate_y": 40, "rotate_z": -25, "scale": [2, 1, 0.5],
                     "translate": [10, -1, 2]}},
      {"mesh": "b", "pivot": [1.5, 3, 4], "transform": {"rotate_y": 90, "translate": [10, 0, 0]}}]
  })",
                                   ".", "pivot.json");
  ASSERT_EQ(s.triangle_count(), 24u);  // the prototype's 12 are not there
  const glm::dvec3 c(1.5, 3, 4), h(0.5, 1, 2);
  {
    const glm::dmat3 m = rotation_of(30, 40, -25) * glm::dmat3(2, 0, 0, 0, 1, 0, 0, 0, 0.5);
    glm::dvec3 half(0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) half[i] += std::fabs(m[j][i]) * h[j];
    const glm::dvec3 centre = c + glm::dvec3(10, -1, 2);
    const Box b = bounds(s, 0, 12);
    expect_near(b.lo, centre - half, kPlacedTol, "general rotation, lo");
    expect_near(b.hi, centre + half, kPlacedTol, "general rotation, hi");
  }
  // 90 degrees about y: x and z swap their extents, the centre stays at c + t.
  const Box b = bounds(s, 12, 12);
  expect_near(b.lo, glm::dvec3(11.5 - 2, 3 - 1, 4 - 0.5), kPlacedTol, "90 about y, lo");
  expect_near(b.hi, glm::dvec3(11.5 + 2, 3 + 1, 4 + 0.5), kPlacedTol, "90 about y, hi");
}

// A shape that is not symmetric (the teapot) turned 180 degrees about its own bounding box's
// centre keeps that box: the centre and the extents. Without a pivot it turns about the origin.
TEST(Instances, HalfTurnAboutItsOwnCentreKeepsItsBox) {
  const std::string teapot =
      R"({"name": "t", "shape": "teapot", "subdivisions": 2, "transform": {"translate": [3, 1, -2]}})";
  const Scene alone = parse_json_scene(R"({"meshes": [)" + teapot + "]}", ".", "t.json");
  const size_t n = alone.triangle_count();
  const Box before = bounds(alone, 0, n);
  const glm::vec3 c = before.centre();
  char pivot[128];
  std::snprintf(pivot, sizeof pivot, "[%.9g, %.9g, %.9g]", c.x, c.y, c.z);
  const Scene s = parse_json_scene(R"({"meshes": [)" + teapot + R"(],
    "instances": [{"mesh": "t", "pivot": )" +
                                       pivot + R"(, "transform": {"rotate_y": 180}},
                  {"mesh": "t", "transform": {"rotate_y": 180}}]})",
                                   ".", "t.json");
  ASSERT_EQ(s.triangle_count(), 3 * n);
  const Box turned = bounds(s, n, n);
  expect_near(turned.centre(), glm::dvec3(c), kPlacedTol, "centre");
  expect_near(turned.hi - turned.lo, glm::dvec3(before.hi - before.lo), 2 * kPlacedTol, "size");
  // The spout (+x) now points to -x: the box is the same, the teapot is not.
  EXPECT_NE(std::vector<glm::vec3>(s.positions.begin() + 3 * n, s.positions.begin() + 6 * n),
            std::vector<glm::vec3>(s.positions.begin(), s.positions.begin() + 3 * n));
  // About the origin (no pivot): the centre goes to (-cx, cy, -cz).
  expect_near(bounds(s, 2 * n, n).centre(), glm::dvec3(-c.x, c.y, -c.z), kPlacedTol, "origin");
}

// "pivot": [0, 0, 0] is the default: the same bits as an instance without it.
TEST(Instances, ZeroPivotIsTheDefaultBitForBit) {
  auto scene = [](const std::string& pivot) {
    return parse_json_scene(
        R"({"meshes": [{"name": "s", "shape": "sphere", "slices": 8,
        "stacks": 4, "center": [0.3, -0.2, 0.1]}],
      "instances": [{"mesh": "s", )" +
            pivot +
            R"("transform": {"rotate_x": 33, "scale": 1.7, "translate": [-0.25, 4, 1e-3]}}]})",
        ".", "z.json");
  };
  const Scene a = scene(""), b = scene(R"("pivot": [0, 0, 0], )");
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
}

// An instance's "material" goes on every face of its copy, whatever materials the mesh had
// (an OBJ's two MTL materials); the mesh and the other copies keep theirs, and the triangles
// and their order (the primitive ids) are as without it.
TEST(Instances, MaterialReplacesEveryFaceOfTheCopy) {
  testing::TempDir dir;
  dir.file("two.mtl", "newmtl a\nKd 0.1 0.2 0.3\nnewmtl b\nKd 0.4 0.5 0.6\n");
  dir.file("two.obj",
           "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl a\nf 1 2 3\nusemtl b\n"
           "f 1 3 4\n");
  const std::string base = R"({"materials": {"red": {"diffuse": [1, 0, 0]}},
    "meshes": [{"name": "m", "file": "two.obj"}], "instances": [
      {"mesh": "m", "transform": {"translate": [2, 0, 0]}},
      {"mesh": "m", "transform": {"translate": [4, 0, 0]})";
  const Scene plain = load_json(dir.file("plain.json", base + "}]}"));
  const Scene red = load_json(dir.file("red.json", base + R"(, "material": "red"}]})"));
  ASSERT_EQ(red.triangle_count(), 6u);
  EXPECT_EQ(red.positions, plain.positions);
  for (size_t t = 0; t < 4; ++t) EXPECT_EQ(red.material[t], plain.material[t]) << t;
  EXPECT_EQ(red.materials[static_cast<size_t>(red.material[0])].name, "a");
  EXPECT_EQ(red.materials[static_cast<size_t>(red.material[1])].name, "b");
  for (size_t t = 4; t < 6; ++t) {
    const Material& m = red.materials[static_cast<size_t>(red.material[t])];
    EXPECT_EQ(m.name, "red") << t;
    EXPECT_EQ(m.params.at("diffuse").color, glm::vec3(1, 0, 0));
  }
}

// A prototype is loaded for its instances and then taken out: the other meshes' triangles
// close up over it (their primitive ids are as if it were not in "meshes"), and the copies
// come after them as before.
TEST(Instances, PrototypesRenderOnlyThroughTheirInstances) {
  auto scene = [](const std::string& flag) {
    return parse_json_scene(R"({"meshes": [
        {"shape": "box", "min": [-4, -1, -4], "max": [4, -0.5, 4]},
        {"name": "ball", "shape": "sphere", "radius": 0.5, "slices": 6, "stacks": 3)" +
                                flag + R"(},
        {"shape": "quad", "vertices": [[-1, 0, -3], [1, 0, -3], [1, 2, -3], [-1, 2, -3]],
         "animate": {"keys": [{"time": 0}, {"time": 1, "translate": [0, 1, 0]}]}}],
      "instances": [{"mesh": "ball", "transform": {"translate": [1, 0, 0]}},
                    {"mesh": "ball", "transform": {"translate": [-1, 0, 0]}}]})",
                            ".", "p.json");
  };
  const Scene plain = scene(""), proto = scene(R"(, "prototype": true)");
  const size_t ball = 6 * (2 * 3 - 2);  // slices * (2 stacks - 2)
  ASSERT_EQ(plain.triangle_count(), 12 + ball + 2 + 2 * ball);
  ASSERT_EQ(proto.triangle_count(), plain.triangle_count() - ball);
  // proto's triangles are plain's without the ball's own [12, 12 + ball).
  auto without_ball = [&](const auto& v) {
    std::decay_t<decltype(v)> w(v.begin(), v.begin() + 3 * 12);
    w.insert(w.end(), v.begin() + 3 * (12 + ball), v.end());
    return w;
  };
  EXPECT_EQ(proto.positions, without_ball(plain.positions));
  EXPECT_EQ(proto.normals, without_ball(plain.normals));
  EXPECT_EQ(proto.texcoords, without_ball(plain.texcoords));
  EXPECT_TRUE(proto.warnings.empty());
  // The moving quad after the prototype is renumbered with its triangles.
  ASSERT_EQ(proto.animation.objects.size(), 1u);
  EXPECT_EQ(plain.animation.objects[0].first, 12 + ball);
  EXPECT_EQ(proto.animation.objects[0].first, 12u);
  EXPECT_EQ(bake(proto, 0.5).positions, without_ball(bake(plain, 0.5).positions));
  // "prototype": false is an ordinary mesh.
  EXPECT_EQ(scene(R"(, "prototype": false)").positions, plain.positions);
}

TEST(Instances, APrototypeWithoutInstancesIsAWarningNamingIt) {
  const Scene s = parse_json_scene(R"({"meshes": [
      {"name": "unused", "shape": "box", "prototype": true},
      {"shape": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]}]})",
                                   ".", "w.json");
  EXPECT_EQ(s.triangle_count(), 1u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_EQ(s.warnings[0],
            "w.json: meshes[0]: prototype 'unused' has no instances, so nothing of it is rendered");
}

// The keys of an instance with a pivot turn and scale it about the pivot where its transform
// put it: a half turn keeps its box's centre, a quarter turn swaps its x and z extents.
TEST(Instances, AnimationKeysActAboutThePivot) {
  const Scene s = parse_json_scene(R"({
    "meshes": [{"name": "b", "shape": "box", "min": [1, 2, 2], "max": [2, 4, 6], "prototype": true}],
    "instances": [{"mesh": "b", "pivot": [1.5, 3, 4], "transform": {"translate": [10, 0, 0]},
      "animate": {"keys": [{"time": 0},
                           {"time": 2, "rotate": {"axis": [0, 1, 0], "degrees": 180}, "scale": 2}]}}]
  })",
                                   ".", "a.json");
  ASSERT_EQ(s.animation.objects.size(), 1u);
  EXPECT_EQ(s.animation.objects[0].first, 0u);
  EXPECT_EQ(s.animation.objects[0].pivot, glm::dvec3(11.5, 3, 4));
  // t = 1: 90 degrees and scale 1.5 about (11.5, 3, 4); t = 2: 180 degrees and scale 2.
  // Posing computes in double and rounds once (half an ulp of 16: 1e-6).
  const Box quarter = bounds(bake(s, 1.0), 0, 12);
  expect_near(quarter.lo, glm::dvec3(11.5 - 3, 3 - 1.5, 4 - 0.75), 2e-6, "t = 1, lo");
  expect_near(quarter.hi, glm::dvec3(11.5 + 3, 3 + 1.5, 4 + 0.75), 2e-6, "t = 1, hi");
  const Box half = bounds(bake(s, 2.0), 0, 12);
  expect_near(half.lo, glm::dvec3(11.5 - 1, 3 - 2, 4 - 4), 2e-6, "t = 2, lo");
  expect_near(half.hi, glm::dvec3(11.5 + 1, 3 + 2, 4 + 4), 2e-6, "t = 2, hi");
  // Without a pivot the keys act about the scene's origin, as before pivots.
  const Scene origin = parse_json_scene(R"({
    "meshes": [{"name": "b", "shape": "box", "min": [1, 2, 2], "max": [2, 4, 6], "prototype": true}],
    "instances": [{"mesh": "b", "transform": {"translate": [10, 0, 0]},
      "animate": {"keys": [{"time": 0}, {"time": 2, "rotate": {"axis": [0, 1, 0], "degrees": 180}}]}}]
  })",
                                        ".", "a.json");
  EXPECT_EQ(origin.animation.objects[0].pivot, glm::dvec3(0.0));
  expect_near(bounds(bake(origin, 2.0), 0, 12).centre(), glm::dvec3(-11.5, 3, -4), 2e-6, "origin");
}

// A prototype that is an OBJ sequence: its copies deform, and it is gone with its animation.
TEST(Instances, PrototypeSequencesDeformThroughTheirInstances) {
  testing::TempDir dir;
  for (int k = 0; k < 2; ++k)
    dir.file("w-" + std::to_string(k) + ".obj", testing::wave_obj(0.5f * static_cast<float>(k)));
  const Scene s = load_json(dir.file("w.json", R"({"animation": {"end": 1, "fps": 1},
    "meshes": [{"name": "w", "file": "w-%d.obj", "sequence": {"last": 1}, "prototype": true}],
    "instances": [{"mesh": "w", "pivot": [1, 0.5, 0], "transform": {"translate": [0, 2, 0]}}]})"));
  ASSERT_EQ(s.triangle_count(), 4u);
  ASSERT_EQ(s.animation.objects.size(), 1u);
  EXPECT_EQ(s.animation.objects[0].first, 0u);
  EXPECT_EQ(s.animation.objects[0].shapes.size(), 2u);
  float top = -1.0f;
  for (const glm::vec3& p : bake(s, 1.0).positions) top = std::max(top, p.z);
  EXPECT_EQ(top, 0.5f);  // file 1's middle vertex
}

TEST(Instances, BadValuesAreErrorsNamingTheKey) {
  auto err = [](const std::string& instance, const std::string& more = "") {
    return error_of([&] {
      parse_json_scene(
          R"({"materials": {"red": {"diffuse": [1, 0, 0]}, "blue": {"diffuse": [0, 0, 1]}},
        "meshes": [{"name": "b", "shape": "box")" +
              more + R"(}], "instances": [)" + instance + "]}",
          ".", "bad.json");
    });
  };
  EXPECT_EQ(err(R"({"mesh": "b", "material": "green"})"),
            "bad.json: instances[0].material: unknown material 'green' (materials: blue, red)");
  EXPECT_EQ(err(R"({"mesh": "b", "material": 3})"),
            "bad.json: instances[0].material must be a material name");
  EXPECT_EQ(err(R"({"mesh": "b", "pivot": [1, 2]})"),
            "bad.json: instances[0].pivot must be an array of 3 numbers");
  EXPECT_EQ(err(R"({"mesh": "b", "pivot": "centre"})"),
            "bad.json: instances[0].pivot must be an array of 3 numbers");
  EXPECT_EQ(err(R"({"mesh": "b", "pivot": [0, 1e39, 0]})"),
            "bad.json: instances[0].pivot[1] must be a finite number");
  EXPECT_EQ(err(R"({"mesh": "b", "pivot": [0, null, 0]})"),
            "bad.json: instances[0].pivot[1] must be a number");
  EXPECT_EQ(err(R"({"mesh": "b"})", R"(, "prototype": "yes")"),
            "bad.json: meshes[0].prototype must be true or false");
  EXPECT_EQ(err(R"({"mesh": "b"})", R"(, "prototype": true, "animate": {"keys": [{"time": 0}]})"),
            "bad.json: meshes[0].animate: a prototype is not rendered itself; animate its "
            "instances");
  EXPECT_EQ(error_of([] {
              parse_json_scene(R"({"meshes": [{"shape": "box", "prototype": true}]})", ".",
                               "bad.json");
            }),
            "bad.json: meshes[0]: a prototype needs a \"name\", for instances to copy it");
  EXPECT_EQ(err(R"({"mesh": "b", "pivot": [0, 0, 0], "spin": 1})"),
            "bad.json: instances[0]: unknown key 'spin' (mesh, name, transform, pivot, material, "
            "animate)");
  // A material named by a file that defines none.
  EXPECT_EQ(error_of([] {
              parse_json_scene(R"({"meshes": [{"name": "b", "shape": "box"}],
                                   "instances": [{"mesh": "b", "material": "red"}]})",
                               ".", "bad.json");
            }),
            "bad.json: instances[0].material: unknown material 'red' (the file defines no "
            "materials)");
}

}  // namespace
}  // namespace rt
