#include "rill/rt/accel/Grid.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <rill/Backend.h>
#include <tbb/parallel_for.h>

namespace rt {

namespace {

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool triangle_box_overlap(const glm::dvec3& c, const glm::dvec3& h, const glm::dvec3 tri[3]) {
  const glm::dvec3 v[3] = {tri[0] - c, tri[1] - c, tri[2] - c};
  // 1. The box's own axes: the triangle's bounding box against the box.
  for (int a = 0; a < 3; ++a) {
    double mn = std::min({v[0][a], v[1][a], v[2][a]}), mx = std::max({v[0][a], v[1][a], v[2][a]});
    if (mn > h[a] || mx < -h[a]) return false;
  }
  const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  // 2. The triangle's plane against the box.
  const glm::dvec3 n = glm::cross(e[0], e[1]);
  const double r = h.x * std::fabs(n.x) + h.y * std::fabs(n.y) + h.z * std::fabs(n.z);
  if (std::fabs(glm::dot(n, v[0])) > r) return false;
  // 3. The nine cross products of the edges with the box axes.
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 unit(0.0);
      unit[a] = 1.0;
      const glm::dvec3 axis = glm::cross(unit, e[i]);
      const double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]), p2 = glm::dot(axis, v[2]);
      const double rad =
          h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
      if (std::min({p0, p1, p2}) > rad || std::max({p0, p1, p2}) < -rad) return false;
    }
  return true;
}

bool triangle_usable(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  if (!finite3(a) || !finite3(b) || !finite3(c)) return false;
  // The kernel intersects with float edges e1 = b - a, e2 = c - a: they must not be parallel.
  const glm::vec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 n = glm::cross(glm::dvec3(e1), glm::dvec3(e2));
  return n.x != 0.0 || n.y != 0.0 || n.z != 0.0;
}

// The auto grid's bound on the build's triangle-voxel tests (build_grid).
constexpr double kAutoGridBoxVoxels = 256;
constexpr double kAutoGridMinTests = double{1 << 24};

glm::ivec3 auto_grid_resolution(const glm::dvec3& extent, size_t n, double density) {
  density = checked_grid_density(density);
  const double mx = std::max({extent.x, extent.y, extent.z});
  if (n == 0 || !(mx > 0)) return glm::ivec3(1);
  glm::dvec3 d = glm::max(extent, glm::dvec3(mx / 256.0));
  double k = std::cbrt(density * static_cast<double>(n) / (d.x * d.y * d.z));
  glm::ivec3 r;
  for (int a = 0; a < 3; ++a) r[a] = static_cast<int>(std::clamp(std::lround(d[a] * k), 1l, 256l));
  while (int64_t{r.x} * r.y * r.z > (int64_t{1} << 22))
    for (int a = 0; a < 3; ++a) r[a] = std::max(1, r[a] * 7 / 8);
  return r;
}

