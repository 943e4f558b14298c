// The BVH over moving triangles (Bvh.h): binned SAH build, refit, depth-first layout.
#include "rill/rt/accel/Bvh.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>

#include "rill/Stopwatch.h"
#include "rill/rt/accel/Grid.h"

namespace rt {

namespace {

// Work over a node's triangles (binning, bounds, partitions) is split into chunks of this
// size.
constexpr size_t kParallelMin = 4096;
// Subtrees of at least this many triangles are built as tasks of their own: small enough
// that the last subtrees of a build do not leave threads idle.
constexpr size_t kParallelSubtreeMin = 1024;
// Nodes of at least this many triangles are partitioned in parallel (below, in place).
constexpr size_t kParallelPartitionMin = 32768;
// Nodes within a subtree this large are refitted on the calling thread.
constexpr int32_t kParallelRefitMin = 2048;

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
  float area() const {
    if (!(hi.x >= lo.x)) return 0.0f;
    const glm::vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

// A triangle as the builder sees it, moved at every partition: 32 bytes aligned to 16, so
// that a swap is two aligned 16-byte moves (at 28 bytes the compiler copied through
// overlapping moves, which stall). Its centroid is kept doubled (lo + hi, exact halving
// aside), which bins and orders the same.
struct alignas(16) Prim {
  Box box;
  int32_t id = 0;
  int32_t bin = 0;  // its bin in the last binning of its node, which the partition reads
  glm::vec3 centroid() const { return box.lo + box.hi; }
  float centroid(int axis) const { return box.lo[axis] + box.hi[axis]; }
};

Box triangle_box(const Scene& s, int32_t id) {
  const glm::vec3* p = &s.positions[3 * static_cast<size_t>(id)];
  Box b;
  b.lo = glm::min(p[0], glm::min(p[1], p[2]));
  b.hi = glm::max(p[0], glm::max(p[1], p[2]));
  return b;
}

// The box grown by the padding of Bvh.h. In float: 4e-7 of the largest coordinate is over
// 3 ulps of it, so the rounded box is still larger by more than 2 ulps on every side.
void pad(const Box& b, glm::vec3& lo, glm::vec3& hi) {
  const glm::vec3 e = b.hi - b.lo;
  const glm::vec3 m = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  const float p = 1e-5f * std::max(e.x, std::max(e.y, e.z)) +
                  4e-7f * std::max(m.x, std::max(m.y, m.z)) + 1e-30f;
  lo = b.lo - glm::vec3(p);
  hi = b.hi + glm::vec3(p);
}

// Four floats in one SSE register where there is SSE (every x86-64), else four floats: the
// bins' boxes grow by one min and one max per side instead of three of each. Only the first
// three lanes mean anything.
#if defined(__SSE2__)
struct Lanes {
  __m128 v;
  static Lanes load(const float* p) { return {_mm_loadu_ps(p)}; }  // p[0..3] readable
  static Lanes all(float f) { return {_mm_set1_ps(f)}; }
  friend Lanes min(Lanes a, Lanes b) { return {_mm_min_ps(a.v, b.v)}; }
  friend Lanes max(Lanes a, Lanes b) { return {_mm_max_ps(a.v, b.v)}; }
  friend Lanes operator+(Lanes a, Lanes b) { return {_mm_add_ps(a.v, b.v)}; }
  glm::vec3 xyz() const {
    alignas(16) float f[4];
    _mm_store_ps(f, v);
    return {f[0], f[1], f[2]};
  }
};
#else
struct Lanes {
  float v[4];
  static Lanes load(const float* p) { return {{p[0], p[1], p[2], 0.0f}}; }  // lane 3 unused
  static Lanes all(float f) { return {{f, f, f, f}}; }
  friend Lanes min(Lanes a, Lanes b) {
    for (int k = 0; k < 4; ++k) a.v[k] = b.v[k] < a.v[k] ? b.v[k] : a.v[k];
    return a;
  }
  friend Lanes max(Lanes a, Lanes b) {
    for (int k = 0; k < 4; ++k) a.v[k] = a.v[k] < b.v[k] ? b.v[k] : a.v[k];
    return a;
  }
  friend Lanes operator+(Lanes a, Lanes b) {
    for (int k = 0; k < 4; ++k) a.v[k] += b.v[k];
    return a;
  }
  glm::vec3 xyz() const { return {v[0], v[1], v[2]}; }
};
#endif

// A bin: the box and the centroid bounds of the triangles whose centroid falls in it, and
// their count. The split's children take their bounds from the bins: no pass of their own.
struct Bin {
  Lanes lo = Lanes::all(std::numeric_limits<float>::infinity());
  Lanes hi = Lanes::all(-std::numeric_limits<float>::infinity());
  Lanes clo = lo, chi = hi;
  size_t count = 0;
  void add(const Prim& p) {
    // Four floats from box.lo (its x, y, z and hi.x) and from box.hi (x, y, z and the id):
    // the fourth lane is never read.
    const Lanes l = Lanes::load(&p.box.lo.x), h = Lanes::load(&p.box.hi.x);
    lo = min(lo, l);
    hi = max(hi, h);
    const Lanes c = l + h;
    clo = min(clo, c);
    chi = max(chi, c);
    ++count;
  }
  void add(const Bin& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
    clo = min(clo, b.clo);
    chi = max(chi, b.chi);
    count += b.count;
  }
  Box box() const { return Box{lo.xyz(), hi.xyz()}; }
  Box centroids() const { return Box{clo.xyz(), chi.xyz()}; }
};
static_assert(offsetof(Prim, box) == 0 && offsetof(Box, lo) == 0 && offsetof(Box, hi) == 12 &&
                  offsetof(Prim, id) == 24 && sizeof(Prim) == 32,
              "Bin::add reads a Prim as two blocks of four floats");
using Bins = std::array<Bin, kBvhBins>;

// The bin of a centroid along an axis, for centroid bounds lo, nb bins and the scale
// nb / extent.
int bin_of(float c, float lo, float scale, int nb) {
  // Clamped as a float first: a tiny extent makes scale infinite, and 0 * inf is NaN, which
  // no int can hold.
  const float f = (c - lo) * scale;
  if (!(f > 0.0f)) return 0;
  if (!(f < static_cast<float>(nb))) return nb - 1;
  return static_cast<int>(f);
}

struct BuildNode {
  Box box, centroids;
  size_t begin = 0, end = 0;      // prims[begin, end)
  int32_t left = -1, right = -1;  // children (-1: a leaf)
  int depth = 1;
  int32_t subtree = 1;  // nodes in its subtree, itself included (where flatten puts them)
};

// Memory for n objects of a type whose copies are plain bytes, left uninitialized: the
// builder's node array and partition scratch are written before they are read, and
// initializing them would cost as much as a small build.
template <class T>
class RawArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
  static_assert(alignof(T) <= __STDCPP_DEFAULT_NEW_ALIGNMENT__);

 public:
  explicit RawArray(size_t n) : bytes_(new unsigned char[n * sizeof(T)]) {}
  T* data() { return reinterpret_cast<T*>(bytes_.get()); }
  const T* data() const { return reinterpret_cast<const T*>(bytes_.get()); }
  T& operator[](size_t i) { return data()[i]; }
  const T& operator[](size_t i) const { return data()[i]; }

 private:
  std::unique_ptr<unsigned char[]> bytes_;  // new[] aligns for any fundamental type
};

// Each node's subtree owns a fixed region of the node array: a node over c triangles has at
// most 2c - 1 nodes in its subtree, so node `at` over [begin, end) puts its left child at
// at + 1 and its right child at at + 2 (mid - begin). Subtrees built in parallel then share
// no counter (an atomic one cost 15% of the build on 2 threads and stopped it scaling) and
// write no cache line in common.
//
// The memory comes from BuildMemory (below): a dynamic scene rebuilds every frame, and fresh
// memory would be faulted in page by page each time.
struct Builder {
  Prim* prims;
  BuildNode* nodes;
  Prim* scratch;  // for partitions in parallel

