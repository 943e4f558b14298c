// The moving triangles' BVH (accel/Bvh.h), on the host: its layout (depth-first, skip
// indices, every triangle in one leaf), boxes that hold their triangles with the padding,
// refits that keep the tree and fall back when triangles come or go.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <tbb/global_control.h>

#include "TestUtil.h"
#include "rill/rt/accel/Bvh.h"
#include "rill/rt/scene/Pose.h"

namespace rt {
namespace {

// n random small triangles in a box, all of them one animated object.
Scene random_scene(int n, unsigned seed) {
  Scene s;
  s.add_material(Material{});
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> at(-10.0f, 10.0f), off(-0.5f, 0.5f);
  for (int i = 0; i < n; ++i) {
    const glm::vec3 c(at(rng), at(rng), at(rng));
    s.add_triangle(c + glm::vec3(off(rng), off(rng), off(rng)),
                   c + glm::vec3(off(rng), off(rng), off(rng)),
                   c + glm::vec3(off(rng), off(rng), off(rng)), 0);
  }
  AnimatedObject o;
  o.name = "all";
  o.count = static_cast<size_t>(n);
  PoseKey a, b;
  b.time = 1.0;
  b.pose.translate = glm::dvec3(3.0, 0.0, -1.0);
  b.pose.rotation = glm::angleAxis(glm::radians(40.0), glm::normalize(glm::dvec3(1, 2, 3)));
  o.track.keys = {a, b};
  s.animation.objects.push_back(o);
  s.animation.time = TimeRange{0.0, 1.0, 10.0};
  return s;
}

bool inside(const BvhNode& n, const glm::vec3& p) {
  return glm::all(glm::greaterThanEqual(p, n.lo)) && glm::all(glm::lessThanEqual(p, n.hi));
}

// Depth-first layout: skips point past the subtree, a node's children nest inside it, every
// triangle is in exactly one leaf, and each box holds what is below it.
void check_tree(const Bvh& b, const Scene& s, const std::vector<int32_t>& ids) {
  ASSERT_FALSE(b.empty());
  EXPECT_EQ(b.nodes[0].skip, static_cast<int32_t>(b.nodes.size()));
  std::vector<int32_t> seen;
  for (size_t i = 0; i < b.nodes.size(); ++i) {
    const BvhNode& n = b.nodes[i];
    ASSERT_GT(n.skip, static_cast<int32_t>(i));
    ASSERT_LE(n.skip, static_cast<int32_t>(b.nodes.size()));
    if (n.count > 0) {
      EXPECT_EQ(n.skip, static_cast<int32_t>(i + 1)) << "a leaf's subtree is itself";
      EXPECT_LE(n.count, kBvhLeafMax);
      for (int32_t k = 0; k < n.count; ++k) {
        const int32_t t = b.tris[static_cast<size_t>(n.first + k)];
        seen.push_back(t);
        for (int v = 0; v < 3; ++v)
          EXPECT_TRUE(inside(n, s.positions[3 * static_cast<size_t>(t) + v]))
              << "triangle " << t << " outside leaf " << i;
      }
    } else {
      const BvhNode& left = b.nodes[i + 1];
      ASSERT_LT(left.skip, n.skip) << "node " << i << " has two children";
      const BvhNode& right = b.nodes[static_cast<size_t>(left.skip)];
      EXPECT_EQ(right.skip, n.skip);
      for (const BvhNode* c : {&left, &right}) {
        EXPECT_TRUE(inside(n, c->lo) && inside(n, c->hi)) << "child box outside node " << i;
      }
    }
  }
  std::sort(seen.begin(), seen.end());
  std::vector<int32_t> want = ids;
  std::sort(want.begin(), want.end());
  EXPECT_EQ(seen, want);
}

TEST(Bvh, BuildsADepthFirstTreeOverEveryMovingTriangle) {
  for (int n : {1, 2, 5, 100, 5000}) {
    const Scene s = random_scene(n, 7u + static_cast<unsigned>(n));
    const std::vector<int32_t> ids = moving_triangles(s);
    ASSERT_EQ(ids.size(), static_cast<size_t>(n));
    const Bvh b = build_bvh(s, ids);
    SCOPED_TRACE(n);
    check_tree(b, s, ids);
    if (n >= 100) {
      EXPECT_LT(b.depth, 40);
    }
  }
}

// Large nodes are binned and partitioned in parallel chunks: the tree must not depend on how
// many threads ran them.
TEST(Bvh, LargeBuildsDoNotDependOnTheThreadCount) {
  const Scene s = random_scene(70000, 11u);
  const std::vector<int32_t> ids = moving_triangles(s);
  Bvh one, all;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = build_bvh(s, ids);
  }
  all = build_bvh(s, ids);
  check_tree(all, s, ids);
  EXPECT_EQ(one.tris, all.tris);
  ASSERT_EQ(one.nodes.size(), all.nodes.size());
  for (size_t i = 0; i < one.nodes.size(); ++i) {
    EXPECT_EQ(one.nodes[i].skip, all.nodes[i].skip);
    EXPECT_EQ(one.nodes[i].first, all.nodes[i].first);
    EXPECT_EQ(one.nodes[i].count, all.nodes[i].count);
    EXPECT_EQ(one.nodes[i].lo, all.nodes[i].lo);
    EXPECT_EQ(one.nodes[i].hi, all.nodes[i].hi);
  }
}

TEST(Bvh, EqualCentroidsStillSplitIntoSmallLeaves) {
  Scene s;
  s.add_material(Material{});
  for (int i = 0; i < 50; ++i)  // 50 copies of one triangle
    s.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), 0);
  AnimatedObject o;
  o.count = 50;
  o.track.keys.push_back(PoseKey{});
  s.animation.objects.push_back(o);
  const std::vector<int32_t> ids = moving_triangles(s);
  check_tree(build_bvh(s, ids), s, ids);
}

TEST(Bvh, RefitKeepsTheTreeAndHoldsTheMovedTriangles) {
  const Scene rest = random_scene(2000, 3u);
  Scene posed = rest;
  const std::vector<int32_t> ids = moving_triangles(rest);
  Bvh b = build_bvh(rest, ids);
  const std::vector<int32_t> order = b.tris;
  pose_objects(rest, 0.8, posed);
  ASSERT_TRUE(refit_bvh(b, posed, ids));
  EXPECT_EQ(b.tris, order);  // the same tree
  check_tree(b, posed, ids);
}

TEST(Bvh, RefitRefusesWhenTheTrianglesChange) {
  Scene s = random_scene(50, 5u);
  const std::vector<int32_t> ids = moving_triangles(s);
  Bvh b = build_bvh(s, ids);
  const Bvh before = b;
  // Triangle 7 collapses to a point: it can no longer be hit, so the tree must be rebuilt.
  for (int v = 0; v < 3; ++v) s.positions[3 * 7 + static_cast<size_t>(v)] = glm::vec3(1.0f);
  const std::vector<int32_t> fewer = moving_triangles(s);
  ASSERT_EQ(fewer.size(), 49u);
  EXPECT_FALSE(refit_bvh(b, s, fewer));
  EXPECT_EQ(b.tris, before.tris);
  check_tree(build_bvh(s, fewer), s, fewer);
}

TEST(Bvh, NoMovingTrianglesGivesAnEmptyTree) {
  const Scene s = builtin_scene("thesis-a");
  EXPECT_TRUE(moving_triangles(s).empty());
  EXPECT_TRUE(build_bvh(s, {}).empty());
}

}  // namespace
}  // namespace rt
