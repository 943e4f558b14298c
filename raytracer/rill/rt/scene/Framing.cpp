// The framing camera (Framing.h; docs/camera.md, "The framing camera"). Computed in double
// and rounded to float at the end.
#include "rill/rt/scene/Framing.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rt {

namespace {

constexpr double kFramingPi = 3.14159265358979323846;
constexpr double kFramingFill = 0.95;  // the box's corners reach 95% of the field of view

bool framing_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec3 unit_axis(int k, double sign = 1.0) {
  glm::dvec3 v(0.0);
  v[k] = sign;
  return v;
}

// The nearest distance along dir (from the box's centre) from which every corner of [lo, hi]
// lies in front of the eye and within kFramingFill of the field of view of a W x H image: 60 steps
// of bisection, keeping the upper end.
double fit_distance(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& dir,
                    const glm::dvec3& up_axis, double tan_half, double aspect) {
  const glm::dvec3 center = (lo + hi) * 0.5, fw = -dir;
  const glm::dvec3 right = glm::normalize(glm::cross(fw, up_axis));
  const glm::dvec3 up = glm::cross(right, fw);
  const double ty = tan_half * kFramingFill, tx = ty * aspect;
  auto fits = [&](double dist) {
    const glm::dvec3 eye = center + dir * dist;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
      const glm::dvec3 v = p - eye;
      const double z = glm::dot(v, fw);
      if (z <= 0 || std::fabs(glm::dot(v, right)) > tx * z || std::fabs(glm::dot(v, up)) > ty * z)
        return false;
    }
    return true;
  };
  const double radius = glm::length(hi - lo) * 0.5;
  double far = radius / std::sin(std::atan(std::min(tx, ty))) * 1.05, near = 0.0;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (near + far);
    (fits(mid) ? far : near) = mid;
  }
  return far;
}

// The area of the triangles lying in the box face of axis k on side sign (all three vertices
// within eps of its plane).
double face_coverage(const Scene& s, int k, double sign, const glm::dvec3& lo, const glm::dvec3& hi,
                     double eps) {
  const double plane = sign > 0 ? hi[k] : lo[k];
  double area = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3* p = &s.positions[3 * t];
    if (!framing_finite(p[0]) || !framing_finite(p[1]) || !framing_finite(p[2])) continue;
    bool on = true;
    for (int v = 0; v < 3; ++v) on = on && std::fabs(p[v][k] - plane) <= eps;
    if (on)
      area += 0.5 * glm::length(glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]),
                                           glm::dvec3(p[2]) - glm::dvec3(p[0])));
  }
  return area;
}

}  // namespace

UpAxis parse_up_axis(const std::string& s) {
  if (s == "auto") return UpAxis::Auto;
  if (s == "x") return UpAxis::X;
  if (s == "y") return UpAxis::Y;
  if (s == "z") return UpAxis::Z;
  throw std::invalid_argument("--up-axis expects auto, x, y or z (got '" + s + "')");
}

int resolve_up_axis(UpAxis up, const glm::vec3& lo, const glm::vec3& hi) {
  switch (up) {
    case UpAxis::X:
      return 0;
    case UpAxis::Y:
      return 1;
    case UpAxis::Z:
      return 2;
    case UpAxis::Auto:
      break;
  }
  const glm::dvec3 e = glm::dvec3(hi) - glm::dvec3(lo);
  const bool tall_z = e.z >= 1.2 * e.x && e.z >= 1.2 * e.y;
  return tall_z && e.y >= e.x ? 2 : 1;
}

bool is_room(const Scene& s) {
  glm::vec3 lo, hi;
  if (!scene_bounds(s, lo, hi)) return false;
  const glm::dvec3 center = (glm::dvec3(lo) + glm::dvec3(hi)) * 0.5;
  double inward = 0, total = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3* p = &s.positions[3 * t];
    if (!framing_finite(p[0]) || !framing_finite(p[1]) || !framing_finite(p[2])) continue;
    const glm::dvec3 a(p[0]), b(p[1]), c(p[2]);
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double area = glm::length(n);
    total += area;
    if (glm::dot(n, center - (a + b + c) / 3.0) > 0) inward += area;
  }
  return total > 0 && inward > 0.5 * total;
}