namespace {

// Calls fn(x, y, z) for each cell of the grid with corner lo, cell size cell and res cells
// that the triangle overlaps, the cells enlarged by margin on every side: the cells of its
// bounding box, then the exact test. The top level and the subgrids share it.
// The cells a..b (inclusive, per axis) of the triangle's bounding box enlarged by margin.
void bounding_cells(const glm::dvec3 tri[3], const glm::dvec3& lo, const glm::dvec3& cell,
                    const glm::ivec3& res, const glm::dvec3& margin, glm::ivec3& a, glm::ivec3& b) {
  for (int k = 0; k < 3; ++k) {
    const double mn = std::min({tri[0][k], tri[1][k], tri[2][k]}) - margin[k];
    const double mx = std::max({tri[0][k], tri[1][k], tri[2][k]}) + margin[k];
    a[k] = std::clamp(static_cast<int>(std::floor((mn - lo[k]) / cell[k])), 0, res[k] - 1);
    b[k] = std::clamp(static_cast<int>(std::floor((mx - lo[k]) / cell[k])), 0, res[k] - 1);
  }
}

// How many cells the triangle's bounding box covers: the exact tests its build makes.
double bounding_cell_count(const glm::dvec3 tri[3], const glm::dvec3& lo, const glm::dvec3& cell,
                           const glm::ivec3& res, const glm::dvec3& margin) {
  glm::ivec3 a, b;
  bounding_cells(tri, lo, cell, res, margin, a, b);
  return double(b.x - a.x + 1) * double(b.y - a.y + 1) * double(b.z - a.z + 1);
}

template <class Fn>
void for_each_overlapped_cell(const glm::dvec3 tri[3], const glm::dvec3& lo, const glm::dvec3& cell,
                              const glm::ivec3& res, const glm::dvec3& margin, Fn&& fn) {
  glm::ivec3 a, b;
  bounding_cells(tri, lo, cell, res, margin, a, b);
  const glm::dvec3 half = cell * 0.5 + margin;
  for (int z = a.z; z <= b.z; ++z)
    for (int y = a.y; y <= b.y; ++y)
      for (int x = a.x; x <= b.x; ++x)
        if (triangle_box_overlap(lo + (glm::dvec3(x, y, z) + 0.5) * cell, half, tri)) fn(x, y, z);
}

// The triangle's vertices in double precision.
void triangle_vertices(const Scene& s, size_t t, glm::dvec3 tri[3]) {
  for (int k = 0; k < 3; ++k) tri[k] = glm::dvec3(s.positions[3 * t + static_cast<size_t>(k)]);
}

// One voxel's subgrid: its resolution, and per sub-voxel (in index order) the count and the
// ascending triangle ids, concatenated.
struct Subgrid {
  int m = 0;
  std::vector<int32_t> counts, ids;
};

// A subgrid that does not pay is not built (m = 0 comes back): one that would list more than
// kSubgridMaxGrowth times the voxel's references in all (triangles that span the voxel, as in
// a pile of coplanar ones, are listed in every sub-voxel), or, for the smallest subgrids,
// whose sub-voxels would list on average more than half the voxel's triangles. The first
// bound also keeps the subgrids' memory within a fixed multiple of the top level's.
constexpr int64_t kSubgridMaxGrowth = 8;

Subgrid make_subgrid(const Grid& g, const Scene& s, int64_t v, double mag) {
  const glm::ivec2 e = g.voxels[static_cast<size_t>(v)];
  Subgrid r;
  const int m = r.m = static_cast<int>(std::clamp(std::lround(std::cbrt(kSubgridDensity * e.y)), 2l,
                                                  static_cast<long>(kSubgridMaxRes)));
  const int64_t cells = int64_t{m} * m * m;
  const int64_t max_refs = std::min(kSubgridMaxGrowth * e.y, cells * e.y / 2);
  const glm::ivec3 vi(v % g.res.x, (v / g.res.x) % g.res.y, v / (int64_t{g.res.x} * g.res.y));
  // The voxel's corner and the sub-voxel size as the kernel computes them, in float
  // (walk_subgrid); the margin covers the rounding of its DDA, as on the top level.
  glm::dvec3 corner, sub;
  for (int a = 0; a < 3; ++a) {
    corner[a] = static_cast<double>(g.lo[a] + static_cast<float>(vi[a]) * g.cell[a]);
    sub[a] = static_cast<double>(g.cell[a] / static_cast<float>(m));
  }
  const glm::dvec3 margin = sub * 1e-4 + glm::dvec3(4e-7 * mag);
  // Triangles whose boxes cover on average more than 4x the sub-voxels the growth bound
  // allows span the voxel: the subgrid would not pay, and finding that out by the exact tests
  // took seconds for a pile of 30000 large triangles (every voxel tested them all).
  double boxes = 0;
  for (int32_t i = 0; i < e.y; ++i) {
    glm::dvec3 tri[3];
    triangle_vertices(s, static_cast<size_t>(g.elements[static_cast<size_t>(e.x + i)]), tri);
    boxes += bounding_cell_count(tri, corner, sub, glm::ivec3(m), margin);
  }
  if (boxes > double(4 * kSubgridMaxGrowth * e.y)) {
    r.m = 0;
    return r;
  }
  std::vector<std::pair<int32_t, int32_t>> refs;  // (sub-voxel, triangle)
  for (int32_t i = 0; i < e.y; ++i) {
    const int32_t t = g.elements[static_cast<size_t>(e.x + i)];
    glm::dvec3 tri[3];
    triangle_vertices(s, static_cast<size_t>(t), tri);
    for_each_overlapped_cell(tri, corner, sub, glm::ivec3(m), margin, [&](int x, int y, int z) {
      refs.emplace_back(x + m * (y + m * z), t);
    });
    if (static_cast<int64_t>(refs.size()) > max_refs) {
      r.m = 0;  // does not pay
      return r;
    }
  }
  // Grouped by sub-voxel; stable, so each list stays ascending like the voxel's.
  std::stable_sort(refs.begin(), refs.end(),
                   [](const auto& p, const auto& q) { return p.first < q.first; });
  r.counts.assign(static_cast<size_t>(m) * m * m, 0);
  r.ids.reserve(refs.size());
  for (const auto& [k, t] : refs) {
    ++r.counts[static_cast<size_t>(k)];
    r.ids.push_back(t);
  }
  return r;
}

}  // namespace

