// The boxes that hold a grid's triangles (accel/OccupiedBoxes.h): every point of every
// triangle the grid holds lies in one of them, they are fewer than asked for, and they are
// tighter than the grid's box.
#include <gtest/gtest.h>

#include <random>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/OccupiedBoxes.h"

namespace rt {
namespace {

bool inside(const glm::vec3& p, const std::vector<Aabb>& boxes) {
  for (const Aabb& b : boxes)
    if (p.x >= b.lo.x && p.y >= b.lo.y && p.z >= b.lo.z && p.x <= b.hi.x && p.y <= b.hi.y &&
        p.z <= b.hi.z)
      return true;
  return false;
}

double volume(const Aabb& b) {
  const glm::dvec3 e = glm::dvec3(b.hi) - glm::dvec3(b.lo);
  return e.x * e.y * e.z;
}

// Vertices, points on the edges and inside, as float32: the boxes are cut on float faces, so
// a point exactly on one belongs to the boxes on both sides.
std::vector<glm::vec3> points_of(const Scene& s, size_t t, std::mt19937& rng) {
  const glm::vec3 a = s.positions[t * 3], b = s.positions[t * 3 + 1], c = s.positions[t * 3 + 2];
  std::vector<glm::vec3> pts{a, b, c};
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int k = 0; k < 30; ++k) {
    float x = u(rng), y = u(rng);
    if (x + y > 1.0f) x = 1.0f - x, y = 1.0f - y;
    pts.push_back(a + (b - a) * x + (c - a) * y);
    pts.push_back(a + (b - a) * x);  // on edges
    pts.push_back(b + (c - b) * y);
  }
  return pts;
}

TEST(OccupiedBoxes, HoldEveryPointOfEveryTriangle) {
  std::mt19937 rng(5);
  // Random triangles of every size, some spanning the scene, and the thesis scenes.
  Scene random;
  const int mat = random.add_material(Material{});
  std::uniform_real_distribution<float> U(-5.0f, 5.0f), S(0.01f, 3.0f);
  for (int t = 0; t < 300; ++t) {
    const glm::vec3 c(U(rng), U(rng), U(rng));
    const float r = t % 50 == 0 ? 8.0f : S(rng);
    random.add_triangle(c + glm::vec3(r, 0, 0), c + glm::vec3(0, r * 0.7f, -r * 0.2f),
                        c + glm::vec3(-r * 0.3f, 0, r), mat);
  }
  for (const Scene& s : {random, builtin_scene("thesis-a"), builtin_scene("thesis-b")}) {
    const Grid g = build_grid(s, 0);
    for (int max_boxes : {1, 7, 64, kMaxOccupiedBoxes}) {
      const std::vector<Aabb> boxes = occupied_boxes(s, g, max_boxes);
      ASSERT_FALSE(boxes.empty());
      EXPECT_LE(boxes.size(), static_cast<size_t>(max_boxes)) << s.name;
      for (size_t t = 0; t < s.triangle_count(); ++t)
        for (const glm::vec3& p : points_of(s, t, rng))
          ASSERT_TRUE(inside(p, boxes)) << s.name << ", " << max_boxes << " boxes: triangle " << t;
    }
  }
}

// What they are for: thesis A's three boxes leave most of their grid's box empty.
TEST(OccupiedBoxes, AreTighterThanTheGridsBox) {
  const Scene s = builtin_scene("thesis-a");
  const Grid g = build_grid(s, 0);
  const std::vector<Aabb> boxes = occupied_boxes(s, g);
  double sum = 0;
  for (const Aabb& b : boxes) sum += volume(b);
  EXPECT_LT(sum, 0.5 * volume(Aabb{g.lo, g.hi}));
  EXPECT_GT(boxes.size(), 8u);
}

TEST(OccupiedBoxes, EmptyGridsAndBudgets) {
  Scene empty;
  EXPECT_TRUE(occupied_boxes(empty, build_grid(empty, 0)).empty());
  // Past the visit budget: the grid's box alone, which holds everything.
  const Scene s = builtin_scene("thesis-a");
  const Grid g = build_grid(s, 0);
  const std::vector<Aabb> whole = occupied_boxes(s, g, kMaxOccupiedBoxes, 10);
  ASSERT_EQ(whole.size(), 1u);
  EXPECT_EQ(whole[0].lo, g.lo);
  EXPECT_EQ(whole[0].hi, g.hi);
}

}  // namespace
}  // namespace rt
