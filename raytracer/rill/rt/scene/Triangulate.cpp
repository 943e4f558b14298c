// Ear clipping in double precision on the projection of the polygon onto the plane of its
// Newell normal (the best-fit plane of a non-planar polygon, oriented by its winding).
#include "rill/rt/scene/Triangulate.h"

#include <cmath>
#include <numeric>

namespace rt {

namespace {

using P2 = glm::dvec2;

double orient(const P2& a, const P2& b, const P2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Whether segments ab and cd share a point. Adjacent edges are not passed in.
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c),
               d4 = orient(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
    return true;
  // Touching: a vertex on the other segment (a repeated vertex, a polygon that pinches).
  auto on = [](const P2& p, const P2& q, const P2& r, double c3) {
    return c3 == 0 && std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) &&
           std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  return on(c, d, a, d1) || on(c, d, b, d2) || on(a, b, c, d3) || on(a, b, d, d4);
}

bool self_intersecting(const std::vector<P2>& p) {
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return true;
    }
  return false;
}

// Convex: no right turn anywhere, and the turns add up to one full turn (a pentagram turns
// left everywhere but twice around). Collinear vertices count as convex: the fan gives them
// zero-area triangles, as it always did.
bool convex(const std::vector<P2>& p, double eps) {
  const size_t n = p.size();
  double turning = 0;
  for (size_t i = 0; i < n; ++i) {
    const P2& a = p[(i + n - 1) % n];
    const P2& b = p[i];
    const P2& c = p[(i + 1) % n];
    const P2 u = b - a, v = c - b;
    const double cr = u.x * v.y - u.y * v.x;
    if (cr < -eps * glm::length(u) * glm::length(v)) return false;
    turning += std::atan2(cr, glm::dot(u, v));
  }
  return turning < 3.0 * M_PI;
}

// Inside or on triangle abc (counter-clockwise).
bool in_triangle(const P2& a, const P2& b, const P2& c, const P2& p) {
  return orient(a, b, p) >= 0 && orient(b, c, p) >= 0 && orient(c, a, p) >= 0;
}

}  // namespace

std::vector<std::array<uint32_t, 3>> fan(size_t n) {
  std::vector<std::array<uint32_t, 3>> t;
  for (size_t k = 1; k + 1 < n; ++k)
    t.push_back({0u, static_cast<uint32_t>(k), static_cast<uint32_t>(k + 1)});
  return t;
}

Triangulation triangulate(std::span<const glm::vec3> poly) {
  const size_t n = poly.size();
  Triangulation r;
  r.triangles = fan(n);
  if (n <= 3) return r;
  // Newell's normal: twice the vector area, the normal of the best-fit plane.
  glm::dvec3 normal(0.0), centre(0.0);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 a(poly[i]), b(poly[(i + 1) % n]);
    normal +=
        glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
    centre += a;
  }
  centre /= double(n);
  const double len = glm::length(normal);
  if (!(len > 0) || !std::isfinite(len)) {
    r.shape = PolygonShape::Degenerate;
    return r;
  }
  const glm::dvec3 w = normal / len;
  // A basis (u, v) of the plane with u x v = w: the projection keeps the winding
  // counter-clockwise.
  const glm::dvec3 axis = std::abs(w.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(axis, w));
  const glm::dvec3 v = glm::cross(w, u);
  std::vector<P2> p(n);
  for (size_t i = 0; i < n; ++i) {
    const glm::dvec3 d = glm::dvec3(poly[i]) - centre;
    p[i] = P2(glm::dot(d, u), glm::dot(d, v));
  }
  if (convex(p, 1e-12)) return r;  // the fan: ids as they always were
  if (n > kMaxEarClipVertices) {
    r.shape = PolygonShape::TooLarge;
    return r;
  }
  if (self_intersecting(p)) {
    r.shape = PolygonShape::SelfIntersecting;
    return r;
  }
  // Ear clipping: the remaining polygon as a list; each step cuts the first ear in list
  // order (docs/primitive-ids.md spells this out: it fixes the triangles' ids).
  std::vector<uint32_t> left(n);
  std::iota(left.begin(), left.end(), 0u);
  r.triangles.clear();
  while (left.size() > 3) {
    const size_t m = left.size();
    size_t ear = m;
    // A zero-area ear (three collinear vertices) only when no proper one is left.
    for (int pass = 0; pass < 2 && ear == m; ++pass)
      for (size_t k = 0; k < m && ear == m; ++k) {
        const uint32_t a = left[(k + m - 1) % m], b = left[k], c = left[(k + 1) % m];
        const double area = orient(p[a], p[b], p[c]);
        if (pass == 0 ? !(area > 0) : !(area >= 0)) continue;
        bool empty = true;
        for (size_t j = 0; j < m && empty; ++j) {
          const uint32_t q = left[j];
          if (q == a || q == b || q == c || p[q] == p[a] || p[q] == p[b] || p[q] == p[c]) continue;
          empty = !in_triangle(p[a], p[b], p[c], p[q]);
        }
        if (empty) ear = k;
      }
    if (ear == m) {  // rounding left no ear: fan what is left, and say so
      r.shape = PolygonShape::Degenerate;
      for (size_t k = 1; k + 1 < m; ++k) r.triangles.push_back({left[0], left[k], left[k + 1]});
      return r;
    }
    r.triangles.push_back({left[(ear + m - 1) % m], left[ear], left[(ear + 1) % m]});
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  r.triangles.push_back({left[0], left[1], left[2]});
  return r;
}

}  // namespace rt
