// The hard cases of ray tracing (issue 8, docs/raytracer.md "Hard cases"), on every backend,
// in strict and fast, with every setting of the intersection knobs (triangle test and grid
// traversal; the self-intersection offset where rays leave surfaces). Each ray's answer is
// checked against a brute-force double-precision reference written here: a hit must be on a
// triangle the exact ray touches, at the exact distance (within float rounding), with no
// clearly closer triangle; a miss must have no triangle the exact ray clearly passes
// through. Rays whose answer sits on a knife edge (the exact ray grazes a triangle edge,
// or starts on a surface) may go either way, except where the case demands a hit
// (watertightness).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Camera.h"

namespace rt {
namespace {

using rill::Accuracy;

class HardCases : public ::testing::TestWithParam<std::string> {};

struct Config {
  Accuracy accuracy;
  TracerOptions knobs;
  std::string name() const {
    return std::string(rill::accuracy_name(accuracy)) + " " + knobs.str();
  }
};

// strict and fast, times both triangle tests and both traversals (the offset plays no
// part in Tracer::intersect).
std::vector<Config> intersect_configs() {
  std::vector<Config> c;
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast})
    for (TriangleTest t : {TriangleTest::MollerTrumbore, TriangleTest::Watertight})
      for (Traversal v : {Traversal::Incremental, Traversal::Recompute}) {
        TracerOptions o;
        o.triangle = t;
        o.traversal = v;
        c.push_back({a, o});
      }
  return c;
}

// ---- the double-precision reference ------------------------------------------------------

// A hit may go either way where the exact ray passes within kRayTol of the (relative)
// distance of a triangle's edge: the float ray, its direction rounded to 2^-24, passes a
// target point up to ~1e-7 of the distance away.
constexpr double kRayTol = 1e-6;
// In fast mode drivers contract and use relaxed division and square roots (NVIDIA's OpenCL
// under -cl-fast-relaxed-math: a few ulps per operation, docs/accuracy.md); over the ~20
// operations from the ray to an edge function that reaches ~1e-5 of the distance.
constexpr double kFastRayTol = 1e-5;

struct RefHit {
  double t = INFINITY;       // closest clear hit, +inf: none
  int32_t id = -1;           // its triangle
  std::vector<double> t_of;  // per triangle: t if the ray touches it (within the tolerance)
};

// The smallest altitude of a triangle: barycentric margin times it is a distance.
double min_altitude(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double twice_area = glm::length(glm::cross(b - a, c - a));
  return twice_area / std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
}

RefHit reference(const Scene& s, const glm::vec3& of, const glm::vec3& df, double ray_tol) {
  RefHit r;
  r.t_of.assign(s.triangle_count(), NAN);
  glm::dvec3 o(of), d(df);
  for (size_t k = 0; k < s.triangle_count(); ++k) {
    const glm::vec3* p = &s.positions[3 * k];
    if (!triangle_usable(p[0], p[1], p[2])) continue;
    const glm::dvec3 a(p[0]), b(p[1]), c(p[2]);
    double t = NAN, margin = NAN;
    const bool ahead = testing::hit_triangle_d(o, d, a, b, c, t, margin);
    const double tol = ray_tol * (glm::length(o) + std::fabs(t) + glm::length(a));
    // A ray that starts on a triangle (t = 0) may or may not report it: fast mode's t comes
    // out just above or below 0 (NVIDIA's OpenCL reported one).
    if (!ahead && !(std::fabs(t) <= tol)) continue;
    // The margin as a distance, against the float ray's uncertainty there.
    const double dist = margin * min_altitude(a, b, c);
    if (dist < -tol) continue;
    r.t_of[k] = t;
    if (dist > tol && t > tol && t < r.t) {
      r.t = t;
      r.id = static_cast<int32_t>(k);
    }
  }
  return r;
}

// The references for a ray set, computed once for all the configurations that trace it
// (the brute force is the slow part of these tests): keyed by the bytes of the scene's
// vertices and of the rays.
const std::vector<RefHit>& references(const Scene& s, const std::vector<glm::vec3>& o,
                                      const std::vector<glm::vec3>& d, double ray_tol) {
  static std::map<uint64_t, std::vector<RefHit>> cache;
  uint64_t h = 1469598103934665603ull ^ std::bit_cast<uint64_t>(ray_tol);  // FNV-1a
  for (const auto* v : {&s.positions, &o, &d}) {
    const auto* b = reinterpret_cast<const unsigned char*>(v->data());
    for (size_t i = 0; i < v->size() * sizeof(glm::vec3); ++i) h = (h ^ b[i]) * 1099511628211ull;
    h = (h ^ v->size()) * 1099511628211ull;
  }
  auto [it, fresh] = cache.try_emplace(h);
  if (fresh)
    for (size_t k = 0; k < o.size(); ++k) it->second.push_back(reference(s, o[k], d[k], ray_tol));
  return it->second;
}

