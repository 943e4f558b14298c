// The second accelerator: a bounding-volume hierarchy over the triangles that move
// (Scene::animation), rebuilt or refitted on the host every frame, while the static
// triangles keep the grid built once (Grid.h). The tracer searches both and keeps the closest
// hit by the one rule of test_triangle (smaller distance, then smaller primitive id), so the
// hit does not depend on which accelerator holds a triangle: a frame is bit for bit the
// static scene baked at that instant (scene/Pose.h).
//
// Build: binned SAH (16 bins over the centroids, Wald 2007) down to leaves of at most
// kBvhLeafMax triangles, subtrees in parallel (oneTBB). Refit: the same tree, boxes
// recomputed from the moved triangles, children before parents: cheaper, and as good as the
// motion is small.
//
// Layout (what BvhView uploads): nodes in depth-first order, so a node's first child is the
// next node and `skip` is the node after its subtree. The kernel walks it without a stack
// (a "threaded" BVH): into a box it hits, to `skip` past one it misses. So that a triangle
// the triangle test accepts is never in a box the float slab test misses, each box is padded
// by 1e-5 of its size and 4e-7 of its coordinates (rounding that grows with the coordinates),
// and the walk widens each slab interval by 8 float epsilons (rounding that grows with the
// distance from the ray's origin; kernel/BvhTraversal.cpp). Tests aim rays at the edges of
// flat faces from far away and near faces far from the origin.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

constexpr int kBvhLeafMax = 4;
constexpr int kBvhBins = 16;

struct BvhNode {
  glm::vec3 lo{0.0f}, hi{0.0f};  // padded
  int32_t skip = 0;              // the node after this subtree (the node count after the last)
  int32_t first = 0, count = 0;  // a leaf: tris[first, first + count); count 0: inner
};

struct Bvh {
  std::vector<BvhNode> nodes;  // empty: no triangle to hold
  std::vector<int32_t> tris;   // primitive ids, leaf by leaf
  std::vector<int32_t> ids;    // the ids it was built over, as given (refits compare)
  int depth = 0;
  double build_ms = 0;  // the last build or refit
  bool empty() const { return nodes.empty(); }
};

// The triangles of `s`'s animated objects that can be hit where they are now (finite, not
// degenerate: triangle_usable, as the grid decides for the static ones).
std::vector<int32_t> moving_triangles(const Scene& s);

// A new tree over the triangles `ids` of `s` (positions as posed).
Bvh build_bvh(const Scene& s, const std::vector<int32_t>& ids);
// The same, into `b` in place of its tree: b's memory is reused (a dynamic scene rebuilds
// every frame, and fresh arrays cost their page faults each time).
void rebuild_bvh(Bvh& b, const Scene& s, const std::vector<int32_t>& ids);

// The same tree with its boxes recomputed from `s`'s positions now. Returns false, leaving
// the tree as it was, when the triangles that can be hit are not those the tree holds (one
// became degenerate or non-finite, or came back): build again then.
bool refit_bvh(Bvh& b, const Scene& s, const std::vector<int32_t>& ids);

}  // namespace rt
