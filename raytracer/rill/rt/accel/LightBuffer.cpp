// Builds the light buffer (LightBuffer.h) on the CPU, in double precision.
#include "rill/rt/accel/LightBuffer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace rt {

namespace {

// The in-face axes of a face's major axis: x -> (y, z), y -> (x, z), z -> (x, y).
constexpr int kU[3] = {1, 0, 0};
constexpr int kV[3] = {2, 2, 1};

// The distance from the origin to triangle (a, b, c): Ericson's closest point on a triangle
// (Real-Time Collision Detection, 5.1.5), for the point 0.
double origin_triangle_distance(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 p(0.0);
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return glm::length(a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return glm::length(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return glm::length(a + ab * (d1 / (d1 - d3)));
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return glm::length(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return glm::length(a + ac * (d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return glm::length(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denom = va + vb + vc;
  if (!(std::fabs(denom) > 0)) return 0.0;  // degenerate: the grid leaves these out anyway
  return glm::length(a + ab * (vb / denom) + ac * (vc / denom));
}

// A convex polygon of at most 7 vertices: a triangle clipped by four planes.
// Room for four clips of a triangle even where rounding makes a clipped polygon slightly
// non-convex (a clip then adds up to one vertex per edge, not one in all): 3 x 2^4.
struct Polygon {
  glm::dvec3 v[48];
  int n = 0;
};

// Sutherland-Hodgman: the part of the polygon where dot(n, p) >= 0.
Polygon clip(const Polygon& poly, const glm::dvec3& n) {
  Polygon out;
  for (int i = 0; i < poly.n; ++i) {
    const glm::dvec3& a = poly.v[i];
    const glm::dvec3& b = poly.v[(i + 1) % poly.n];
    const double da = glm::dot(n, a), db = glm::dot(n, b);
    if (da >= 0) out.v[out.n++] = a;
    if ((da >= 0) != (db >= 0)) out.v[out.n++] = a + (b - a) * (da / (da - db));
  }
  return out;
}

// The range of cells [lo, hi] covering in-face coordinates [a, b] (in [-1, 1]).
glm::ivec2 cell_span(double a, double b, int res) {
  auto cell = [&](double x) {
    return std::clamp(static_cast<int>(std::floor((x + 1.0) * 0.5 * res)), 0, res - 1);
  };
  return {cell(std::max(a, -1.0)), cell(std::min(b, 1.0))};
}

// A float at or below the distance from the light of any point the triangle test may report
// on a triangle whose exact distance is d: its rounding is a few ulps of the scene's scale,
// and slack (1e-5 of it) is far above.
float near_bound(double d, double slack) {
  const double nd = (d - slack) * (1.0 - 1e-6);
  float near = nd > 0 ? std::nextafter(static_cast<float>(nd), 0.0f) : 0.0f;
  if (static_cast<double>(near) > nd) near = 0.0f;
  return near;
}

// The angular margin of a triangle dmin from the light, in a face's (u, v) coordinates: the
// float lookup (about 1e-7), the test's rounding seen from the light (slack / dmin), and the
// shadow ray's own direction, rounded to about 1.5e-7 and seen from the light at a hit dmin
// away: 1.5e-7 |q| / dmin, within 4 slack / dmin for origins up to `reach` from the light
// (the kernels send rays from farther to the grid).
double triangle_margin(double dmin, double slack) {
  return 2e-5 + (dmin > 0 ? 4.0 * slack / dmin : 4.0);
}

// Added to the margin where a cell's planes clip a triangle in double precision: far above
// that arithmetic's rounding, far below the margin.
constexpr double kClipSlack = 1e-9;

struct Entry {
  float near;
  int32_t tri;
  bool refine;  // near may be tightened to the cell (cell_near)
  bool operator<(const Entry& o) const { return near < o.near || (near == o.near && tri < o.tri); }
};

// The smallest distance from the light (the origin) of the triangle's points whose
// directions lie in cell (i, j) of face (axis, sign), widened by `margin` in the face's
// (u, v) coordinates as the cells' lists are (build_light_buffer): the triangle clipped by
// the four planes through the light that bound those directions (together they keep the
// face's side, w > 0). Negative when no point of the triangle lies there.
double cell_near(const Polygon& tri, int axis, int sign, int i, int j, int res, double margin) {
  const double sg = sign ? -1.0 : 1.0;
  const int U = kU[axis], V = kV[axis];
  const double step = 2.0 / res;
  Polygon poly = tri;
  for (int c : {U, V}) {
    const int k = c == U ? i : j;
    const double lo = -1.0 + step * k - margin, hi = -1.0 + step * (k + 1) + margin;
    glm::dvec3 n(0.0);
    n[c] = 1.0;  // q[c] - lo w >= 0, w = sg q[axis]
    n[axis] = -lo * sg;
    poly = clip(poly, n);
    n[c] = -1.0;  // hi w - q[c] >= 0
    n[axis] = hi * sg;
    poly = clip(poly, n);
  }
  if (poly.n == 0) return -1.0;
  double d = HUGE_VAL;
  for (int k = 1; k + 1 < poly.n; ++k)
    d = std::min(d, origin_triangle_distance(poly.v[0], poly.v[k], poly.v[k + 1]));
  // (Clipping a triangle leaves none or at least three vertices; a degenerate piece, whose
  // distance is 0/0, tightens nothing.)
  return poly.n < 3 || !(d < HUGE_VAL) ? 0.0 : d;
}

}  // namespace

glm::ivec3 light_buffer_cell(const glm::vec3& q, int res) {
  // The kernels' rule (kernel/Intersector.cpp, occluders), in the same float operations.
  const glm::vec3 a = glm::abs(q);
  const bool ax = a.x >= a.y && a.x >= a.z;
  const bool ay = !ax && a.y >= a.z;
  const int axis = ax ? 0 : (ay ? 1 : 2);
  const float w = a[axis];
  const int face = 2 * axis + (q[axis] < 0.0f ? 1 : 0);
  const float w1 = w > 0.0f ? w : 1.0f;
  auto cell = [&](float c) {
    const float x = (c / w1 + 1.0f) * (0.5f * static_cast<float>(res));
    const float f = std::floor(x);
    const int i =
        std::isnan(f) ? 0 : static_cast<int>(std::clamp(f, -1.0f, static_cast<float>(res)));
    return std::clamp(i, 0, res - 1);
  };
  return {face, cell(q[kU[axis]]), cell(q[kV[axis]])};
}

LightBuffer build_light_buffer(const Scene& s, const Grid& grid, int res, int max_list,
                               uint64_t max_visits, size_t max_tightened) {
  const auto t0 = std::chrono::steady_clock::now();
  LightBuffer lb;
  if (res <= 0 || s.lights.empty() || grid.empty()) return lb;
  if (res > kLightBufferMaxRes)
    throw std::invalid_argument("light buffer: " + std::to_string(res) +
                                " cells per face edge (at most " +
                                std::to_string(kLightBufferMaxRes) + ")");
  const uint64_t cell_count =
      6ull * static_cast<uint64_t>(res) * static_cast<uint64_t>(res) * s.lights.size();
  if (cell_count > (1ull << 24))
    throw std::invalid_argument(
        "light buffer: " + std::to_string(s.lights.size()) + " lights at " + std::to_string(res) +
        " cells per face edge make " + std::to_string(cell_count) +
        " cells (at most 2^24); choose a smaller --light-buffer (options.light_buffer in a "
        "scene file)");
  lb.res = res;
  // The triangles the grid holds: the static, usable ones.
  std::vector<char> in_grid(s.triangle_count(), 0);
  for (int32_t t : grid.elements) in_grid[static_cast<size_t>(t)] = 1;
  std::vector<int32_t> ids;
  for (size_t t = 0; t < in_grid.size(); ++t)
    if (in_grid[t]) ids.push_back(static_cast<int32_t>(t));

  // The scene's scale: what the triangle test's rounding is relative to.
  double scale = 0;
  for (int32_t t : ids)
    for (int k = 0; k < 3; ++k)
      scale = std::max(
          scale, static_cast<double>(glm::length(s.positions[static_cast<size_t>(t) * 3 + k])));
  for (const Light& l : s.lights)
    scale = std::max(scale, static_cast<double>(glm::length(l.position)));

  // Cells visited (a triangle's rectangle of cells on a face): the build's time, bounded.
  std::atomic<uint64_t> visits{0};
  std::atomic<bool> over_budget{false};
  const size_t per_face = static_cast<size_t>(res) * static_cast<size_t>(res);
  const size_t per_light = 6 * per_face;
  lb.cells.resize(per_light * s.lights.size());
  const double slack = 1e-5 * scale;
  // Static triangles and the lights are within `scale` of the origin, so are the shadow
  // rays' origins on them: 2 scale from a light at most. Only a moving object far outside
  // the static scene puts one farther.
  lb.reach = static_cast<float>(32.0 * scale);
  for (size_t li = 0; li < s.lights.size(); ++li) {
    if (s.lights[li].type == LightType::Directional) {
      // No position to look from: every cell sends its shadow rays to the grid.
      for (size_t c = 0; c < per_light; ++c)
        lb.cells[li * per_light + c] = {static_cast<int32_t>(lb.tris.size()), -1};
      lb.fallback_cells += per_light;
      continue;
    }
    const glm::dvec3 L(s.lights[li].position);
    // Each chunk of triangles lists its (cell, entry) pairs; then a counting sort by cell.
    constexpr size_t kChunk = 1024;
    std::vector<std::vector<std::pair<uint32_t, Entry>>> parts((ids.size() + kChunk - 1) / kChunk);
    // Per cell, how many triangles it lists so far: past max_list the cell sends its rays to
    // the grid, so no more of its entries are kept (memory stays within cells x (max_list +
    // 1) entries whatever the triangles).
    std::vector<std::atomic<uint32_t>> listed(per_light);
    tbb::parallel_for(size_t(0), parts.size(), [&](size_t part) {
      auto& out = parts[part];
      const size_t end = std::min(ids.size(), (part + 1) * kChunk);
      for (size_t k = part * kChunk; k < end && !over_budget.load(std::memory_order_relaxed); ++k) {
        const int32_t t = ids[k];
        Polygon tri;
        tri.n = 3;
        for (int c = 0; c < 3; ++c)
          tri.v[c] = glm::dvec3(s.positions[static_cast<size_t>(t) * 3 + c]) - L;
        const double dmin = origin_triangle_distance(tri.v[0], tri.v[1], tri.v[2]);
        // A lower bound of the distance from the light of any point the triangle test may
        // report (its rounding is a few ulps of the scene's scale; 1e-5 of it is far above).
        const float near = near_bound(dmin, slack);
        const double margin = triangle_margin(dmin, slack);
        for (int axis = 0; axis < 3; ++axis)
          for (int sign = 0; sign < 2; ++sign) {
            const double sg = sign ? -1.0 : 1.0;
            const int U = kU[axis], V = kV[axis];
            // The face's pyramid, widened so that directions on an edge belong to both
            // faces, by the triangle's margin too (a ray towards a triangle close to the
            // light swings by as much as the margin allows, across a face's edge as well as
            // within it): four planes through the light. A triangle wholly outside one of
            // them misses the face.
            const double kWide = 1.0 + 1e-3 + 2.0 * margin;
            glm::dvec3 planes[4];
            int pn = 0;
            for (int c : {U, V})
              for (double cs : {1.0, -1.0}) {
                glm::dvec3 n(0.0);
                n[axis] = sg * kWide;
                n[c] = -cs;
                planes[pn++] = n;
              }
            Polygon poly = tri;
            bool outside = false;
            for (const glm::dvec3& n : planes) {
              int in = 0;
              for (int c = 0; c < 3; ++c) in += glm::dot(n, tri.v[c]) >= 0;
              if (in == 0) outside = true;
            }
            if (outside) continue;
            for (const glm::dvec3& n : planes) {
              poly = clip(poly, n);
              if (poly.n == 0) break;
            }
            if (poly.n == 0) continue;
            double u0 = 2, u1 = -2, v0 = 2, v1 = -2;
            bool whole = margin >= 1.0;
            for (int c = 0; c < poly.n && !whole; ++c) {
              const glm::dvec3& q = poly.v[c];
              const double w = sg * q[axis];
              // A polygon that reaches the light itself covers every direction of the face.
              if (!(w > 1e-9 * scale)) {
                whole = true;
                break;
              }
              u0 = std::min(u0, q[U] / w);
              u1 = std::max(u1, q[U] / w);
              v0 = std::min(v0, q[V] / w);
              v1 = std::max(v1, q[V] / w);
            }
            if (whole) u0 = v0 = -1, u1 = v1 = 1;
            const glm::ivec2 iu = cell_span(u0 - margin, u1 + margin, res);
            const glm::ivec2 iv = cell_span(v0 - margin, v1 + margin, res);
            const size_t base = static_cast<size_t>(2 * axis + sign) * per_face;
            const uint64_t cells =
                static_cast<uint64_t>(iu.y - iu.x + 1) * static_cast<uint64_t>(iv.y - iv.x + 1);
            if (visits.fetch_add(cells, std::memory_order_relaxed) + cells > max_visits) {
              over_budget = true;
              return;
            }
            for (int j = iv.x; j <= iv.y; ++j)
              for (int i = iu.x; i <= iu.y; ++i) {
                const uint32_t c = static_cast<uint32_t>(base + static_cast<size_t>(j) * res +
                                                         static_cast<size_t>(i));
                if (listed[c].fetch_add(1, std::memory_order_relaxed) <=
                    static_cast<uint32_t>(max_list))
                  out.push_back({c, Entry{near, t, !whole}});
              }
          }
      }
    });
    if (over_budget) break;
    std::vector<uint32_t> count(per_light + 1, 0);
    for (const auto& part : parts)
      for (const auto& ce : part) ++count[ce.first + 1];
    for (size_t c = 0; c < per_light; ++c) count[c + 1] += count[c];
    std::vector<Entry> sorted(count[per_light]);
    {
      std::vector<uint32_t> at(count.begin(), count.end() - 1);
      for (const auto& part : parts)
        for (const auto& ce : part) sorted[at[ce.first]++] = ce.second;
    }
    parts.clear();
    // Each entry's distance tightened to the part of its triangle that the cell's rays can
    // reach (cell_near), where the cells hold few entries in all: a shadow ray then stops
    // before the triangles whose nearest point lies outside its cell, and skips those whose
    // box of cells touched its cell but not the triangle itself.
    const bool tighten = sorted.size() <= max_tightened;
    std::vector<uint32_t> kept(per_light, 0);
    tbb::parallel_for(size_t(0), per_light, [&](size_t c) {
      if (listed[c] > static_cast<uint32_t>(max_list)) return;
      const auto first = sorted.begin() + count[c], last = sorted.begin() + count[c + 1];
      auto end = last;
      if (tighten) {
        const int face = static_cast<int>(c / per_face);
        const int j = static_cast<int>(c % per_face) / res,
                  i = static_cast<int>(c % per_face) % res;
        end = std::remove_if(first, last, [&](Entry& e) {
          if (!e.refine) return false;
          Polygon tri;
          tri.n = 3;
          for (int k = 0; k < 3; ++k)
            tri.v[k] = glm::dvec3(s.positions[static_cast<size_t>(e.tri) * 3 + k]) - L;
          const double dmin = origin_triangle_distance(tri.v[0], tri.v[1], tri.v[2]);
          const double d = cell_near(tri, face / 2, face % 2, i, j, res,
                                     triangle_margin(dmin, slack) + kClipSlack);
          if (d < 0) return true;  // the triangle misses the cell's (widened) directions
          e.near = std::max(e.near, near_bound(d, slack));
          return false;
        });
      }
      std::sort(first, end);
      kept[c] = static_cast<uint32_t>(end - first);
    });
    for (size_t c = 0; c < per_light; ++c) {
      glm::ivec2& cell = lb.cells[li * per_light + c];
      if (listed[c] > static_cast<uint32_t>(max_list)) {
        cell = {static_cast<int32_t>(lb.tris.size()), -1};
        ++lb.fallback_cells;
        continue;
      }
      cell = {static_cast<int32_t>(lb.tris.size()), static_cast<int32_t>(kept[c])};
      for (uint32_t k = count[c]; k < count[c] + kept[c]; ++k) {
        lb.tris.push_back(sorted[k].tri);
        lb.near.push_back(sorted[k].near);
      }
    }
  }
  if (over_budget) {
    LightBuffer none;
    none.skipped = "its triangles cover more than " + std::to_string(max_visits) + " cells at " +
                   std::to_string(res) + " cells per face edge";
    none.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return none;
  }
  lb.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return lb;
}

int light_buffer_res(const Scene& s) {
  if (s.options.light_buffer != kLightBufferAuto) return s.options.light_buffer;
  // Directional lights have no cube of directions around a point (build_light_buffer): a
  // scene of them alone has no use for one.
  bool positioned = false;
  for (const Light& l : s.lights) positioned = positioned || l.type != LightType::Directional;
  if (!positioned) return 0;
  // Its build visits every triangle once per light (about 0.1-0.3 us each on one core):
  // beyond 2^26 pairs (seconds) auto leaves it off, and the shadow rays walk the grid.
  if (static_cast<uint64_t>(s.triangle_count()) * s.lights.size() > (1ull << 26)) return 0;
  int res = kLightBufferRes;
  auto cells = [&](int r) {
    return 6ull * static_cast<uint64_t>(r) * static_cast<uint64_t>(r) * s.lights.size();
  };
  while (res > 8 && cells(res) > (1ull << 22)) res /= 2;
  return cells(res) > (1ull << 22) ? 0 : res;  // tens of thousands of lights: none
}

int parse_light_buffer(const std::string& s) {
  if (s == "auto") return kLightBufferAuto;
  if (s == "off") return kLightBufferOff;
  try {
    size_t used = 0;
    const int n = std::stoi(s, &used);
    if (used == s.size() && n >= 1 && n <= kLightBufferMaxRes) return n;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument("--light-buffer expects auto, off or cells per face edge 1.." +
                              std::to_string(kLightBufferMaxRes) + " (got '" + s + "')");
}

}  // namespace rt