// Checks the tracer's answers for the rays against the reference. require_hit: every ray
// must hit (the cases where a miss is a hole). Returns the number of misses.
int check_rays(const Scene& s, const Grid& g, const Config& c, const std::string& backend,
               const std::vector<glm::vec3>& o, const std::vector<glm::vec3>& d, bool require_hit,
               const std::string& what) {
  Tracer tracer(s, g, c.knobs);
  std::vector<int32_t> prim;
  std::vector<float> dist;
  tracer.intersect(backend, o, d, prim, dist, c.accuracy);
  EXPECT_EQ(prim.size(), o.size());
  // Float rounding of t: relative to the ray's length and the coordinates' magnitude.
  glm::vec3 lo, hi;
  scene_bounds(s, lo, hi);
  const double mag = std::max(glm::length(glm::dvec3(lo)), glm::length(glm::dvec3(hi)));
  const double ray_tol = c.accuracy == Accuracy::Strict ? kRayTol : kFastRayTol;
  const std::vector<RefHit>& refs = references(s, o, d, ray_tol);
  int wrong = 0, misses = 0;
  auto fail = [&](size_t k, const std::string& why) {
    if (++wrong <= 5)
      ADD_FAILURE() << what << " [" << c.name() << " on " << backend << "] ray " << k << " ("
                    << o[k].x << ", " << o[k].y << ", " << o[k].z << ") -> (" << d[k].x << ", "
                    << d[k].y << ", " << d[k].z << "): " << why;
  };
  for (size_t k = 0; k < o.size(); ++k) {
    const RefHit& r = refs[k];
    const double tol =
        1e-4 * (mag + glm::length(glm::dvec3(o[k])) + (std::isfinite(r.t) ? r.t : 0));
    if (std::isnan(dist[k])) fail(k, "NaN distance");
    if (prim[k] < 0) {
      ++misses;
      if (!(std::isinf(dist[k]) && dist[k] > 0)) fail(k, "a miss with a finite distance");
      bool touches = false;  // the exact ray meets a triangle, if only on an edge
      for (double t : r.t_of) touches = touches || t > tol;
      if (require_hit && touches) fail(k, "a miss where the exact ray hits (a hole)");
      // A clear hit beyond the start region must be found.
      else if (r.id >= 0 && r.t > tol)
        fail(k, "missed triangle " + std::to_string(r.id) + " at " + std::to_string(r.t));
      continue;
    }
    if (static_cast<size_t>(prim[k]) >= s.triangle_count() || std::isnan(r.t_of[prim[k]])) {
      fail(k, "hit triangle " + std::to_string(prim[k]) + " which the exact ray does not touch");
      continue;
    }
    const double tp = r.t_of[prim[k]];
    if (std::fabs(dist[k] - tp) > tol)
      fail(k, "distance " + std::to_string(dist[k]) + ", exact " + std::to_string(tp));
    if (r.id >= 0 && r.t + tol < dist[k] && r.t > tol)
      fail(k, "hit " + std::to_string(prim[k]) + " at " + std::to_string(dist[k]) +
                  " behind the closest " + std::to_string(r.id) + " at " + std::to_string(r.t));
  }
  EXPECT_EQ(wrong, 0) << what << " [" << c.name() << " on " << backend << "]";
  return misses;
}

Scene box_scene() {
  Scene s;
  s.name = "box";
  int m = s.add_material(Material{});
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  add_quad(s, {-4, -1.5f, -4}, {4, -1.5f, -4}, {4, -1.5f, 4}, {-4, -1.5f, 4}, m);  // a floor
  s.lights.push_back(Light{{0, 5, 0}, glm::vec3(1.0f)});
  return s;
}

// ---- 1. axis-parallel rays: +0, -0 and denormal direction components ----------------------

TEST_P(HardCases, AxisParallelRaysWithSignedZerosAndDenormals) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = box_scene();
  Grid g = build_grid(s, 4);
  const float dn = std::numeric_limits<float>::denorm_min(), sub = 1e-39f;
  const float zeros[] = {0.0f, -0.0f, dn, -dn, sub, -sub};
  std::vector<glm::vec3> o, d;
  for (float a : zeros)
    for (float b : zeros)
      for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f}) {
          glm::vec3 dir, org(0.3f, -0.2f, 0.1f);
          dir[axis] = sign;
          dir[(axis + 1) % 3] = a;
          dir[(axis + 2) % 3] = b;
          org[axis] = -5.0f * sign;  // from outside, towards the box
          o.push_back(org);
          d.push_back(dir);
          o.push_back(glm::vec3(0.3f, -0.2f, 0.1f));  // from inside the box
          d.push_back(dir);
          glm::vec3 on = org;  // along a cell plane of the grid (x = lo + 2 cells)
          on[(axis + 1) % 3] = g.lo[(axis + 1) % 3] + 2.0f * g.cell[(axis + 1) % 3];
          o.push_back(on);
          d.push_back(dir);
        }
  for (const Config& c : intersect_configs())
    EXPECT_EQ(check_rays(s, g, c, GetParam(), o, d, true, "axis-parallel"), 0);
}

// ---- 2. origins on cell faces, edges, lattice points and the grid's faces ----------------

