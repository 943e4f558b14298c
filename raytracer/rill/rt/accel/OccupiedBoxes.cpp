// The boxes that hold a grid's triangles (OccupiedBoxes.h).
#include "rill/rt/accel/OccupiedBoxes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rt {

namespace {

// Blocks per axis: about cubic, at most max_boxes in all, and none thinner than the grid's
// box allows (a flat box gets one block across).
glm::ivec3 block_counts(const glm::vec3& extent, int max_boxes) {
  const double big = std::max({double(extent.x), double(extent.y), double(extent.z)});
  glm::dvec3 e(extent);
  for (int a = 0; a < 3; ++a) e[a] = std::max(e[a], big * 1e-3);
  double edge = std::cbrt(e.x * e.y * e.z / max_boxes);
  for (;;) {
    glm::ivec3 n;
    for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::floor(e[a] / edge)));
    if (int64_t{n.x} * n.y * n.z <= max_boxes) return n;
    edge *= 1.05;
  }
}

}  // namespace

float hit_margin(const std::vector<Aabb>& boxes, const Aabb* moving, const glm::vec3& eye) {
  double mag = 0;
  auto grow = [&](const Aabb& b) {
    for (int a = 0; a < 3; ++a)
      mag = std::max({mag, std::fabs(double(b.lo[a])), std::fabs(double(b.hi[a]))});
  };
  for (const Aabb& b : boxes) grow(b);
  if (moving) grow(*moving);
  const double eye_mag = glm::length(glm::dvec3(eye));
  const double m = 1e-4 * (eye_mag + mag);
  return std::isfinite(m) ? static_cast<float>(m) * 1.0001f
                          : std::numeric_limits<float>::infinity();
}

Aabb widened(const Aabb& b, float margin) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  Aabb w;
  for (int a = 0; a < 3; ++a) {
    w.lo[a] = std::nextafter(b.lo[a] - margin, -kInf);
    w.hi[a] = std::nextafter(b.hi[a] + margin, kInf);
  }
  return w;
}

std::vector<Aabb> occupied_boxes(const Scene& s, const Grid& grid, int max_boxes,
                                 uint64_t max_visits) {
  if (grid.empty()) return {};
  const Aabb whole{grid.lo, grid.hi};
  if (max_boxes < 1) return {whole};
  const glm::vec3 extent = grid.hi - grid.lo;
  if (!std::isfinite(extent.x) || !std::isfinite(extent.y) || !std::isfinite(extent.z))
    return {whole};  // (a box too large for float: one box, the grid's)
  const glm::ivec3 blocks = block_counts(extent, max_boxes);
  // The block faces per axis: face i of axis a is where block i - 1 ends and block i begins,
  // one float for both; the outer two at infinity, so that no part of a triangle is lost.
  constexpr float kInf = std::numeric_limits<float>::infinity();
  std::vector<float> faces[3];
  for (int a = 0; a < 3; ++a) {
    faces[a].resize(static_cast<size_t>(blocks[a]) + 1);
    faces[a].front() = -kInf;
    faces[a].back() = kInf;
    const float step = (grid.hi[a] - grid.lo[a]) / static_cast<float>(blocks[a]);
    for (int i = 1; i < blocks[a]; ++i)
      faces[a][static_cast<size_t>(i)] = grid.lo[a] + static_cast<float>(i) * step;
  }
  // The block holding coordinate x along axis a: faces[a][b] <= x < faces[a][b + 1].
  auto block_of = [&](int a, float x) {
    const auto& f = faces[a];
    const auto it = std::upper_bound(f.begin() + 1, f.end() - 1, x);
    return static_cast<int>(it - f.begin()) - 1;
  };

  std::vector<char> in_grid(s.triangle_count(), 0);
  for (int32_t t : grid.elements) in_grid[static_cast<size_t>(t)] = 1;
  std::vector<Aabb> box(static_cast<size_t>(blocks.x) * blocks.y * blocks.z,
                        Aabb{glm::vec3(kInf), glm::vec3(-kInf)});
  uint64_t visits = 0;
  for (size_t t = 0; t < in_grid.size(); ++t) {
    if (!in_grid[t]) continue;
    const glm::vec3* p = &s.positions[t * 3];
    const glm::vec3 lo = glm::min(glm::min(p[0], p[1]), p[2]);
    const glm::vec3 hi = glm::max(glm::max(p[0], p[1]), p[2]);
    glm::ivec3 b0, b1;
    for (int a = 0; a < 3; ++a) {
      b0[a] = block_of(a, lo[a]);
      b1[a] = block_of(a, hi[a]);
    }
    visits += uint64_t(b1.x - b0.x + 1) * uint64_t(b1.y - b0.y + 1) * uint64_t(b1.z - b0.z + 1);
    if (visits > max_visits) return {whole};
    for (int z = b0.z; z <= b1.z; ++z)
      for (int y = b0.y; y <= b1.y; ++y)
        for (int x = b0.x; x <= b1.x; ++x) {
          const glm::ivec3 b(x, y, z);
          glm::vec3 cut_lo, cut_hi;  // the triangle's box within the block's
          for (int a = 0; a < 3; ++a) {
            cut_lo[a] = std::max(lo[a], faces[a][static_cast<size_t>(b[a])]);
            cut_hi[a] = std::min(hi[a], faces[a][static_cast<size_t>(b[a]) + 1]);
          }
          Aabb& to = box[static_cast<size_t>(x + blocks.x * (y + blocks.y * z))];
          to.lo = glm::min(to.lo, cut_lo);
          to.hi = glm::max(to.hi, cut_hi);
        }
  }
  std::vector<Aabb> out;
  for (const Aabb& b : box)
    if (b.lo.x <= b.hi.x) out.push_back(b);
  return out;
}

}  // namespace rt