int32_t parse_subgrid_min(const std::string& s) {
  if (s == "off") return kNoSubgrids;
  if (s == "auto") return kSubgridsAuto;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || end == s.c_str() || *end != '\0' || v < 1 || v > (1 << 20))
    throw SceneError("--subgrids expects auto, off or a triangle count in 1..1048576 (got '" + s +
                     "')");
  return static_cast<int32_t>(v);
}

int parse_grid_resolution(const std::string& s, const std::string& option) {
  if (s.empty() || s == "auto") return 0;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || v < 1 || v > 512)
    throw SceneError(option + " expects 'auto' or a number of voxels per axis in 1..512 (got '" +
                     s + "')");
  return static_cast<int>(v);
}

double checked_grid_density(double d) {
  if (!(d >= kGridDensityMin && d <= kGridDensityMax)) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", d);
    throw SceneError(std::string("grid density: expected voxels per triangle in 0.125..256 (got ") +
                     buf + ")");
  }
  return d;
}

double parse_grid_density(const std::string& s) {
  if (s == "auto") return kGridDensityAuto;
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || end == s.c_str() || *end != '\0' ||
      !(v >= kGridDensityMin && v <= kGridDensityMax))
    throw SceneError(
        "--grid-density expects auto or a number of voxels per triangle in 0.125..256 (got '" + s +
        "')");
  return v;
}

static_assert(kGridDensityAuto == SceneOptions{}.grid_density,
              "SceneOptions::grid_density's default is kGridDensityAuto");
static_assert(kGridDensityAuto < kGridDensityMin, "kGridDensityAuto is no density");
static_assert(kNoSubgrids == 0, "SceneOptions::subgrid_min's default (0) is kNoSubgrids");