  Builder(Prim* p, BuildNode* n, Prim* s) : prims(p), nodes(n), scratch(s) {
    new (&nodes[0]) BuildNode{};
  }

  // prims[begin, end) reordered with those for which `left` holds first; returns the split.
  // Large ranges are counted and scattered in parallel chunks of a fixed size, keeping the
  // order within each side, so the tree never depends on the thread count.
  template <class Pred>
  size_t partition(size_t begin, size_t end, Pred left) {
    if (end - begin < kParallelPartitionMin) {
      return static_cast<size_t>(std::partition(prims + begin, prims + end, left) - prims);
    }
    const size_t chunks = (end - begin + kParallelMin - 1) / kParallelMin;
    std::vector<size_t> lefts(chunks);
    auto chunk = [&](size_t c, size_t& from, size_t& to) {
      from = begin + c * kParallelMin;
      to = std::min(end, from + kParallelMin);
    };
    tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
      size_t from, to, n = 0;
      chunk(c, from, to);
      for (size_t i = from; i < to; ++i) n += left(prims[i]) ? 1 : 0;
      lefts[c] = n;
    });
    std::vector<size_t> at_left(chunks), at_right(chunks);
    size_t total_left = 0;
    for (size_t c = 0; c < chunks; ++c) {
      at_left[c] = total_left;
      total_left += lefts[c];
    }
    for (size_t c = 0, right = total_left; c < chunks; ++c) {
      size_t from, to;
      chunk(c, from, to);
      at_right[c] = right;
      right += (to - from) - lefts[c];
    }
    tbb::parallel_for(size_t{0}, chunks, [&](size_t c) {
      size_t from, to;
      chunk(c, from, to);
      // The scratch slots of this range only: subtrees partition in parallel too.
      size_t l = begin + at_left[c], r = begin + at_right[c];
      for (size_t i = from; i < to; ++i)
        std::memcpy(&scratch[left(prims[i]) ? l++ : r++], &prims[i], sizeof(Prim));
    });
    tbb::parallel_for(tbb::blocked_range<size_t>(0, end - begin, kParallelMin),
                      [&](const tbb::blocked_range<size_t>& r) {
                        std::memcpy(&prims[begin + r.begin()], &scratch[begin + r.begin()],
                                    (r.end() - r.begin()) * sizeof(Prim));
                      });
    return begin + total_left;
  }