TEST_P(HardCases, OriginsOnTheGridLatticeAndGrazingRays) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = box_scene();
  add_sphere(s, {0.5f, 1.6f, 0.2f}, 0.5f, 10, 6, 0, false);
  Grid g = build_grid(s, 5);
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> cell(0, 5);
  std::normal_distribution<float> nd(0.0f, 1.0f);
  std::vector<glm::vec3> o, d;
  auto lattice = [&](int i, int j, int k) {
    return g.lo +
           glm::vec3(static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)) * g.cell;
  };
  const glm::vec3 dirs[] = {{1, 1, 1}, {-1, 1, 1}, {1, -1, -1}, {1, 1, 0}, {0, -1, 1},
                            {1, 0, 0}, {0, -1, 0}, {0, 0, 1},   {-1, 0, 0}};
  for (int n = 0; n < 300; ++n) {
    glm::vec3 p = lattice(cell(rng), cell(rng), cell(rng));  // lattice points, grid corners
    if (n % 3 == 1) p.x += 0.37f * g.cell.x;                 // on a cell edge
    if (n % 3 == 2) p.y += 0.61f * g.cell.y, p.z += 0.29f * g.cell.z;  // on a cell face
    glm::vec3 dir = n < 200 ? dirs[n % 9] : glm::vec3(nd(rng), nd(rng), nd(rng));
    // Diagonals through lattice points, grazing along faces (the zero components).
    o.push_back(p);
    d.push_back(glm::normalize(dir));
    // Aimed at the box or sphere from the lattice point.
    glm::vec3 target(nd(rng) * 0.5f, nd(rng) * 0.8f, nd(rng) * 0.5f);
    o.push_back(p);
    d.push_back(glm::normalize(target - p));
  }
  for (const Config& c : intersect_configs())
    check_rays(s, g, c, GetParam(), o, d, false, "lattice origins");
}

// ---- 3. triangles in cell planes and at the bottom of the grid: no holes ------------------

TEST_P(HardCases, TrianglesInCellPlanesHaveNoHoles) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = box_scene();
  const int res = 6;
  Grid g0 = build_grid(s, res);
  // A floor exactly on an interior cell plane (y = lo + 2 cells), inside the scene's box so
  // that the grid does not change; and the scene's lowest floor (y = -1.5).
  const float y = g0.lo.y + 2.0f * g0.cell.y;
  add_quad(s, {-3.9f, y, -3.9f}, {3.9f, y, -3.9f}, {3.9f, y, 3.9f}, {-3.9f, y, 3.9f}, 0);
  Grid g = build_grid(s, res);
  ASSERT_EQ(g.lo, g0.lo);
  ASSERT_EQ(g.cell, g0.cell);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-3.8f, 3.8f);
  std::vector<glm::vec3> o, d;
  for (int n = 0; n < 200; ++n) {
    // Rays from above and below at the plane, outside the box (the box hides the rest).
    glm::vec3 t(u(rng), y, u(rng));
    if (std::fabs(t.x) < 1.2f && std::fabs(t.z) < 1.2f) continue;
    if (n % 4 == 0)
      t.x = g.lo.x + static_cast<float>(1 + n % (res - 1)) * g.cell.x;  // on cell edges
    glm::vec3 from = t + glm::vec3(u(rng) * 0.1f, (n % 2 ? 1.0f : -0.2f), u(rng) * 0.1f);
    o.push_back(from);
    d.push_back(glm::normalize(t - from));
    // The lowest floor (y = -1.5, just inside the grid's padded bottom face), from below
    // and grazing from outside the grid.
    glm::vec3 b(t.x, -1.5f, t.z);
    o.push_back(b + glm::vec3(u(rng) * 0.1f, n % 2 ? -0.3f : -1e-3f, u(rng) * 0.1f));
    d.push_back(glm::normalize(b - o.back()));
  }
  for (const Config& c : intersect_configs()) {
    check_rays(s, g, c, GetParam(), o, d, true, "floors in a cell plane and at the bottom");
  }
}

// ---- 4. watertightness: shared edges and vertices, rays from inside closed meshes --------

// A fan of n triangles around a centre, and a finely subdivided, jittered plane (shared
// vertices bit for bit). Rays aimed exactly at the vertices and at points of the edges.
Scene mesh_scene(std::vector<glm::vec3>& targets) {
  Scene s;
  int m = s.add_material(Material{});
  const glm::vec3 c(0.1f, 0.2f, 0.3f);
  const int n = 37;
  std::vector<glm::vec3> rim;
  for (int k = 0; k < n; ++k) {
    double a = 2.0 * M_PI * k / n;
    rim.emplace_back(c + glm::vec3(static_cast<float>(std::cos(a)), 0.013f * (k % 3),
                                   static_cast<float>(std::sin(a))));
  }
  for (int k = 0; k < n; ++k) {
    s.add_triangle(c, rim[k], rim[(k + 1) % n], m);
    targets.push_back(c + (rim[k] - c) * 0.3f);  // on a shared edge (rounded)
  }
  targets.push_back(c);
  // The subdivided plane: 24 x 24 quads, vertices jittered, at z = -2.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> j(-0.02f, 0.02f);
  const int q = 24;
  std::vector<glm::vec3> v((q + 1) * (q + 1));
  for (int a = 0; a <= q; ++a)
    for (int b = 0; b <= q; ++b)
      v[a * (q + 1) + b] =
          glm::vec3(-1.5f + 3.0f * a / q + j(rng), -1.5f + 3.0f * b / q + j(rng), -2.0f + j(rng));
  for (int a = 0; a < q; ++a)
    for (int b = 0; b < q; ++b) {
      const glm::vec3 &p00 = v[a * (q + 1) + b], &p10 = v[(a + 1) * (q + 1) + b],
                      &p11 = v[(a + 1) * (q + 1) + b + 1], &p01 = v[a * (q + 1) + b + 1];
      s.add_triangle(p00, p10, p11, m);
      s.add_triangle(p00, p11, p01, m);
      if (a > 0 && b > 0) {
        targets.push_back(p00);
        targets.push_back(0.5f * (p00 + p11));  // the diagonal
        targets.push_back(0.5f * (p00 + p10));
      }
    }
  return s;
}