void build_subgrids(Grid& g, const Scene& s, int32_t min_count) {
  const int64_t nv = g.voxel_count();
  if (min_count <= 0 || g.voxels.size() != static_cast<size_t>(nv)) return;
  double mag = 0;
  for (int a = 0; a < 3; ++a)
    mag = std::max(
        {mag, std::fabs(static_cast<double>(g.lo[a])), std::fabs(static_cast<double>(g.hi[a]))});
  std::vector<int64_t> dense;
  for (int64_t v = 0; v < nv; ++v)
    if (g.voxels[static_cast<size_t>(v)].y > min_count) dense.push_back(v);
  if (dense.empty()) return;
  // The subgrids are independent: built in parallel, then laid out in voxel order.
  std::vector<Subgrid> subs(dense.size());
  // Their memory, against what the grid's limit leaves (grid_memory_limit): counted as each
  // subgrid is built, so that an error comes before the memory is gone.
  const uint64_t limit = grid_memory_limit();
  const uint64_t used = static_cast<uint64_t>(g.voxels.size()) * kGridBytesPerVoxel +
                        static_cast<uint64_t>(g.elements.size()) * kGridBytesPerReference;
  std::atomic<uint64_t> added{0};
  tbb::parallel_for(size_t{0}, dense.size(), [&](size_t i) {
    subs[i] = make_subgrid(g, s, dense[i], mag);
    const uint64_t bytes = static_cast<uint64_t>(subs[i].counts.size()) * kGridBytesPerVoxel +
                           static_cast<uint64_t>(subs[i].ids.size()) * kGridBytesPerReference;
    if (used + (added += bytes) > limit)
      throw SceneError("the grid's subgrids need more than the limit of " +
                       std::to_string(limit >> 20) +
                       " MiB (half this machine's memory, or RILL_MAX_GRID_MB): use --subgrids "
                       "off, or a smaller --grid");
  });
  std::vector<int32_t> elements;
  elements.reserve(g.elements.size());
  size_t next = 0;
  for (int64_t v = 0; v < nv; ++v) {
    glm::ivec2& e = g.voxels[static_cast<size_t>(v)];
    if (next < dense.size() && dense[next] == v && subs[next].m == 0) ++next;  // did not pay
    if (next < dense.size() && dense[next] == v) {
      const Subgrid& sg = subs[next++];
      const size_t base = g.voxels.size();  // (g.voxels grows: e is not used after this)
      const int32_t m = sg.m;
      g.voxels[static_cast<size_t>(v)] = glm::ivec2(static_cast<int32_t>(base), -m);
      int32_t start = static_cast<int32_t>(elements.size());
      for (int32_t c : sg.counts) {
        g.voxels.emplace_back(start, c);
        start += c;
      }
      elements.insert(elements.end(), sg.ids.begin(), sg.ids.end());
      ++g.subgrids;
      continue;
    }
    const glm::ivec2 old = e;
    e.x = static_cast<int32_t>(elements.size());
    elements.insert(elements.end(), g.elements.begin() + old.x, g.elements.begin() + old.x + old.y);
  }
  if (elements.size() > (size_t{1} << 30)) throw SceneError("grid too large: reduce --grid");
  g.elements = std::move(elements);
}