  // The node's triangles binned by their centroids along `axis` into bins[0, nb), which
  // start empty; each keeps its bin for the partition.
  void bin(const BuildNode& n, int axis, float scale, int nb, Bin* bins) {
    const float lo = n.centroids.lo[axis];
    auto add = [&](size_t from, size_t to, Bin* into) {
      for (size_t i = from; i < to; ++i) {
        const int b = bin_of(prims[i].centroid(axis), lo, scale, nb);
        prims[i].bin = b;
        into[static_cast<size_t>(b)].add(prims[i]);
      }
    };
    if (n.end - n.begin < 4 * kParallelMin) return add(n.begin, n.end, bins);
    const Bins sum = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(n.begin, n.end, kParallelMin), Bins{},
        [&](const tbb::blocked_range<size_t>& r, Bins acc) {
          add(r.begin(), r.end(), acc.data());
          return acc;
        },
        [nb](Bins a, const Bins& b) {
          for (size_t k = 0; k < static_cast<size_t>(nb); ++k) a[k].add(b[k]);
          return a;
        });
    std::copy(sum.begin(), sum.begin() + nb, bins);
  }

  // Splits node `at` where the surface area heuristic says (binned along the longest axis
  // of its centroids, as Wald 2007 does), or leaves it a leaf, then its children.
  void build(int32_t at) {
    BuildNode& n = nodes[static_cast<size_t>(at)];
    const size_t count = n.end - n.begin;
    if (count <= 1) return;
    const glm::vec3 ext = n.centroids.hi - n.centroids.lo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    size_t mid = n.begin;
    Bin n_left, n_right;  // the children's bounds (empty: to be computed)
    if (ext[axis] > 0) {
      // As many bins as triangles, up to kBvhBins: a small node needs no more, and most
      // nodes are small.
      const int nb = count >= static_cast<size_t>(kBvhBins) ? kBvhBins : static_cast<int>(count);
      const float scale = static_cast<float>(nb) / ext[axis];
      // Only the bins in use are made empty: most nodes are small, and 16 empty bins cost
      // them more than their binning.
      alignas(Bin) unsigned char bin_bytes[sizeof(Bin) * kBvhBins];
      Bin* bins = reinterpret_cast<Bin*>(bin_bytes);
      for (int k = 0; k < nb; ++k) new (&bins[k]) Bin{};
      bin(n, axis, scale, nb, bins);
      // The cheapest split: one box test for the node, then the children's triangle tests
      // weighted by their areas (relative to the node's). A leaf costs its triangle count.
      // The sweep keeps only the right sides' areas and counts; the chosen split's bounds
      // are summed once afterwards.
      std::array<float, kBvhBins> right_cost;
      Bin r;
      for (int k = nb - 1; k > 0; --k) {
        r.add(bins[k]);
        right_cost[static_cast<size_t>(k)] =
            r.count == 0 ? -1.0f : r.box().area() * static_cast<float>(r.count);
      }
      float best = static_cast<float>(count);
      int split = 0;
      const float area = std::max(n.box.area(), 1e-30f);
      Bin l;
      for (int k = 1; k < nb; ++k) {
        l.add(bins[k - 1]);
        const float rc = right_cost[static_cast<size_t>(k)];
        if (l.count == 0 || rc < 0.0f) continue;
        const float cost = 0.125f + (l.box().area() * static_cast<float>(l.count) + rc) / area;
        if (cost < best) {
          best = cost;
          split = k;
        }
      }
      if (split > 0) {
        for (int k = 0; k < split; ++k) n_left.add(bins[k]);
        for (int k = split; k < nb; ++k) n_right.add(bins[k]);
        mid = partition(n.begin, n.end, [split](const Prim& p) { return p.bin < split; });
      }
    }
    if (mid == n.begin && count > static_cast<size_t>(kBvhLeafMax)) {
      // A leaf would be too large and SAH finds no split (equal centroids, or a leaf looked
      // cheaper): halve by count.
      mid = n.begin + count / 2;
      std::nth_element(prims + n.begin, prims + mid, prims + n.end,
                       [&](const Prim& a, const Prim& b) {
                         const float ca = a.centroid(axis), cb = b.centroid(axis);
                         return ca < cb || (ca == cb && a.id < b.id);
                       });
    }
    if (mid == n.begin || mid == n.end) return;  // a leaf (at most kBvhLeafMax)
    const int32_t left = at + 1, right = at + 2 * static_cast<int32_t>(mid - n.begin);
    n.left = left;
    n.right = right;
    BuildNode& l = *new (&nodes[static_cast<size_t>(left)]) BuildNode{};
    BuildNode& r = *new (&nodes[static_cast<size_t>(right)]) BuildNode{};
    l.begin = n.begin;
    l.end = mid;
    r.begin = mid;
    r.end = n.end;
    const bool parallel = count >= kParallelSubtreeMin;
    auto child = [&](BuildNode& c, int32_t index, const Bin& from) {
      if (from.count == c.end - c.begin) {
        c.box = from.box();
        c.centroids = from.centroids();
      } else {
        bound(c, parallel);  // the median split's halves
      }
      build(index);
    };
    if (parallel)
      tbb::parallel_invoke([&] { child(l, left, n_left); }, [&] { child(r, right, n_right); });
    else {
      child(l, left, n_left);
      child(r, right, n_right);
    }
    n.depth = 1 + std::max(l.depth, r.depth);
    n.subtree = 1 + l.subtree + r.subtree;
  }

  // A node's box and centroid bounds, from its triangles.
  void bound(BuildNode& c, bool parallel) const {
    struct Bounds {
      Box box, centroids;
    };
    auto add = [&](size_t from, size_t to, Bounds acc) {
      for (size_t i = from; i < to; ++i) {
        acc.box.grow(prims[i].box);
        acc.centroids.grow(prims[i].centroid());
      }
      return acc;
    };
    Bounds b;
    if (parallel && c.end - c.begin >= 4 * kParallelMin)
      b = tbb::parallel_reduce(
          tbb::blocked_range<size_t>(c.begin, c.end, kParallelMin), Bounds{},
          [&](const tbb::blocked_range<size_t>& r, Bounds acc) {
            return add(r.begin(), r.end(), acc);
          },
          [](Bounds x, const Bounds& y) {
            x.box.grow(y.box);
            x.centroids.grow(y.centroids);
            return x;
          });
    else
      b = add(c.begin, c.end, b);
    c.box = b.box;
    c.centroids = b.centroids;
  }

  // Depth-first order with skips (Bvh.h), from the build's pairs, into out.nodes (sized to the
  // root's subtree): build node `at` goes to slot i, its left subtree right after it and its
  // right subtree after that, so large subtrees are written in parallel.
  void flatten(int32_t at, int32_t i, Bvh& out) const {
    const BuildNode& n = nodes[static_cast<size_t>(at)];
    BvhNode& o = out.nodes[static_cast<size_t>(i)];
    pad(n.box, o.lo, o.hi);
    o.skip = i + n.subtree;
    if (n.left < 0) {
      o.first = static_cast<int32_t>(n.begin);
      o.count = static_cast<int32_t>(n.end - n.begin);
      return;
    }
    o.first = o.count = 0;
    const int32_t right_at = i + 1 + nodes[static_cast<size_t>(n.left)].subtree;
    if (n.subtree >= static_cast<int32_t>(kParallelMin))
      tbb::parallel_invoke([&] { flatten(n.left, i + 1, out); },
                           [&] { flatten(n.right, right_at, out); });
    else {
      flatten(n.left, i + 1, out);
      flatten(n.right, right_at, out);
    }
  }
};

