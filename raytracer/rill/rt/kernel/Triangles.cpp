// Uploads the triangles for the kernels (Triangles.h).
#include "rill/rt/kernel/Triangles.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

namespace {

// Per triangle, one of its three vertices' values (3 per triangle in `v`), or `fallback`
// for every triangle when `v` is empty.
template <class T>
std::vector<T> corner(const std::vector<T>& v, size_t n, int k, const std::vector<T>& fallback) {
  if (v.empty()) return fallback;
  std::vector<T> r(n);
  for (size_t t = 0; t < n; ++t) r[t] = v[3 * t + static_cast<size_t>(k)];
  return r;
}

}  // namespace

void Triangles::upload(const Scene& scene, const TracerOptions& K, const Features& F) {
  upload_geometry(scene, K, F);
  const size_t n = scene.triangle_count();
  if (F.vertex_colors) {
    const std::vector<glm::vec3> white(n, glm::vec3(1.0f));
    upload_padded(c0, corner(scene.colors, n, 0, white));
    upload_padded(c1, corner(scene.colors, n, 1, white));
    upload_padded(c2, corner(scene.colors, n, 2, white));
  }
  if (F.texcoords) upload_padded(uv, scene.texcoords);
  upload_padded(material, std::vector<int32_t>(scene.material));
}

namespace {

// What the kernels hold of triangles first .. end - 1 of the scene, in the order of the
// triangles: the Moller-Trumbore form and the unit geometric normal, and (as asked) the
// vertices and the vertex normals.
struct Geometry {
  std::vector<glm::vec3> v0, e1, e2, ng, v1, v2, n0, n1, n2;
};

// The geometry arrays the knobs and features call for, each with the Geometry field that
// fills it: the one list that geometry(), upload_geometry and update_geometry go by.
using GeometryArray =
    std::pair<rill::Array<rill::Float3> Triangles::*, std::vector<glm::vec3> Geometry::*>;
std::vector<GeometryArray> geometry_arrays(const TracerOptions& K, const Features& F) {
  std::vector<GeometryArray> a{{&Triangles::v0, &Geometry::v0},
                               {&Triangles::e1, &Geometry::e1},
                               {&Triangles::e2, &Geometry::e2},
                               {&Triangles::ng, &Geometry::ng}};
  if (K.triangle == TriangleTest::Watertight)
    a.insert(a.end(), {{&Triangles::v1, &Geometry::v1}, {&Triangles::v2, &Geometry::v2}});
  if (F.vertex_normals)
    a.insert(a.end(), {{&Triangles::n0, &Geometry::n0},
                       {&Triangles::n1, &Geometry::n1},
                       {&Triangles::n2, &Geometry::n2}});
  return a;
}

Geometry geometry(const Scene& scene, const TracerOptions& K, const Features& F, size_t first,
                  size_t end) {
  const size_t n = end - first;
  Geometry g;
  for (const auto& [array, field] : geometry_arrays(K, F)) (g.*field).resize(n);
  const bool watertight = K.triangle == TriangleTest::Watertight;
  // Per triangle on its own (so the same bits on any number of threads): dynamic scenes do
  // this every frame.
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, n, 8192), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const size_t t = first + i;
          const glm::vec3* p = &scene.positions[3 * t];
          g.v0[i] = p[0];
          g.e1[i] = p[1] - p[0];
          g.e2[i] = p[2] - p[0];
          glm::dvec3 c = glm::cross(glm::dvec3(g.e1[i]), glm::dvec3(g.e2[i]));
          double l = glm::length(c);
          g.ng[i] = (std::isfinite(l) && l > 0) ? glm::vec3(c / l) : glm::vec3(0.0f, 1.0f, 0.0f);
          if (watertight) {
            g.v1[i] = p[1];
            g.v2[i] = p[2];
          }
          if (F.vertex_normals) {
            const bool given = !scene.normals.empty();
            g.n0[i] = given ? scene.normals[3 * t] : g.ng[i];
            g.n1[i] = given ? scene.normals[3 * t + 1] : g.ng[i];
            g.n2[i] = given ? scene.normals[3 * t + 2] : g.ng[i];
          }
        }
      });
  return g;
}

}  // namespace

void Triangles::upload_geometry(const Scene& scene, const TracerOptions& K, const Features& F) {
  Geometry g = geometry(scene, K, F, 0, scene.triangle_count());
  for (const auto& [array, field] : geometry_arrays(K, F))
    upload_padded(this->*array, std::move(g.*field));
}

void Triangles::update_geometry(const Scene& scene, const TracerOptions& K, const Features& F,
                                size_t first, size_t end) {
  if (first == end) return;
  if (end > scene.triangle_count() || first > end ||
      static_cast<int64_t>(scene.triangle_count()) != v0.size())
    throw std::logic_error("Triangles::update_geometry: triangles " + std::to_string(first) + ".." +
                           std::to_string(end) + " of a scene of " +
                           std::to_string(scene.triangle_count()) + " after an upload of " +
                           std::to_string(v0.size()));
  const Geometry g = geometry(scene, K, F, first, end);
  for (const auto& [array, field] : geometry_arrays(K, F))
    (this->*array).upload(static_cast<int64_t>(first), g.*field);
}

}  // namespace rt