TEST_P(HardCases, SharedEdgesAndVerticesAreWatertight) {
  RT_REQUIRE_BACKEND(GetParam());
  std::vector<glm::vec3> targets;
  Scene s = mesh_scene(targets);
  Grid g = build_grid(s, 0);
  std::vector<glm::vec3> o, d;
  const glm::vec3 eyes[] = {
      {0.3f, 3.0f, 0.2f}, {0.1f, -2.5f, 0.31f}, {2.0f, 0.7f, 5.0f}, {-0.4f, 0.1f, 4.0f}};
  for (const glm::vec3& e : eyes)
    for (const glm::vec3& t : targets) {
      // Only targets of the surface facing this eye and not hidden: the fan is at y ~ 0.2,
      // the plane at z ~ -2; the reference decides which is hit first.
      o.push_back(e);
      d.push_back(glm::normalize(t - e));
    }
  for (const Config& c : intersect_configs()) {
    // The watertight test must not leak; Moller-Trumbore may (counted in the benchmark).
    // Only in strict: in fast mode a driver may contract the edge functions into FMAs, which
    // breaks their exact antisymmetry on shared edges (NVIDIA's OpenCL does: docs/raytracer.md).
    const bool must =
        c.knobs.triangle == TriangleTest::Watertight && c.accuracy == Accuracy::Strict;
    check_rays(s, g, c, GetParam(), o, d, must, "fan and subdivided plane");
  }
}

TEST_P(HardCases, RaysFromInsideClosedMeshesAlwaysHit) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s;
  int m = s.add_material(Material{});
  add_sphere(s, {0.2f, -0.1f, 0.3f}, 1.3f, 23, 13, m, false);
  add_box(s, glm::vec3(3.0f), glm::vec3(4.0f, 5.0f, 3.5f), m);
  Grid g = build_grid(s, 0);
  std::mt19937 rng(5);
  std::normal_distribution<float> nd(0.0f, 1.0f);
  std::vector<glm::vec3> o, d;
  for (int n = 0; n < 600; ++n) {
    glm::vec3 from = n % 2 ? glm::vec3(0.2f, -0.1f, 0.3f) : glm::vec3(3.5f, 4.0f, 3.25f);
    // Strictly inside (the box's half depth is 0.25).
    from += glm::clamp(glm::vec3(nd(rng), nd(rng), nd(rng)) * 0.1f, -0.2f, 0.2f);
    // Towards vertices of the meshes (the hardest points) or anywhere.
    glm::vec3 dir;
    if (n % 3 == 0) {
      size_t t = static_cast<size_t>(n) % s.triangle_count();
      dir = s.positions[3 * t + (n % 5) % 3] - from;
    } else {
      dir = glm::vec3(nd(rng), nd(rng), nd(rng));
    }
    if (n % 2 == 0) dir = s.positions[3 * (s.triangle_count() - 1 - n % 12)] - from;
    o.push_back(from);
    d.push_back(glm::normalize(dir));
  }
  for (const Config& c : intersect_configs()) {
    const bool must =
        c.knobs.triangle == TriangleTest::Watertight && c.accuracy == Accuracy::Strict;
    check_rays(s, g, c, GetParam(), o, d, must, "inside closed meshes");
  }
}

// ---- 5. degenerate and needle triangles ----------------------------------------------------

TEST_P(HardCases, DegenerateAndNeedleTrianglesGiveNoNaN) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = box_scene();
  const size_t first = s.triangle_count();
  s.add_triangle({2, 0, 0}, {2, 0, 0}, {2, 1, 0}, 0);          // repeated vertex
  s.add_triangle({2, 0, 1}, {2, 0.5f, 1}, {2, 1, 1}, 0);       // collinear
  s.add_triangle({2, 2, 2}, {2, 2, 2}, {2, 2, 2}, 0);          // a point
  s.add_triangle({-2, 0, 0}, {-2, 1e-7f, 3}, {-2, 0, 3}, 0);   // a needle
  s.add_triangle({-3, 0, 0}, {-3, 0, 1e-30f}, {-3, 1, 0}, 0);  // zero-width in float edges
  Grid g = build_grid(s, 3);
  std::vector<glm::vec3> o, d;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-0.1f, 3.1f);
  for (int n = 0; n < 200; ++n) {
    glm::vec3 t(n % 2 ? 2.0f : -2.0f, u(rng) * 0.33f, u(rng));
    if (n % 5 == 0) t = glm::vec3(-2.0f, 0.0f, u(rng));  // along the needle
    glm::vec3 from(n % 2 ? 5.0f : -5.0f, 0.5f, 1.3f);
    o.push_back(from);
    d.push_back(glm::normalize(t - from));
  }
  for (const Config& c : intersect_configs()) {
    Tracer tracer(s, g, c.knobs);
    std::vector<int32_t> prim;
    std::vector<float> dist;
    tracer.intersect(GetParam(), o, d, prim, dist, c.accuracy);
    for (size_t k = 0; k < o.size(); ++k) {
      EXPECT_FALSE(std::isnan(dist[k])) << c.name() << " ray " << k;
      // A needle 1e-7 wide is below the float ray's resolution: a hit or a miss.
      EXPECT_TRUE(prim[k] < static_cast<int32_t>(first) ||
                  prim[k] == static_cast<int32_t>(first) + 3)
          << c.name() << " ray " << k << " hit degenerate triangle " << prim[k];
    }
  }
}

