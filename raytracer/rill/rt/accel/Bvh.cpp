// The BVH over moving triangles (Bvh.h): binned SAH build, refit, depth-first layout.
#include "rill/rt/accel/Bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "rill/rt/accel/Grid.h"

namespace rt {

namespace {

// Below this many triangles a subtree is built on the calling thread.
constexpr size_t kParallelMin = 4096;

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::infinity()};
  glm::vec3 hi{-std::numeric_limits<float>::infinity()};
  void grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  double area() const {
    if (!(hi.x >= lo.x)) return 0.0;
    const glm::dvec3 e = glm::dvec3(hi) - glm::dvec3(lo);
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

struct Prim {
  Box box;
  glm::vec3 centroid{0.0f};
  int32_t id = 0;
};

Box triangle_box(const Scene& s, int32_t id) {
  Box b;
  for (int k = 0; k < 3; ++k) b.grow(s.positions[3 * static_cast<size_t>(id) + k]);
  return b;
}

// The box grown by the padding of Bvh.h, rounded outwards to float.
void pad(const Box& b, glm::vec3& lo, glm::vec3& hi) {
  const glm::dvec3 l(b.lo), h(b.hi);
  const glm::dvec3 e = h - l;
  const double ext = std::max({e.x, e.y, e.z});
  const double mag = std::max({std::fabs(l.x), std::fabs(l.y), std::fabs(l.z), std::fabs(h.x),
                               std::fabs(h.y), std::fabs(h.z)});
  const double p = 1e-5 * ext + 4e-7 * mag + 1e-30;
  for (int a = 0; a < 3; ++a) {
    float x = static_cast<float>(l[a] - p);
    if (static_cast<double>(x) > l[a] - p) x = std::nextafter(x, -INFINITY);
    float y = static_cast<float>(h[a] + p);
    if (static_cast<double>(y) < h[a] + p) y = std::nextafter(y, INFINITY);
    lo[a] = x;
    hi[a] = y;
  }
}

struct BuildNode {
  Box box;
  size_t begin = 0, end = 0;  // prims[begin, end) for a leaf
  std::unique_ptr<BuildNode> left, right;
  int depth = 1;
};

// The best SAH split of prims[begin, end): axis and bin boundary (split), or false when a leaf
// is cheaper or the centroids cannot be told apart.
bool best_split(const std::vector<Prim>& prims, size_t begin, size_t end, const Box& cbox,
                int& axis, int& split) {
  const size_t n = end - begin;
  double best = static_cast<double>(n);  // a leaf's cost: n triangle tests, relative area 1
  bool found = false;
  Box all;
  for (size_t i = begin; i < end; ++i) all.grow(prims[i].box);
  const double area = std::max(all.area(), 1e-300);
  for (int a = 0; a < 3; ++a) {
    const float lo = cbox.lo[a], hi = cbox.hi[a];
    if (!(hi > lo)) continue;
    const double scale = kBvhBins / (static_cast<double>(hi) - lo);
    std::array<Box, kBvhBins> bins;
    std::array<size_t, kBvhBins> counts{};
    for (size_t i = begin; i < end; ++i) {
      int b = static_cast<int>((prims[i].centroid[a] - static_cast<double>(lo)) * scale);
      b = std::clamp(b, 0, kBvhBins - 1);
      ++counts[static_cast<size_t>(b)];
      bins[static_cast<size_t>(b)].grow(prims[i].box);
    }
    std::array<double, kBvhBins> right_cost{};
    Box r;
    size_t rn = 0;
    for (int b = kBvhBins - 1; b > 0; --b) {
      r.grow(bins[static_cast<size_t>(b)]);
      rn += counts[static_cast<size_t>(b)];
      right_cost[static_cast<size_t>(b)] = r.area() * static_cast<double>(rn);
    }
    Box l;
    size_t ln = 0;
    for (int b = 1; b < kBvhBins; ++b) {
      l.grow(bins[static_cast<size_t>(b - 1)]);
      ln += counts[static_cast<size_t>(b - 1)];
      if (ln == 0 || ln == n) continue;
      // One box test for the node, then the children's tests weighted by their areas.
      const double cost =
          0.125 + (l.area() * static_cast<double>(ln) + right_cost[static_cast<size_t>(b)]) / area;
      if (cost < best) {
        best = cost;
        axis = a;
        split = b;
        found = true;
      }
    }
  }
  return found;
}

std::unique_ptr<BuildNode> build(std::vector<Prim>& prims, size_t begin, size_t end) {
  auto node = std::make_unique<BuildNode>();
  node->begin = begin;
  node->end = end;
  Box cbox;
  for (size_t i = begin; i < end; ++i) {
    node->box.grow(prims[i].box);
    cbox.grow(prims[i].centroid);
  }
  const size_t n = end - begin;
  if (n <= 1) return node;
  int axis = 0, split = 0;
  size_t mid = begin;
  if (best_split(prims, begin, end, cbox, axis, split)) {
    const double lo = cbox.lo[axis];
    const double scale = kBvhBins / (static_cast<double>(cbox.hi[axis]) - lo);
    auto it = std::partition(prims.begin() + static_cast<std::ptrdiff_t>(begin),
                             prims.begin() + static_cast<std::ptrdiff_t>(end), [&](const Prim& p) {
                               int b = static_cast<int>((p.centroid[axis] - lo) * scale);
                               return std::clamp(b, 0, kBvhBins - 1) < split;
                             });
    mid = static_cast<size_t>(it - prims.begin());
  } else if (n > static_cast<size_t>(kBvhLeafMax)) {
    // A leaf would be too large and SAH finds no split (equal centroids, or a leaf looked
    // cheaper): halve by count along the longest axis.
    const glm::vec3 e = cbox.hi - cbox.lo;
    axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    mid = begin + n / 2;
    std::nth_element(prims.begin() + static_cast<std::ptrdiff_t>(begin),
                     prims.begin() + static_cast<std::ptrdiff_t>(mid),
                     prims.begin() + static_cast<std::ptrdiff_t>(end),
                     [&](const Prim& a, const Prim& b) {
                       return a.centroid[axis] < b.centroid[axis] ||
                              (a.centroid[axis] == b.centroid[axis] && a.id < b.id);
                     });
  }
  if (mid == begin || mid == end) return node;  // a leaf (at most kBvhLeafMax)
  auto left = [&] { node->left = build(prims, begin, mid); };
  auto right = [&] { node->right = build(prims, mid, end); };
  if (n >= kParallelMin)
    tbb::parallel_invoke(left, right);
  else {
    left();
    right();
  }
  node->depth = 1 + std::max(node->left->depth, node->right->depth);
  return node;
}

void flatten(const BuildNode& n, const std::vector<Prim>& prims, Bvh& out) {
  const size_t at = out.nodes.size();
  out.nodes.emplace_back();
  pad(n.box, out.nodes[at].lo, out.nodes[at].hi);
  if (!n.left) {
    out.nodes[at].first = static_cast<int32_t>(out.tris.size());
    out.nodes[at].count = static_cast<int32_t>(n.end - n.begin);
    for (size_t i = n.begin; i < n.end; ++i) out.tris.push_back(prims[i].id);
  } else {
    flatten(*n.left, prims, out);
    flatten(*n.right, prims, out);
  }
  out.nodes[at].skip = static_cast<int32_t>(out.nodes.size());
}

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

std::vector<int32_t> moving_triangles(const Scene& s) {
  std::vector<int32_t> ids;
  for (const AnimatedObject& o : s.animation.objects)
    for (size_t t = o.first; t < o.first + o.count; ++t)
      if (triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]))
        ids.push_back(static_cast<int32_t>(t));
  return ids;
}