// The unpadded box of node i's subtree, its nodes padded on the way (children first).
Box refit(Bvh& b, const Scene& s, int32_t i) {
  BvhNode& n = b.nodes[static_cast<size_t>(i)];
  Box box;
  if (n.count > 0) {
    for (int32_t k = 0; k < n.count; ++k)
      box.grow(triangle_box(s, b.tris[static_cast<size_t>(n.first + k)]));
  } else {
    const int32_t left = i + 1, right = b.nodes[static_cast<size_t>(left)].skip;
    Box l, r;
    if (n.skip - i >= kParallelRefitMin)
      tbb::parallel_invoke([&] { l = refit(b, s, left); }, [&] { r = refit(b, s, right); });
    else {
      l = refit(b, s, left);
      r = refit(b, s, right);
    }
    box = l;
    box.grow(r);
  }
  pad(box, n.lo, n.hi);
  return box;
}

using rill::ms_since;

// The builder's memory for n triangles: the triangles, the partition scratch and the node
// array (2n nodes: Builder's regions).
struct BuildMemory {
  size_t capacity;
  RawArray<Prim> prims, scratch;
  RawArray<BuildNode> nodes;
  explicit BuildMemory(size_t n) : capacity(n), prims(n), scratch(n), nodes(2 * n) {}
};