// ---- 7. coplanar overlapping triangles: the documented tie-break ------------------------

TEST_P(HardCases, CoplanarOverlapsPickTheSmallerIdEverywhere) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s;
  int m = s.add_material(Material{});
  add_quad(s, {-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, m);           // 0, 1
  s.add_triangle({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, m);                    // 2: a copy of 0
  s.add_triangle({-0.5f, 0, -0.7f}, {0.9f, 0, -0.3f}, {0.1f, 0, 0.8f}, m);  // 3: overlapping
  s.add_triangle({-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, m);                    // 4: a second copy of 0
  Grid g = build_grid(s, 3);
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-0.95f, 0.95f);
  std::vector<glm::vec3> o, d;
  for (int n = 0; n < 200; ++n) {
    glm::vec3 t(u(rng), 0.0f, u(rng));
    glm::vec3 from(u(rng), n % 2 ? 2.0f : -2.0f, u(rng));
    o.push_back(from);
    d.push_back(glm::normalize(t - from));
  }
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast})
    for (TriangleTest tt : {TriangleTest::MollerTrumbore, TriangleTest::Watertight}) {
      TracerOptions k;
      k.triangle = tt;
      Tracer tracer(s, g, k);
      std::vector<int32_t> prim, cpu_prim;
      std::vector<float> dist, cpu_dist;
      tracer.intersect(GetParam(), o, d, prim, dist, a);
      tracer.intersect("cpu", o, d, cpu_prim, cpu_dist, a);
      for (size_t n = 0; n < o.size(); ++n) {
        // Exact copies compute the same t from the same bits: the smaller id wins.
        EXPECT_NE(prim[n], 2) << "ray " << n;
        EXPECT_NE(prim[n], 4) << "ray " << n;
        EXPECT_GE(prim[n], 0) << "ray " << n;
        if (a == Accuracy::Strict) {  // and the choice is the same on every backend
          EXPECT_EQ(prim[n], cpu_prim[n]) << "ray " << n;
          EXPECT_EQ(std::bit_cast<uint32_t>(dist[n]), std::bit_cast<uint32_t>(cpu_dist[n]));
        }
      }
    }
}

// ---- 9. rays that miss the grid; a tiny object in a huge empty scene ----------------------

TEST_P(HardCases, MissesAndTheTeapotInAStadium) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s;
  int m = s.add_material(Material{});
  Transform tiny;
  tiny.scale = glm::vec3(1e-3f);
  tiny.translate = glm::vec3(3.0f, 2.0f, -1.0f);
  add_teapot(s, 3, m, tiny, false);
  const size_t pot = s.triangle_count();
  // The stadium: a ring of walls 1e3 across, far from the teapot.
  add_quad(s, {-500, -10, -500}, {500, -10, -500}, {500, 200, -500}, {-500, 200, -500}, m);
  add_quad(s, {-500, -10, 500}, {500, -10, 500}, {500, -10, -500}, {-500, -10, -500}, m);
  Grid g = build_grid(s, 0);
  std::vector<glm::vec3> o, d;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (size_t t = 0; t < pot; t += 7) {
    // Aimed at the centroid of a teapot triangle from near and from far away (not slivers,
    // which the float ray from 600 units cannot resolve).
    const glm::vec3* p = &s.positions[3 * t];
    if (min_altitude(p[0], p[1], p[2]) < 1e-4) continue;
    glm::vec3 c = (p[0] + p[1] + p[2]) / 3.0f;
    glm::vec3 from = t % 2 ? glm::vec3(3.1f, 2.05f, -0.9f) : glm::vec3(-400.0f, 150.0f, 300.0f);
    o.push_back(from);
    d.push_back(glm::normalize(c - from));
  }
  const size_t aimed = o.size();
  for (int n = 0; n < 60; ++n) {  // rays that miss the grid entirely, or leave it
    glm::vec3 from(u(rng) * 2000 - 1000, 300.0f + u(rng) * 10, u(rng) * 2000 - 1000);
    o.push_back(from);
    d.push_back(glm::normalize(glm::vec3(u(rng) - 0.5f, n % 2 ? 1.0f : 0.01f, u(rng) - 0.5f)));
  }
  for (const Config& c : intersect_configs()) {
    Tracer tracer(s, g, c.knobs);
    std::vector<int32_t> prim;
    std::vector<float> dist;
    tracer.intersect(GetParam(), o, d, prim, dist, c.accuracy);
    int pot_hits = 0;
    for (size_t k = 0; k < aimed; ++k) pot_hits += prim[k] >= 0 && prim[k] < int32_t(pot);
    // The teapot's patches are tessellated separately: only the watertight test never
    // slips through the seams.
    if (c.knobs.triangle == TriangleTest::Watertight) {
      EXPECT_EQ(pot_hits, static_cast<int>(aimed)) << c.name();
    } else {
      EXPECT_GE(pot_hits, static_cast<int>(aimed) - 2) << c.name();
    }
    for (size_t k = aimed; k < o.size(); ++k) EXPECT_EQ(prim[k], -1) << c.name() << " ray " << k;
    check_rays(s, g, c, GetParam(), o, d, false, "teapot in a stadium");
  }
}

// ---- 10. every traversal ends, whatever the ray ------------------------------------------