void compute_empty_distances(Grid& g) {
  const glm::ivec3 r = g.res;
  const size_t top = static_cast<size_t>(g.voxel_count());
  if (g.voxels.size() < top) return;
  bool any = false;
  for (size_t v = 0; v < top; ++v) any = any || g.voxels[v].y != 0;
  if (!any) {
    for (size_t v = 0; v < top; ++v) g.voxels[v].x = 0;
    return;
  }
  // The chessboard distance transform (Rosenfeld & Pfaltz): a forward raster pass takes
  // the 13 of the 26 neighbours already visited, a backward pass the other 13; with unit
  // weights the two passes give the exact distance. The distances live in a copy of the
  // grid with a one-voxel border (kMaxSkip: outside counts as empty), so that the inner
  // loop needs no bounds checks.
  const int64_t X = r.x + 2, Y = r.y + 2, Z = r.z + 2;
  std::vector<int32_t> dist(static_cast<size_t>(X * Y * Z), kMaxSkip);
  auto inner = [&](int64_t x, int64_t y, int64_t z) {
    return static_cast<size_t>((x + 1) + X * ((y + 1) + Y * (z + 1)));
  };
  auto entry = [&](int64_t x, int64_t y, int64_t z) -> glm::ivec2& {
    return g.voxels[static_cast<size_t>(x + r.x * (y + r.y * z))];
  };
  for (int64_t z = 0; z < r.z; ++z)
    for (int64_t y = 0; y < r.y; ++y)
      for (int64_t x = 0; x < r.x; ++x)
        if (entry(x, y, z).y != 0) dist[inner(x, y, z)] = 0;
  // The neighbours that come before a voxel in the forward scan (z, then y, then x): all
  // have a smaller flat index.
  int64_t before[13];
  int nb = 0;
  for (int dz = -1; dz <= 0; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dz < 0 || dy < 0 || (dy == 0 && dx < 0)) before[nb++] = dx + X * (dy + Y * dz);
  for (int pass = 0; pass < 2; ++pass) {
    const int64_t sign = pass == 0 ? 1 : -1;
    for (int64_t zi = 0; zi < r.z; ++zi)
      for (int64_t yi = 0; yi < r.y; ++yi)
        for (int64_t xi = 0; xi < r.x; ++xi) {
          const size_t i =
              pass == 0 ? inner(xi, yi, zi) : inner(r.x - 1 - xi, r.y - 1 - yi, r.z - 1 - zi);
          int32_t best = dist[i];
          if (best == 0) continue;
          for (int k = 0; k < 13; ++k)
            best = std::min(
                best, dist[static_cast<size_t>(static_cast<int64_t>(i) + sign * before[k])] + 1);
          dist[i] = std::min(best, kMaxSkip);
        }
  }
  for (int64_t z = 0; z < r.z; ++z)
    for (int64_t y = 0; y < r.y; ++y)
      for (int64_t x = 0; x < r.x; ++x) {
        glm::ivec2& e = entry(x, y, z);
        if (e.y == 0) e.x = dist[inner(x, y, z)];
      }
}

int32_t subgrid_min_for(int32_t subgrid_min, const std::string& backend) {
  if (subgrid_min != kSubgridsAuto) return subgrid_min;
  return rill::backend(backend).runs_on_gpu() ? kNoSubgrids : kSubgridMin;
}

double grid_density_for(double density, const std::string& backend, size_t triangles,
                        Integrator integrator) {
  if (density != kGridDensityAuto) return density;
  return backend == "simd" && triangles >= kGridDensityLargeScene &&
                 integrator == Integrator::Whitted
             ? kGridDensitySimdLarge
             : kGridDensity;
}

Grid build_grid_for(const Scene& s, const std::string& backend) {
  return build_grid(
      s, s.options.grid, subgrid_min_for(s.options.subgrid_min, backend),
      grid_density_for(s.options.grid_density, backend, s.triangle_count(), s.options.integrator));
}

uint64_t grid_memory_limit() {
  if (const char* env = std::getenv("RILL_MAX_GRID_MB"); env != nullptr && *env != '\0') {
    char* end = nullptr;
    const unsigned long long mb = std::strtoull(env, &end, 10);
    if (*end != '\0' || mb < 1 || mb > (uint64_t{1} << 30))
      throw SceneError(std::string("RILL_MAX_GRID_MB='") + clipped(env) +
                       "' is not a size in MiB (1..1073741824)");
    return static_cast<uint64_t>(mb) << 20;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return uint64_t{4} << 30;  // unknown: 4 GiB
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) / 2;
}