// The last build's memory, kept for the next (a build that finds it in use makes its own).
// Claimed with a flag, not a mutex: a thread waiting inside one build may run a task of
// another build (oneTBB), and a mutex may not be tried by the thread that holds it. It holds
// the largest build's memory until the process ends.
struct KeptMemory {
  std::atomic<bool> busy{false};
  std::unique_ptr<BuildMemory> kept;
} g_memory;

}  // namespace

std::vector<int32_t> moving_triangles(const Scene& s) {
  std::vector<int32_t> ids;
  for (const AnimatedObject& o : s.animation.objects)
    for (size_t t = o.first; t < o.first + o.count; ++t)
      if (triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]))
        ids.push_back(static_cast<int32_t>(t));
  return ids;
}

void rebuild_bvh(Bvh& out, const Scene& s, const std::vector<int32_t>& ids) {
  const auto start = std::chrono::steady_clock::now();
  if (ids.empty()) {
    out = Bvh{};
    return;
  }
  const size_t n = ids.size();
  // The last build's memory when it is large enough and no other build holds it.
  const bool claimed = !g_memory.busy.exchange(true, std::memory_order_acquire);
  struct Release {
    bool claimed;
    ~Release() {
      if (claimed) g_memory.busy.store(false, std::memory_order_release);
    }
  } release{claimed};
  std::unique_ptr<BuildMemory> own;
  BuildMemory* memory = nullptr;
  if (claimed) {
    if (!g_memory.kept || g_memory.kept->capacity < n)
      g_memory.kept = std::make_unique<BuildMemory>(n);
    memory = g_memory.kept.get();
  } else {
    own = std::make_unique<BuildMemory>(n);
    memory = own.get();
  }
  Prim* prims = memory->prims.data();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kParallelMin),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i)
                        new (&prims[i]) Prim{triangle_box(s, ids[i]), ids[i], 0};
                    });
  Builder builder(prims, memory->nodes.data(), memory->scratch.data());
  BuildNode& root = builder.nodes[0];
  root.begin = 0;
  root.end = n;
  builder.bound(root, true);
  builder.build(0);
  // Resized, not made anew: the last tree's memory holds this one (every slot is written).
  out.nodes.resize(static_cast<size_t>(builder.nodes[0].subtree));
  builder.flatten(0, 0, out);
  out.tris.resize(n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kParallelMin),
                    [&](const tbb::blocked_range<size_t>& r) {
                      for (size_t i = r.begin(); i != r.end(); ++i) out.tris[i] = prims[i].id;
                    });
  out.ids = ids;
  out.depth = builder.nodes[0].depth;
  out.build_ms = ms_since(start);
}

Bvh build_bvh(const Scene& s, const std::vector<int32_t>& ids) {
  Bvh out;
  rebuild_bvh(out, s, ids);
  return out;
}

bool refit_bvh(Bvh& b, const Scene& s, const std::vector<int32_t>& ids) {
  const auto start = std::chrono::steady_clock::now();
  if (ids.size() != b.tris.size() || b.nodes.empty()) return false;
  // The same triangles as the tree holds (a triangle that became degenerate, or came back,
  // changes the set: then only a rebuild will do).
  if (!std::equal(ids.begin(), ids.end(), b.ids.begin())) return false;
  refit(b, s, 0);
  b.build_ms = ms_since(start);
  return true;
}

}  // namespace rt