TEST_P(HardCases, NaNAndInfiniteRaysEndAsMisses) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = box_scene();
  Grid g = build_grid(s, 7);
  const float nan = std::nanf(""), inf = INFINITY;
  std::vector<glm::vec3> o = {{nan, 0, 5},        {0, 0, 5}, {0, 0, 5},          {inf, 0, 0},
                              {0, 0, 5},          {0, 0, 5}, {0.1f, 0.2f, 0.3f}, {1e30f, 0, 0},
                              {-inf, -inf, -inf}, {0, 0, 0}, {nan, nan, nan}};
  std::vector<glm::vec3> d = {
      {0, 0, -1},   {nan, 0, -1},          {0, nan, nan}, {-1, 0, 0}, {0, 0, 0},
      {inf, 0, -1}, {-0.0f, -0.0f, -0.0f}, {-1, 0, 0},    {1, 1, 1},  {nan, nan, nan},
      {1, 0, 0}};
  for (const Config& c : intersect_configs()) {
    Tracer tracer(s, g, c.knobs);
    std::vector<int32_t> prim;
    std::vector<float> dist;
    tracer.intersect(GetParam(), o, d, prim, dist, c.accuracy);  // returns: the loops ended
    for (size_t k = 0; k < o.size(); ++k) {
      if (c.accuracy == Accuracy::Strict) {
        EXPECT_EQ(prim[k], -1) << c.name() << " ray " << k;
        EXPECT_TRUE(std::isinf(dist[k])) << c.name() << " ray " << k;
      }
      EXPECT_TRUE(prim[k] >= -1 && prim[k] < static_cast<int32_t>(s.triangle_count()));
    }
  }
}

// The step limit is a bound, not a cut: a ray along the grid's longest voxel path (corner
// to corner, crossing every plane) still reaches a triangle in the far corner voxel.
TEST_P(HardCases, TheStepLimitNeverCutsATraversalShort) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s;
  int m = s.add_material(Material{});
  s.add_triangle({0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}, m);  // defines the near corner
  s.add_triangle({9.99f, 9.9f, 10}, {10, 9.9f, 10}, {10, 10, 10}, m);
  s.add_triangle({9.9f, 9.99f, 9.9f}, {10, 10, 9.9f}, {9.9f, 10, 10}, m);
  std::vector<glm::vec3> o, d;
  for (int n = 0; n < 16; ++n) {
    glm::vec3 from(1e-3f * n, 2e-3f, 1e-3f * (n % 3));
    glm::vec3 to = (s.positions[3 + n % 6 / 3 * 3] + s.positions[4 + n % 6 / 3 * 3] +
                    s.positions[5 + n % 6 / 3 * 3]) /
                   3.0f;
    o.push_back(from);
    d.push_back(glm::normalize(to - from));
  }
  // Cubic grids from one voxel to 128^3 (2M voxels).
  for (int res : {1, 48, 128}) {
    Grid g = build_grid(s, res);
    for (const Config& c : intersect_configs())
      EXPECT_EQ(check_rays(s, g, c, GetParam(), o, d, true, "corner to corner"), 0);
  }
}

// ---- 6 and 8: rendered: acne, contact shadows, lights on surfaces, the critical angle ----

// A lit floor with a box standing on it, translated and scaled. Returns per pixel whether
// the double-precision reference says the floor point is lit, shadowed, or neither (not the
// floor, or within a small margin of the shadow's edge).
struct ShadowCase {
  Scene scene;
  std::vector<int8_t> truth;  // 1 lit floor, 0 shadowed floor, -1 not compared
  glm::vec3 ambient_color;    // the colour of a shadowed floor pixel
};