namespace {

std::string mib(uint64_t bytes) {
  char b[64];
  std::snprintf(b, sizeof b, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return b;
}

std::string res_str(const glm::ivec3& r) {
  return std::to_string(r.x) + "x" + std::to_string(r.y) + "x" + std::to_string(r.z);
}

// Throws when the grid's estimated memory is over the limit, naming both.
void check_grid_memory(const glm::ivec3& res, uint64_t voxels, uint64_t refs, uint64_t limit) {
  const uint64_t need = voxels * kGridBytesPerVoxel + refs * kGridBytesPerReference;
  if (need <= limit) return;
  const bool env = std::getenv("RILL_MAX_GRID_MB") != nullptr;
  throw SceneError(
      "the grid " + res_str(res) + " (" + std::to_string(voxels) + " voxels" +
      (refs > 0 ? ", " + std::to_string(refs) + " triangle references so far" : "") +
      ") needs about " + mib(need) + ", over the limit of " + mib(limit) +
      (env ? " (RILL_MAX_GRID_MB)" : " (half this machine's memory; RILL_MAX_GRID_MB sets it)") +
      ": use a smaller --grid, or --grid auto");
}

}  // namespace

Grid build_grid(const Scene& s, int resolution, int32_t subgrid_min, double density) {
  const auto start = std::chrono::steady_clock::now();
  // Left to the renderer with no backend named (tools, fuzzing): the GPU backends' density.
  if (density == kGridDensityAuto) density = kGridDensity;
  Grid g;
  const size_t n = s.triangle_count();
  std::vector<uint8_t> usable(n);
  // Triangles that move are not in the grid: the tracer finds them in its BVH (Bvh.h).
  std::vector<uint8_t> moving(n);
  for (const AnimatedObject& o : s.animation.objects)
    std::fill(moving.begin() + static_cast<std::ptrdiff_t>(o.first),
              moving.begin() + static_cast<std::ptrdiff_t>(o.first + o.count), 1);
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t t = 0; t < n; ++t) {
    if (moving[t]) {
      ++g.moving;
      continue;
    }
    const glm::vec3* p = &s.positions[3 * t];
    if (!finite3(p[0]) || !finite3(p[1]) || !finite3(p[2])) {
      ++g.non_finite;
      continue;
    }
    if (!triangle_usable(p[0], p[1], p[2])) {
      ++g.degenerate;
      continue;
    }
    usable[t] = 1;
    ++g.usable;
    for (int k = 0; k < 3; ++k) {
      lo = glm::min(lo, glm::dvec3(p[k]));
      hi = glm::max(hi, glm::dvec3(p[k]));
    }
  }
  if (g.usable == 0) {
    g.voxels.assign(1, glm::ivec2(0));
    g.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return g;
  }
  // Pad the box: flat scenes get some thickness, and no triangle lies on its faces.
  const glm::dvec3 ext = hi - lo;
  const double mx = std::max({ext.x, ext.y, ext.z});
  const double mag = std::max({std::fabs(lo.x), std::fabs(lo.y), std::fabs(lo.z), std::fabs(hi.x),
                               std::fabs(hi.y), std::fabs(hi.z)});
  const double pad = 1e-4 * mx + 1e-6 * mag + 1e-30;
  lo -= glm::dvec3(pad);
  hi += glm::dvec3(pad);
  g.res =
      resolution > 0 ? glm::ivec3(resolution) : auto_grid_resolution(hi - lo, g.usable, density);
  if (resolution <= 0) {
    // The build tests each triangle against every voxel of its bounding box. Where many
    // triangles span much of the scene (a pile of large overlapping ones), the voxels auto
    // picks for their count make that quadratic: 8000 such triangles took 15 s, 30000 over a
    // minute. Coarser, until the voxels tested stay within kAutoGridBoxVoxels per triangle
    // (ordinary meshes test a few each, so their grids do not change).
    const double budget =
        std::max(kAutoGridMinTests, kAutoGridBoxVoxels * static_cast<double>(g.usable));
    const glm::dvec3 extent = hi - lo;
    for (int round = 0; round < 64; ++round) {
      const glm::dvec3 cell = extent / glm::dvec3(g.res);
      double tested = 0;
      for (size_t t = 0; t < n && tested <= budget; ++t) {
        if (!usable[t]) continue;
        glm::dvec3 tri[3];
        triangle_vertices(s, t, tri);
        tested += bounding_cell_count(tri, lo, cell, g.res, glm::dvec3(0.0));
      }
      if (tested <= budget || g.res == glm::ivec3(1)) break;
      for (int a = 0; a < 3; ++a) g.res[a] = std::max(1, g.res[a] * 3 / 4);
    }
  }
  g.lo = glm::vec3(lo);
  for (int a = 0; a < 3; ++a) {
    // The float cell size must cover the padded box: round up.
    float c = static_cast<float>((hi[a] - static_cast<double>(g.lo[a])) / g.res[a]);
    while (static_cast<double>(g.lo[a]) + static_cast<double>(c) * g.res[a] < hi[a])
      c = std::nextafter(c, INFINITY);
    g.cell[a] = c;
    g.hi[a] = static_cast<float>(static_cast<double>(g.lo[a]) + static_cast<double>(c) * g.res[a]);
  }

