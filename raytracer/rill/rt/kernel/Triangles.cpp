// Uploads the triangles for the kernels (Triangles.h).
#include "rill/rt/kernel/Triangles.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

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

void Triangles::upload_geometry(const Scene& scene, const TracerOptions& K, const Features& F) {
  const size_t n = scene.triangle_count();
  std::vector<glm::vec3> vv0(n), ve1(n), ve2(n), vng(n);
  // Per triangle on its own (so the same bits on any number of threads): dynamic scenes do
  // this every frame.
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, n, 8192), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t t = r.begin(); t != r.end(); ++t) {
          const glm::vec3* p = &scene.positions[3 * t];
          vv0[t] = p[0];
          ve1[t] = p[1] - p[0];
          ve2[t] = p[2] - p[0];
          glm::dvec3 c = glm::cross(glm::dvec3(ve1[t]), glm::dvec3(ve2[t]));
          double l = glm::length(c);
          vng[t] = (std::isfinite(l) && l > 0) ? glm::vec3(c / l) : glm::vec3(0.0f, 1.0f, 0.0f);
        }
      });
  upload_padded(v0, vv0);
  upload_padded(e1, ve1);
  upload_padded(e2, ve2);
  upload_padded(ng, vng);
  if (K.triangle == TriangleTest::Watertight) {
    upload_padded(v1, corner(scene.positions, n, 1, {}));
    upload_padded(v2, corner(scene.positions, n, 2, {}));
  }
  if (F.vertex_normals) {
    upload_padded(n0, corner(scene.normals, n, 0, vng));
    upload_padded(n1, corner(scene.normals, n, 1, vng));
    upload_padded(n2, corner(scene.normals, n, 2, vng));
  }
}

}  // namespace rt