ShadowCase shadow_case(float translate, float scale, int W, int H, float light_height) {
  ShadowCase c;
  Scene& s = c.scene;
  auto P = [&](float x, float y, float z) {
    return glm::vec3(translate) + scale * glm::vec3(x, y, z);
  };
  const glm::vec3 diffuse(0.8f);
  int m = s.add_material(Material{}.set("diffuse", diffuse));
  add_quad(s, P(-4, 0, -4), P(4, 0, -4), P(4, 0, 4), P(-4, 0, 4), m);
  const size_t floor_tris = s.triangle_count();
  Transform t;
  t.scale = glm::vec3(scale);
  t.translate = glm::vec3(translate);
  add_box(s, glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), m, t);
  s.lights.push_back(Light{P(1.7f, light_height, 1.1f), glm::vec3(1.0f)});
  s.camera = Camera{P(0.3f, 6.0f, 5.0f), P(0.3f, 0.0f, 0.5f), {0, 1, 0}, 50.0f};
  s.has_camera = true;
  s.width = W;
  s.height = H;
  s.options.max_depth = 0;
  s.background = glm::vec3(0.0f);
  c.ambient_color = s.options.ambient * diffuse;
  // The reference, in the scene's unscaled units (exact geometry).
  CameraFrame f = camera_frame(s.camera, W, H);
  const glm::dvec3 L = (glm::dvec3(s.lights[0].position) - glm::dvec3(translate)) / double(scale);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      glm::dvec3 e = (glm::dvec3(f.eye) - glm::dvec3(translate)) / double(scale);
      glm::dvec3 dir(camera_ray(f, i, j));
      int8_t v = -1;
      double best = INFINITY, margin_best = 0;
      int32_t id = -1;
      for (size_t k = 0; k < s.triangle_count(); ++k) {
        double tk, mk;
        glm::dvec3 a = (glm::dvec3(s.positions[3 * k]) - glm::dvec3(translate)) / double(scale);
        glm::dvec3 b = (glm::dvec3(s.positions[3 * k + 1]) - glm::dvec3(translate)) / double(scale);
        glm::dvec3 cc =
            (glm::dvec3(s.positions[3 * k + 2]) - glm::dvec3(translate)) / double(scale);
        if (testing::hit_triangle_d(e, dir, a, b, cc, tk, mk) && mk >= -1e-9 && tk < best) {
          best = tk;
          id = static_cast<int32_t>(k);
          margin_best = mk;
        }
      }
      if (id >= 0 && static_cast<size_t>(id) < floor_tris && margin_best > 1e-4) {
        glm::dvec3 p = e + best * dir;
        // The segment to the light against the box (|x|, |z| <= 0.5, 0 <= y <= 1): lit if
        // it passes at least 0.02 units (2% of the box) from it, shadowed if through it by
        // as much; the box touching the floor makes the shadow's contact region exact.
        double lo_t = 0, hi_t = 1;
        glm::dvec3 dd = L - p;
        const double bl[3] = {-0.5, 0.0, -0.5}, bh[3] = {0.5, 1.0, 0.5};
        auto clipped = [&](double grow) {
          double a0 = lo_t, a1 = hi_t;
          for (int ax = 0; ax < 3; ++ax) {
            double lo = bl[ax] - grow, hi = bh[ax] + grow;
            if (dd[ax] == 0) {
              if (p[ax] < lo || p[ax] > hi) return false;
              continue;
            }
            double t0 = (lo - p[ax]) / dd[ax], t1 = (hi - p[ax]) / dd[ax];
            a0 = std::max(a0, std::min(t0, t1));
            a1 = std::min(a1, std::max(t0, t1));
          }
          return a0 <= a1;
        };
        const bool near = clipped(0.02), deep = clipped(-0.02);
        if (!near) v = 1;
        if (deep && p.y > -1) v = 0;
      }
      c.truth.push_back(v);
    }
  return c;
}

struct Counts {
  int acne = 0, lost = 0, lit = 0, shadowed = 0, nonfinite = 0;
};

// A render of scene s at w x h on a backend with one self-intersection offset.
RenderResult render_with_offset(const Scene& s, const Grid& g, SelfIntersection off,
                                const std::string& backend, Accuracy a, int w, int h) {
  TracerOptions k;
  k.offset = off;
  Tracer tracer(s, g, k);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = backend;
  rs.accuracy = a;
  rs.width = w;
  rs.height = h;
  return tracer.render(rs, s.camera);
}

Counts count_errors(const ShadowCase& c, const RenderResult& r) {
  Counts n;
  for (size_t p = 0; p < r.color.size(); ++p) {
    const glm::vec3& col = r.color[p];
    if (!std::isfinite(col.x) || !std::isfinite(col.y) || !std::isfinite(col.z)) ++n.nonfinite;
    if (c.truth[p] < 0) continue;
    const bool dark = col.x <= c.ambient_color.x * 1.0001f + 1e-6f;
    if (c.truth[p] == 1) ++n.lit, n.acne += dark;
    if (c.truth[p] == 0) ++n.shadowed, n.lost += !dark;
  }
  return n;
}

TEST_P(HardCases, NoAcneFarFromTheOriginOrScaledTiny) {
  RT_REQUIRE_BACKEND(GetParam());
  const int W = 40, H = 30;
  struct Place {
    float translate, scale;
  };
  for (Place pl : {Place{0.0f, 1.0f}, Place{1e4f, 1.0f}, Place{-3e4f, 1.0f}, Place{0.0f, 1e-4f},
                   Place{10.0f, 1e-3f}}) {
    ShadowCase c = shadow_case(pl.translate, pl.scale, W, H, 3.0f);
    Grid g = build_grid(c.scene, 0);
    for (Accuracy a : {Accuracy::Strict, Accuracy::Fast})
      for (SelfIntersection off : {SelfIntersection::Epsilon, SelfIntersection::Scaled}) {
        RenderResult r = render_with_offset(c.scene, g, off, GetParam(), a, W, H);
        Counts n = count_errors(c, r);
        TracerOptions k;
        k.offset = off;
        const std::string what = "translate " + std::to_string(pl.translate) + " scale " +
                                 std::to_string(pl.scale) + " [" + rill::accuracy_name(a) + " " +
                                 k.str() + "]";
        EXPECT_GT(n.lit, W * H / 5) << what;
        EXPECT_GT(n.shadowed, 10) << what;
        EXPECT_EQ(n.nonfinite, 0) << what;
        EXPECT_EQ(n.acne, 0) << what << ": lit floor pixels in shadow";
        EXPECT_EQ(n.lost, 0) << what << ": shadowed floor pixels lit (contact shadow lost)";
      }
  }
}