  const glm::dvec3 glo(g.lo), cell(g.cell);
  const glm::dvec3 margin = cell * 1e-4 + glm::dvec3(4e-7 * mag);
  const int64_t nv = g.voxel_count();
  // (--grid allows 512^3; voxel indices are 32-bit here and in the kernel.)
  if (nv > INT32_MAX) throw SceneError("grid too large: reduce --grid");
  // Memory, before allocating: the voxels now, the triangle references as they come.
  const uint64_t limit = grid_memory_limit();
  check_grid_memory(g.res, static_cast<uint64_t>(nv), 0, limit);
  // A resolution far above what auto picks is mostly empty space: it costs memory and build
  // time and does not make tracing faster.
  if (resolution > 0) {
    const glm::ivec3 a = auto_grid_resolution(hi - lo, g.usable, density);
    const int64_t auto_voxels = int64_t{a.x} * a.y * a.z;
    if (nv > (int64_t{1} << 20) && nv > 64 * auto_voxels)
      g.warnings.push_back("the grid " + res_str(g.res) + " has " + std::to_string(nv) +
                           " voxels for " + std::to_string(g.usable) + " triangles, " +
                           std::to_string(nv / std::max<int64_t>(auto_voxels, 1)) +
                           " times what --grid auto picks (" + res_str(a) +
                           "): mostly empty space, which costs memory (about " +
                           mib(static_cast<uint64_t>(nv) * kGridBytesPerVoxel) +
                           ") and build time without making tracing faster");
  }
  // Each triangle's voxels, once (triangles in id order), then a counting sort by voxel:
  // each voxel's list stays ascending.
  std::vector<std::pair<int32_t, int32_t>> refs;  // (voxel, triangle)
  for (size_t t = 0; t < n; ++t) {
    if (!usable[t]) continue;
    glm::dvec3 tri[3];
    triangle_vertices(s, t, tri);
    for_each_overlapped_cell(tri, glo, cell, g.res, margin, [&](int x, int y, int z) {
      refs.emplace_back(x + g.res.x * (y + g.res.y * z), static_cast<int32_t>(t));
    });
    check_grid_memory(g.res, static_cast<uint64_t>(nv), refs.size(), limit);  // a compare
  }
  if (refs.size() > (size_t{1} << 30)) throw SceneError("grid too large: reduce --grid");
  g.voxels.assign(static_cast<size_t>(nv), glm::ivec2(0));
  for (const auto& r : refs) ++g.voxels[static_cast<size_t>(r.first)].y;
  int32_t first = 0;
  for (glm::ivec2& v : g.voxels) {
    v.x = first;
    first += v.y;
  }
  g.elements.resize(refs.size());
  std::vector<int32_t> fill(static_cast<size_t>(nv), 0);
  for (const auto& [v, t] : refs) {
    const glm::ivec2 e = g.voxels[static_cast<size_t>(v)];
    g.elements[static_cast<size_t>(e.x + fill[static_cast<size_t>(v)]++)] = t;
  }
  build_subgrids(g, s, subgrid_min);
  compute_empty_distances(g);
  g.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return g;
}

}  // namespace rt