Bvh build_bvh(const Scene& s, const std::vector<int32_t>& ids) {
  const auto start = std::chrono::steady_clock::now();
  Bvh out;
  if (ids.empty()) return out;
  std::vector<Prim> prims(ids.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, ids.size(), 4096),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i) {
                        prims[i].id = ids[i];
                        prims[i].box = triangle_box(s, ids[i]);
                        prims[i].centroid = (prims[i].box.lo + prims[i].box.hi) * 0.5f;
                      }
                    });
  const std::unique_ptr<BuildNode> root = build(prims, 0, prims.size());
  out.nodes.reserve(2 * ids.size());
  out.tris.reserve(ids.size());
  flatten(*root, prims, out);
  out.depth = root->depth;
  out.build_ms = ms_since(start);
  return out;
}

bool refit_bvh(Bvh& b, const Scene& s, const std::vector<int32_t>& ids) {
  const auto start = std::chrono::steady_clock::now();
  if (ids.size() != b.tris.size()) return false;
  std::vector<int32_t> held = b.tris, now = ids;
  std::sort(held.begin(), held.end());
  std::sort(now.begin(), now.end());
  if (held != now) return false;
  // Children come after their parent in depth-first order: back to front, a node's children
  // are done before it. The unpadded boxes are kept apart so padding is not compounded.
  std::vector<Box> boxes(b.nodes.size());
  for (size_t i = b.nodes.size(); i-- > 0;) {
    BvhNode& n = b.nodes[i];
    Box box;
    if (n.count > 0) {
      for (int32_t k = 0; k < n.count; ++k)
        box.grow(triangle_box(s, b.tris[static_cast<size_t>(n.first + k)]));
    } else {
      box = boxes[i + 1];
      box.grow(boxes[static_cast<size_t>(b.nodes[i + 1].skip)]);
    }
    boxes[i] = box;
    pad(box, n.lo, n.hi);
  }
  b.build_ms = ms_since(start);
  return true;
}

}  // namespace rt