Camera framing_camera(const Scene& s, int width, int height, UpAxis up_choice) {
  Camera c;
  glm::vec3 lo_f, hi_f;
  if (!scene_bounds(s, lo_f, hi_f)) return c;
  const glm::dvec3 lo(lo_f), hi(hi_f), center = (lo + hi) * 0.5;
  const double diag = glm::length(hi - lo);
  // A scene of no extent (every vertex at one point) has no view to frame: the eye would sit
  // on the point it looks at.
  if (!(diag > 0))
    throw SceneError("the scene has no extent (every vertex is at " + vec_str(lo_f) +
                     "): the default camera cannot frame it; give the scene a camera (a JSON "
                     "scene's \"camera\")");
  const int u = resolve_up_axis(up_choice, lo_f, hi_f);
  const glm::dvec3 up = unit_axis(u);
  // The front: +z for y up and x up, -y for z up (as a z-up modeller's front view).
  const glm::dvec3 front = u == 2 ? unit_axis(1, -1.0) : unit_axis(2);
  const double tan_half = std::tan(c.fov_y * 0.5 * kFramingPi / 180.0);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  glm::dvec3 eye, look_at = center;
  if (!is_room(s)) {
    // From the front, slightly above.
    const glm::dvec3 dir = glm::normalize(front + 0.3 * up);
    eye = center + dir * fit_distance(lo, hi, dir, up, tan_half, aspect);
  } else {
    // A room: seen through its least covered wall (the front first among equals), from
    // outside that wall when it is open (under half covered), else from just inside it.
    int best_k = -1;
    double best_sign = 0, best_cover = HUGE_VAL;
    const glm::dvec3 sides[4] = {front, -front, glm::cross(up, front), -glm::cross(up, front)};
    for (const glm::dvec3& n : sides) {
      int k = 0;
      while (n[k] == 0) ++k;
      const double cover = face_coverage(s, k, n[k], lo, hi, 1e-4 * diag);
      if (cover < best_cover) best_k = k, best_sign = n[k], best_cover = cover;
    }
    const glm::dvec3 n = unit_axis(best_k, best_sign);
    const glm::dvec3 e = hi - lo;
    const double face_area = e[(best_k + 1) % 3] * e[(best_k + 2) % 3];
    if (best_cover < 0.5 * face_area) {
      eye = center + n * fit_distance(lo, hi, n, up, tan_half, aspect);
    } else {
      // Just inside the wall (5% of the depth in), the field of view widened to take in the
      // opposite wall at kFramingFill (between 10 and 150 degrees).
      const double depth = e[best_k];
      eye = center + n * (0.45 * depth);
      const glm::dvec3 fw = -n, right = glm::normalize(glm::cross(fw, up));
      const double z = 0.95 * depth;
      const double half_w = 0.5 * std::fabs(glm::dot(e, right)),
                   half_h = 0.5 * std::fabs(glm::dot(e, up));
      const double t = std::max(half_w / aspect, half_h) / z / kFramingFill;
      c.fov_y =
          static_cast<float>(std::clamp(2.0 * std::atan(t) * 180.0 / kFramingPi, 10.0, 150.0));
    }
  }
  c.look_at = glm::vec3(look_at);
  c.eye = glm::vec3(eye);
  c.up = glm::vec3(up);
  if (!framing_finite(c.eye) || c.eye == c.look_at)
    throw SceneError("the scene's box, " + vec_str(lo_f) + " to " + vec_str(hi_f) +
                     ", is too large or too far out for the default camera to frame in floats; "
                     "give the scene a camera (a JSON scene's \"camera\")");
  return c;
}

glm::vec3 framing_light_position(const Camera& c) {
  const glm::dvec3 eye(c.eye), fw = glm::dvec3(c.look_at) - eye;
  const double d = glm::length(fw);
  const glm::dvec3 right = glm::normalize(glm::cross(fw, glm::dvec3(c.up)));
  const glm::dvec3 up = glm::normalize(glm::cross(right, fw));
  return glm::vec3(eye + d * (0.5 * up - 0.35 * right));
}

Camera default_camera(const Scene& s) {
  return framing_camera(s, s.width, s.height);
}

}  // namespace rt
