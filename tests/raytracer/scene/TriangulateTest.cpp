// Polygon triangulation (rill/rt/scene/Triangulate.h) and the OBJ loader's use of it: concave
// faces cover exactly their area, convex ones keep the fan's primitive ids, and polygons with
// no inside are fanned with a warning naming file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "TestUtil.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/scene/Triangulate.h"

namespace rt {
namespace {

using testing::TempDir;

// Signed area of the triangle's projection on z (positive: counter-clockwise seen from +z).
double signed_area_z(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  return 0.5 *
         ((double(b.x) - a.x) * (double(c.y) - a.y) - (double(b.y) - a.y) * (double(c.x) - a.x));
}

bool triangle_covers(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
                     const glm::vec3& p) {
  return signed_area_z(a, b, p) >= 0 && signed_area_z(b, c, p) >= 0 && signed_area_z(c, a, p) >= 0;
}

// The L: a 2 x 2 square without its top right quarter; area 3, the notch at (1.5, 1.5).
const char* kLShapedHexagon = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\n";

TEST(Triangulate, LShapedHexagonCoversTheLAndNotTheNotch) {
  TempDir dir;
  const std::string obj = dir.file("l.obj", std::string(kLShapedHexagon) + "f 1 2 3 4 5 6\n");
  const Scene s = load_obj(obj);
  ASSERT_EQ(s.triangle_count(), 4u);  // n - 2, as a fan would have
  double area = 0;
  for (size_t t = 0; t < 4; ++t) {
    const glm::vec3* p = &s.positions[3 * t];
    const double a = signed_area_z(p[0], p[1], p[2]);
    EXPECT_GT(a, 0) << "triangle " << t << " keeps the face's winding";
    area += a;
    EXPECT_FALSE(triangle_covers(p[0], p[1], p[2], glm::vec3(1.5f, 1.5f, 0))) << "triangle " << t;
  }
  EXPECT_DOUBLE_EQ(area, 3.0);  // the L's area: the triangles neither overlap nor miss any
  EXPECT_TRUE(s.warnings.empty());
}

// Convex faces keep the fan (v0, vk, vk+1), so their ids do not change, also around and after
// a concave face (which has n - 2 triangles like its fan): ids are per face, in file order.
TEST(Triangulate, ConvexFacesKeepTheirFanIdsAroundAConcaveOne) {
  TempDir dir;
  const std::string obj =
      dir.file("mix.obj", std::string(kLShapedHexagon) +
                              "v 5 0 0\nv 6 0 0.1\nv 6 1 0\nv 5 1 0.1\n"  // non-planar convex quad
                              "f 7 8 9 10\nf 1 2 3 4 5 6\nf 7 8 9 10\n");
  const Scene s = load_obj(obj);
  ASSERT_EQ(s.triangle_count(), 2u + 4u + 2u);
  const glm::vec3 q[4] = {{5, 0, 0}, {6, 0, 0.1f}, {6, 1, 0}, {5, 1, 0.1f}};
  for (size_t first : {size_t{0}, size_t{6}}) {
    const glm::vec3 fan[6] = {q[0], q[1], q[2], q[0], q[2], q[3]};
    for (size_t k = 0; k < 6; ++k) EXPECT_EQ(s.positions[3 * first + k], fan[k]) << first;
  }
}

TEST(Triangulate, ConcaveFacesInAnyPlaneAndWindingCoverTheirArea) {
  // The L turned into an oblique plane, clockwise and counter-clockwise, and bent a little out
  // of its plane: every triangle faces the way the polygon's winding does, and their areas
  // projected onto the plane add up to the L's, so they neither overlap nor leave a gap.
  const glm::vec3 u = glm::normalize(glm::vec3(1, 2, 0.5f));
  const glm::vec3 v = glm::normalize(glm::cross(glm::vec3(0.3f, -0.2f, 1), u));
  const glm::vec3 w = glm::cross(u, v);
  const glm::vec2 l[6] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (bool reversed : {false, true})
    for (float bend : {0.0f, 0.01f}) {
      std::vector<glm::vec3> poly;
      for (int i = 0; i < 6; ++i) {
        const glm::vec2 p = l[reversed ? 5 - i : i];
        poly.push_back(p.x * u + p.y * v + (i % 2 ? bend : -bend) * w);
      }
      const Triangulation t = triangulate(poly);
      EXPECT_EQ(t.shape, PolygonShape::Ok);
      ASSERT_EQ(t.triangles.size(), 4u);
      double area = 0;
      for (const auto& tri : t.triangles) {
        const glm::dvec3 a(poly[tri[0]]), b(poly[tri[1]]), c(poly[tri[2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        const double projected = 0.5 * glm::dot(n, glm::dvec3(w)) * (reversed ? -1 : 1);
        EXPECT_GT(projected, 0);
        area += projected;
      }
      EXPECT_NEAR(area, 3.0, 1e-5) << reversed << " " << bend;
    }
}

// Random star-shaped polygons (a random radius at each of n equal angles: simple, and mostly
// concave): each is cut, every triangle turns the polygon's way, and the triangles' areas add
// up to the polygon's (shoelace formula), so none overlaps another or sticks out.
TEST(Triangulate, RandomStarShapedPolygonsAreCutExactly) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> radius(0.2, 1);
  for (int it = 0; it < 2000; ++it) {
    const size_t n = 4 + rng() % 40;
    std::vector<glm::vec3> p(n);
    for (size_t i = 0; i < n; ++i) {
      const double a = 2 * M_PI * double(i) / double(n), r = radius(rng);
      p[i] = glm::vec3(float(r * std::cos(a)), float(r * std::sin(a)), 0.0f);
    }
    double area = 0;
    for (size_t i = 0; i < n; ++i) {
      const glm::dvec3 a(p[i]), b(p[(i + 1) % n]);
      area += 0.5 * (a.x * b.y - a.y * b.x);
    }
    const Triangulation t = triangulate(p);
    ASSERT_EQ(t.shape, PolygonShape::Ok) << "polygon " << it;
    ASSERT_EQ(t.triangles.size(), n - 2);
    double sum = 0;
    for (const auto& tri : t.triangles) {
      const double a = signed_area_z(p[tri[0]], p[tri[1]], p[tri[2]]);
      EXPECT_GE(a, 0) << "polygon " << it;
      sum += a;
    }
    EXPECT_NEAR(sum, area, 1e-12) << "polygon " << it;
  }
}

TEST(Triangulate, PolygonsWithNoInsideAreFannedWithAWarning) {
  TempDir dir;
  const std::string obj =
      dir.file("bad.obj",
               "v 0 0 0\nv 2 2 0\nv 2 0 0\nv 0 1 0\nv 4 4 0\n"
               "f 1 2 3 4\n"  // line 6: a bow tie (lobes of unequal area), its edges cross
               "f 1 2 5 2\n"  // line 7: all on one line, no area
               "f 1 3 2\n");  // a triangle: never a warning
  const Scene s = load_obj(obj);
  EXPECT_EQ(s.triangle_count(), 2u + 2u + 1u);  // fanned: the ids after them do not shift
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_NE(s.warnings[0].find(obj + ":6: a polygon of 4 vertices"), std::string::npos)
      << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("its edges cross"), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[1].find(obj + ":7:"), std::string::npos) << s.warnings[1];
  EXPECT_NE(s.warnings[1].find("no area"), std::string::npos) << s.warnings[1];
}

TEST(Triangulate, PentagramIsSelfIntersectingNotConvex) {
  std::vector<glm::vec3> star;
  for (int i = 0; i < 5; ++i) {
    const double a = 2 * M_PI * (2 * i) / 5;
    star.emplace_back(std::cos(a), std::sin(a), 0);
  }
  EXPECT_EQ(triangulate(star).shape, PolygonShape::SelfIntersecting);
}

}  // namespace
}  // namespace rt