TEST_P(HardCases, LightsOnAndNearSurfaces) {
  RT_REQUIRE_BACKEND(GetParam());
  const int W = 24, H = 18;
  for (float h : {1e-3f, 0.0f}) {
    // A light just above the floor, and one exactly in its plane (grazing: no direct light).
    ShadowCase c = shadow_case(0.0f, 1.0f, W, H, h);
    Grid g = build_grid(c.scene, 0);
    for (SelfIntersection off : {SelfIntersection::Epsilon, SelfIntersection::Scaled}) {
      RenderResult r = render_with_offset(c.scene, g, off, GetParam(), Accuracy::Strict, W, H);
      Counts n = count_errors(c, r);
      EXPECT_EQ(n.nonfinite, 0);
      if (h == 0.0f) {
        EXPECT_EQ(n.acne, n.lit) << "a light in the floor's plane lights it";
      }
    }
  }
  // A light exactly on a ceiling (as on an area light's quad): the ceiling does not shadow
  // the floor below it; and a box above the light (the shadow ray ends inside its cell
  // before reaching the box) does not either.
  Scene s;
  int m = s.add_material(Material{});
  add_quad(s, {-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}, m);
  add_quad(s, {-1, 3, -1}, {-1, 3, 1}, {1, 3, 1}, {1, 3, -1}, m);  // ceiling at y = 3
  add_box(s, {-0.3f, 5.0f, -0.3f}, {0.3f, 5.5f, 0.3f}, m);
  s.lights.push_back(Light{{0.25f, 3.0f, 0.125f}, glm::vec3(1.0f)});
  s.lights.push_back(Light{{0.0f, 4.0f, 0.0f}, glm::vec3(1.0f)});
  s.camera = Camera{{0.0f, 2.0f, 6.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}, 40.0f};
  s.options.max_depth = 0;
  for (int light = 0; light < 2; ++light) {
    Scene one = s;
    one.lights = {s.lights[static_cast<size_t>(light)]};
    Grid g = build_grid(one, 4);
    for (SelfIntersection off : {SelfIntersection::Epsilon, SelfIntersection::Scaled}) {
      RenderResult r = render_with_offset(one, g, off, GetParam(), Accuracy::Strict, W, H);
      TracerOptions k;
      k.offset = off;
      const CameraFrame f = camera_frame(one.camera, W, H);
      const glm::dvec3 L(one.lights[0].position);
      int floor = 0, dark = 0, wrong = 0;
      for (size_t p = 0; p < r.color.size(); ++p)
        if (r.prim[p] == 0 || r.prim[p] == 1) {
          ++floor;
          const bool is_dark = r.color[p].x <= 0.1f * 0.8f * 1.0001f;
          dark += is_dark;
          // Light 1 (at y = 4): the ceiling's shadow is where the segment to the light
          // crosses y = 3 within the quad; the box beyond the light casts none.
          const glm::dvec3 P =
              glm::dvec3(f.eye) +
              double(r.depth[p]) * glm::dvec3(camera_ray(f, int(p) % W, int(p) / W));
          const glm::dvec3 X = P + (3.0 - P.y) / (L.y - P.y) * (L - P);
          const double edge = std::max(std::fabs(X.x), std::fabs(X.z));
          if (light == 1 && ((edge < 0.98 && !is_dark) || (edge > 1.02 && is_dark))) ++wrong;
        }
      EXPECT_GT(floor, 20);
      // Light 0 sits on the ceiling and shines down: nothing of the floor is dark.
      if (light == 0) {
        EXPECT_EQ(dark, 0) << "light on the ceiling, " << k.str();
      } else {
        EXPECT_GT(dark, 5) << "the ceiling's shadow";
        EXPECT_EQ(wrong, 0) << "light above the ceiling, " << k.str();
      }
    }
  }
}

TEST_P(HardCases, RefractionAtTheCriticalAngleStaysFinite) {
  RT_REQUIRE_BACKEND(GetParam());
  // The camera inside a glass block looks at its faces over a wide field of view: the rays
  // meet them on both sides of the critical angle (asin(1 / 1.5) = 41.8 degrees).
  Scene s;
  Material glass;
  glass.shader = "glass";
  glass.set("transmit", 0.9f).set("reflect", 0.05f).set("ior", 1.5f);
  int g = s.add_material(glass);
  int m = s.add_material(Material{});
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f), g);
  add_quad(s, {-5, -2, -5}, {5, -2, -5}, {5, -2, 5}, {-5, -2, 5}, m);
  s.lights.push_back(Light{{2, 4, 3}, glm::vec3(1.0f)});
  s.camera = Camera{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {0, 1, 0}, 120.0f};
  Grid grid = build_grid(s, 0);
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast})
    for (TriangleTest tt : {TriangleTest::MollerTrumbore, TriangleTest::Watertight}) {
      TracerOptions k;
      k.triangle = tt;
      Tracer tracer(s, grid, k);
      RenderSettings rs;
      rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
      rs.backend = GetParam();
      rs.accuracy = a;
      rs.width = 33;
      rs.height = 33;
      rs.max_depth = 4;
      RenderResult r = tracer.render(rs, s.camera);
      int misses = 0;
      for (size_t p = 0; p < r.color.size(); ++p) {
        ASSERT_TRUE(std::isfinite(r.color[p].x) && std::isfinite(r.color[p].y) &&
                    std::isfinite(r.color[p].z))
            << "pixel " << p;
        // Inside the block every camera ray hits a face; Moller-Trumbore can slip through an
        // edge (the image's diagonals meet the cube's edges and corners).
        if (tt == TriangleTest::Watertight) {
          ASSERT_GE(r.prim[p], 0) << "pixel " << p << ": a hole";
        } else {
          misses += r.prim[p] < 0;
        }
      }
      EXPECT_LE(misses, 4) << "Moller-Trumbore holes";
    }
}

INSTANTIATE_TEST_SUITE_P(Backends, HardCases, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
