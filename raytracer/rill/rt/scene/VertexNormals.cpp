// Angle weighting (Thuermer and Wuethrich 1998) by default rather than area weighting: a
// face's weight at a vertex is its angle there, so the normal does not depend on how a polygon
// was cut into triangles (the angles of a planar polygon's triangles at a vertex add up to the
// polygon's own) nor on how long the faces' edges are, which area weighting lets a single
// sliver or a big face dominate. Area and area-times-angle weights are there for meshes made
// for them (and to match other tools). Computed in double precision, so the result is the
// same on every backend (the normals are scene data, uploaded as any OBJ's `vn`).
#include "rill/rt/scene/VertexNormals.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rt {

NormalWeighting parse_normal_weighting(const std::string& s) {
  if (s == "angle") return NormalWeighting::Angle;
  if (s == "area") return NormalWeighting::Area;
  if (s == "area_angle") return NormalWeighting::AreaAngle;
  throw std::invalid_argument("'" + s + "' is not a normal weighting (angle, area, area_angle)");
}

std::vector<glm::vec3> vertex_normals(const NormalMesh& mesh, float crease_degrees,
                                      NormalWeighting weighting) {
  const size_t tris = mesh.positions.size() / 3;
  std::vector<glm::dvec3> face(tris, glm::dvec3(0.0));
  std::vector<double> weight(3 * tris, 0.0);  // each corner's weight: its angle, area or both
  for (size_t t = 0; t < tris; ++t) {
    const glm::dvec3 p[3] = {glm::dvec3(mesh.positions[3 * t]),
                             glm::dvec3(mesh.positions[3 * t + 1]),
                             glm::dvec3(mesh.positions[3 * t + 2])};
    const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double len = glm::length(n);
    if (!(len > 0) || !std::isfinite(len)) continue;  // no area: no normal, no weight
    face[t] = n / len;
    const double area = 0.5 * len;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 a = glm::normalize(p[(k + 1) % 3] - p[k]);
      const glm::dvec3 b = glm::normalize(p[(k + 2) % 3] - p[k]);
      const double corner = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
      weight[3 * t + k] = weighting == NormalWeighting::Angle  ? corner
                          : weighting == NormalWeighting::Area ? area
                                                               : area * corner;
    }
  }
  // The corners of each vertex (counting sort by vertex index).
  int32_t vmax = -1;
  for (int32_t v : mesh.vertex) vmax = std::max(vmax, v);
  std::vector<uint32_t> start(static_cast<size_t>(vmax) + 2, 0), corners(3 * tris);
  for (int32_t v : mesh.vertex) ++start[static_cast<size_t>(v) + 1];
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for (size_t c = 0; c < 3 * tris; ++c)
    corners[fill[static_cast<size_t>(mesh.vertex[c])]++] = static_cast<uint32_t>(c);

  const double cos_crease = std::cos(double(crease_degrees) * M_PI / 180.0);
  auto group = [&](size_t t) { return mesh.group.empty() ? 1u : mesh.group[t]; };
  std::vector<glm::vec3> out(3 * tris, glm::vec3(0.0f));
  for (size_t c = 0; c < 3 * tris; ++c) {
    const size_t t = c / 3;
    if (face[t] == glm::dvec3(0.0)) continue;
    glm::dvec3 sum = face[t] * weight[c];
    // Group 0 (`s off`): the face's own normal.
    if (group(t) != 0) {
      const size_t v = static_cast<size_t>(mesh.vertex[c]);
      for (uint32_t k = start[v]; k < start[v + 1]; ++k) {
        const uint32_t o = corners[k];
        const size_t u = o / 3;
        if (u == t || group(u) != group(t)) continue;
        // Within the crease angle of this corner's own face (a face that bends further on
        // gives a hard edge here, whatever it does to the faces between).
        if (glm::dot(face[u], face[t]) >= cos_crease) sum += face[u] * weight[o];
      }
    }
    const double len = glm::length(sum);
    out[c] = glm::vec3(len > 0 ? sum / len : face[t]);
  }
  return out;
}

bool keeps_flat(const glm::vec3 p[3], const glm::vec3* computed, glm::vec3 n[3]) {
  const glm::vec3 face = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  bool flat = true;
  for (int k = 0; k < 3; ++k) {
    n[k] = computed[k];
    flat = flat && (n[k] == glm::vec3(0.0f) || glm::dot(n[k], face) > 1.0f - 1e-6f);
  }
  return flat;
}

}  // namespace rt
