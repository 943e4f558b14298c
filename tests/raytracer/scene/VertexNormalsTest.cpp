// Vertex normals computed for OBJ files without `vn` (rill/rt/scene/VertexNormals.h): close to
// a sphere's true normals, hard edges kept at the crease angle, `s off` faces flat, and files
// with `vn` keep their own.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "TestUtil.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/scene/VertexNormals.h"

namespace rt {
namespace {

using testing::TempDir;

// A UV sphere of radius 1 as OBJ text: one vertex per pole, quads between the rings,
// triangles at the poles, counter-clockwise seen from outside; `vn` lines when asked.
std::string uv_sphere_obj(int slices, int stacks, bool with_vn) {
  std::ostringstream o;
  o.precision(9);
  auto vertex = [&](double theta, double phi) {
    const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta),
                 z = -std::sin(theta) * std::sin(phi);
    o << "v " << x << " " << y << " " << z << "\n";
    if (with_vn) o << "vn " << x << " " << y << " " << z << "\n";
  };
  vertex(0, 0);  // 1: north pole
  for (int i = 1; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) vertex(M_PI * i / stacks, 2 * M_PI * j / slices);
  vertex(M_PI, 0);  // south pole
  const int south = 2 + (stacks - 1) * slices;
  auto id = [&](int ring, int j) { return 2 + (ring - 1) * slices + (j % slices); };
  auto ref = [&](int v) {
    return with_vn ? std::to_string(v) + "//" + std::to_string(v) : std::to_string(v);
  };
  for (int j = 0; j < slices; ++j)
    o << "f " << ref(1) << " " << ref(id(1, j)) << " " << ref(id(1, j + 1)) << "\n";
  for (int i = 1; i + 1 < stacks; ++i)
    for (int j = 0; j < slices; ++j)
      o << "f " << ref(id(i, j)) << " " << ref(id(i + 1, j)) << " " << ref(id(i + 1, j + 1)) << " "
        << ref(id(i, j + 1)) << "\n";
  for (int j = 0; j < slices; ++j)
    o << "f " << ref(id(stacks - 1, j)) << " " << ref(south) << " " << ref(id(stacks - 1, j + 1))
      << "\n";
  return o.str();
}

// The largest angle (degrees) between a corner's normal and the sphere's (its position).
double worst_normal_error_degrees(const Scene& s) {
  double worst = 0;
  for (size_t c = 0; c < s.positions.size(); ++c) {
    const double d = glm::dot(glm::dvec3(glm::normalize(s.normals[c])),
                              glm::normalize(glm::dvec3(s.positions[c])));
    worst = std::max(worst, std::acos(std::min(d, 1.0)) * 180 / M_PI);
  }
  return worst;
}

TEST(VertexNormals, SphereWithoutVnGetsNormalsCloseToTheTrueOnes) {
  TempDir dir;
  // 24 x 12: faces meet at 15 degrees, under the default crease angle (60).
  const Scene s = load_obj(dir.file("ball.obj", uv_sphere_obj(24, 12, false)));
  ASSERT_EQ(s.normals.size(), s.positions.size());
  // A face normal is up to ~10.6 degrees from the true normal at the corners (half the
  // diagonal of a 15 x 15 degree cell); the angle-weighted mean of the ring around a vertex
  // is within 1 degree (the rings above and below a vertex differ in width; measured 0.60,
  // recorded as the property worst_degrees).
  const double worst = worst_normal_error_degrees(s);
  RecordProperty("worst_degrees", std::to_string(worst));
  EXPECT_LT(worst, 1.0);
  for (const glm::vec3& n : s.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(VertexNormals, FileWithVnKeepsItsOwn) {
  TempDir dir;
  // Normals tilted on purpose: what the file says is what the scene gets.
  std::string text = uv_sphere_obj(8, 4, true), tilted;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    tilted += (line.rfind("vn ", 0) == 0 ? std::string("vn 0 0 1") : line) + "\n";
  const Scene s = load_obj(dir.file("own.obj", tilted));
  ASSERT_EQ(s.normals.size(), s.positions.size());
  for (const glm::vec3& n : s.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

const char* kHardEdgedCube =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 4 8 7 3\nf 1 5 8 4\nf 2 3 7 6\n";

TEST(VertexNormals, CubeKeepsFlatFacesUnderTheCreaseAngle) {
  TempDir dir;
  const std::string obj = dir.file("cube.obj", kHardEdgedCube);
  // 90-degree edges, over the default 60: every triangle flat, so no normals at all (the
  // scene, and its kernel, as before smoothing existed).
  const Scene flat = load_obj(obj);
  EXPECT_EQ(flat.triangle_count(), 12u);
  EXPECT_TRUE(flat.normals.empty());
  // A crease angle of 180 smooths everything: each corner points along its diagonal.
  ObjLoadOptions all;
  all.crease_degrees = 180;
  const Scene round = load_obj(obj, all);
  ASSERT_EQ(round.normals.size(), round.positions.size());
  for (size_t c = 0; c < round.positions.size(); ++c)
    EXPECT_LT(glm::length(round.normals[c] - glm::normalize(round.positions[c])), 1e-6f) << c;
  // Smoothing off: flat again.
  ObjLoadOptions off;
  off.smooth = false;
  EXPECT_TRUE(load_obj(obj, off).normals.empty());
}

TEST(VertexNormals, SmoothingGroupOffKeepsAFaceFlat) {
  TempDir dir;
  // Two quads folded by 20 degrees along x = 0, well under the crease angle.
  const std::string v = "v -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 1 0 0.364\nv 1 1 0.364\n";
  const Scene smooth = load_obj(dir.file("s1.obj", v + "s 1\nf 1 2 3 4\nf 2 5 6 3\n"));
  ASSERT_FALSE(smooth.normals.empty());
  EXPECT_NE(smooth.normals[1], smooth.normals[0]);  // the fold's corner is bent
  const Scene off = load_obj(dir.file("off.obj", v + "s off\nf 1 2 3 4\nf 2 5 6 3\n"));
  EXPECT_TRUE(off.normals.empty());
  // Different groups never share either.
  const Scene two = load_obj(dir.file("s12.obj", v + "s 1\nf 1 2 3 4\ns 2\nf 2 5 6 3\n"));
  EXPECT_TRUE(two.normals.empty());
}

TEST(VertexNormals, JsonSmoothKeySetsTheCreaseAngleOrTurnsItOff) {
  TempDir dir;
  dir.file("cube.obj", kHardEdgedCube);
  auto load = [&](const std::string& smooth) {
    return load_scene(
        dir.file("s.json", "{\"meshes\": [{\"file\": \"cube.obj\", \"smooth\": " + smooth + "}]}"));
  };
  EXPECT_TRUE(load("true").normals.empty());  // 60: the cube's edges stay hard
  EXPECT_FALSE(load("120").normals.empty());  // 120 > 90: smoothed
  EXPECT_TRUE(load("false").normals.empty());
  EXPECT_THROW(load("\"yes\""), SceneError);
  EXPECT_THROW(load("200"), SceneError);
}

// Faces of a file that give `vn` keep theirs; the faces that give none get computed normals,
// shared with their neighbours whether those have `vn` or not.
TEST(VertexNormals, FacesWithoutVnInAFileWithSomeGetComputedOnes) {
  TempDir dir;
  // Two quads folded by 20 degrees along x = 0; the first gives vn (along y, on purpose).
  const Scene s =
      load_obj(dir.file("partial.obj",
                        "v -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 1 0 0.364\nv 1 1 0.364\n"
                        "vn 0 1 0\nf 1//1 2//1 3//1 4//1\nf 2 5 6 3\n"));
  ASSERT_EQ(s.triangle_count(), 4u);
  ASSERT_EQ(s.normals.size(), 12u);
  for (int c = 0; c < 6; ++c) EXPECT_EQ(s.normals[c], glm::vec3(0, 1, 0)) << c;
  // The second quad's corners on the fold (vertices 2 and 3) bend towards the first's face
  // normal (0, 0, 1); its outer corners keep its own face normal.
  const glm::vec3 own = glm::normalize(glm::vec3(-0.364f, 0, 1));
  for (int c = 6; c < 12; ++c) {
    const bool on_fold = s.positions[c].x == 0.0f;
    EXPECT_NEAR(glm::length(s.normals[c]), 1.0f, 1e-6f) << c;
    if (on_fold)
      EXPECT_GT(glm::dot(s.normals[c], glm::vec3(0, 0, 1)), glm::dot(own, glm::vec3(0, 0, 1))) << c;
    else
      EXPECT_LT(glm::length(s.normals[c] - own), 1e-6f) << c;
  }
}

// The three weightings against a normal computed here from the definitions: at a vertex shared
// by a small face with a wide angle and a large face with a narrow one, within the crease angle.
TEST(VertexNormals, WeightingsByAngleAreaAndBoth) {
  // Face A: normal +z, area 0.5, angle 90 degrees at the origin. Face B: tilted 30 degrees
  // about x, long and narrow at the origin.
  const double c30 = std::cos(M_PI / 6), s30 = std::sin(M_PI / 6);
  const glm::vec3 positions[6] = {{0, 0, 0},
                                  {1, 0, 0},
                                  {0, 1, 0},
                                  {0, 0, 0},
                                  {-0.5f, float(-4 * c30), float(-4 * s30)},
                                  {0.5f, float(-4 * c30), float(-4 * s30)}};
  const int32_t vertex[6] = {0, 1, 2, 0, 3, 4};
  auto expected = [&](NormalWeighting w) {
    glm::dvec3 sum(0.0);
    for (int t = 0; t < 2; ++t) {
      const glm::dvec3 p0(positions[3 * t]), p1(positions[3 * t + 1]), p2(positions[3 * t + 2]);
      const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
      const double area = glm::length(n) / 2;
      const double angle = std::acos(glm::dot(glm::normalize(p1 - p0), glm::normalize(p2 - p0)));
      const double weight = w == NormalWeighting::Angle  ? angle
                            : w == NormalWeighting::Area ? area
                                                         : area * angle;
      sum += weight * glm::normalize(n);
    }
    return glm::vec3(glm::normalize(sum));
  };
  glm::vec3 at_origin[3];
  int i = 0;
  for (NormalWeighting w :
       {NormalWeighting::Angle, NormalWeighting::Area, NormalWeighting::AreaAngle}) {
    const auto n = vertex_normals({positions, vertex, {}}, kDefaultCreaseDegrees, w);
    ASSERT_EQ(n.size(), 6u);
    EXPECT_EQ(n[0], n[3]);  // both faces' corners at the shared vertex
    EXPECT_LT(glm::length(n[0] - expected(w)), 1e-6f) << i;
    at_origin[i++] = n[0];
  }
  // The tilted narrow face (area 2, angle 14 degrees) counts least by angle and most by area;
  // the product (0.79 against 0.50) lies between: the normal leans from +z accordingly.
  EXPECT_GT(at_origin[0].z, at_origin[2].z);
  EXPECT_GT(at_origin[2].z, at_origin[1].z);
  EXPECT_EQ(parse_normal_weighting("area_angle"), NormalWeighting::AreaAngle);
  EXPECT_THROW(parse_normal_weighting("areas"), std::invalid_argument);
}

TEST(VertexNormals, JsonNormalWeightingKey) {
  TempDir dir;
  dir.file("fold.obj",
           "v -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 3 0 1.092\nv 3 1 1.092\n"
           "f 1 2 3 4\nf 2 5 6 3\n");
  auto load = [&](const std::string& w) {
    return load_scene(dir.file(
        "w.json", "{\"meshes\": [{\"file\": \"fold.obj\", \"normal_weighting\": " + w + "}]}"));
  };
  // The faces have equal angles at the fold, unequal areas: angle and area weights differ.
  const Scene angle = load("\"angle\""), area = load("\"area\"");
  ASSERT_EQ(angle.normals.size(), 12u);
  EXPECT_NE(angle.normals[1], area.normals[1]);
  EXPECT_THROW(load("\"areas\""), SceneError);
  EXPECT_THROW(load("1"), SceneError);
}

}  // namespace
}  // namespace rt
