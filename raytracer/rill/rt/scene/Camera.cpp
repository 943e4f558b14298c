// Built with -ffp-contract=off (see CMakeLists.txt): every operation rounds to float32.
#include "rill/rt/scene/Camera.h"

#include <algorithm>
#include <cmath>

namespace rt {

float dot3(const glm::vec3& a, const glm::vec3& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}

glm::vec3 cross3(const glm::vec3& a, const glm::vec3& b) {
  return glm::vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

glm::vec3 normalize3(const glm::vec3& v) {
  float l = std::sqrt(dot3(v, v));
  return glm::vec3(v.x / l, v.y / l, v.z / l);
}

CameraFrame camera_frame(const Camera& c, int width, int height) {
  CameraFrame f;
  f.eye = c.eye;
  f.forward = normalize3(c.look_at - c.eye);
  f.right = normalize3(cross3(f.forward, c.up));
  f.up = cross3(f.right, f.forward);
  f.width = static_cast<float>(width);
  f.height = static_cast<float>(height);
  f.aspect = f.width / f.height;
  const float arg = c.fov_y * 0.5f * 0.0174532924f;
  f.tan_half = static_cast<float>(std::tan(static_cast<double>(arg)));
  return f;
}

glm::vec3 camera_ray(const CameraFrame& f, int i, int j, float ox, float oy) {
  const float sx = ((static_cast<float>(i) + ox) / f.width * 2.0f - 1.0f) * f.tan_half * f.aspect;
  const float sy = (1.0f - (static_cast<float>(j) + oy) / f.height * 2.0f) * f.tan_half;
  glm::vec3 d = f.forward + sx * f.right;
  d = d + sy * f.up;
  return normalize3(d);
}

PixelRect pixels_seeing_box(const CameraFrame& f, const glm::vec3& lo, const glm::vec3& hi) {
  const int w = static_cast<int>(f.width), h = static_cast<int>(f.height);
  const PixelRect all{glm::ivec2(0), glm::ivec2(w, h)};
  if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return PixelRect{};
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a])) return all;
  // In double, against the camera's float frame: the box's corners as (sx, sy), the screen
  // coordinates of docs/camera.md. The box is convex and, when every corner is in front of
  // the eye, so is all of it: its rays lie within the corners' (sx, sy) range.
  const glm::dvec3 fw(f.forward), rt(f.right), up(f.up), eye(f.eye);
  const double size = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
  double sx_min = HUGE_VAL, sx_max = -HUGE_VAL, sy_min = HUGE_VAL, sy_max = -HUGE_VAL;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec3 v = p - eye;
    const double z = glm::dot(v, fw);
    if (!(z > 1e-3 * std::max(size, glm::length(v)))) return all;
    const double sx = glm::dot(v, rt) / z, sy = glm::dot(v, up) / z;
    sx_min = std::min(sx_min, sx);
    sx_max = std::max(sx_max, sx);
    sy_min = std::min(sy_min, sy);
    sy_max = std::max(sy_max, sy);
  }
  // sx = ((i + ox) / W * 2 - 1) t a and sy = (1 - (j + oy) / H * 2) t, solved for i and j;
  // ox, oy in [0, 1) widen each range by one pixel, and two more cover rounding. A float ray
  // is off its exact direction by a few 1e-7 radians whatever the field of view (the frame
  // is orthonormal to rounding): in pixels that grows as the pixels shrink, so a narrow view
  // gets that much more (1e-6 (1 + s^2) in screen units, s the box's largest coordinate).
  const double t = f.tan_half, a = f.aspect;
  if (!(t > 0) || !(a > 0)) return all;
  auto column = [&](double sx) { return (sx / (t * a) + 1.0) * 0.5 * f.width; };
  auto row = [&](double sy) { return (1.0 - sy / t) * 0.5 * f.height; };
  auto clamp_to = [](double v, int n) {
    return static_cast<int>(std::clamp(v, 0.0, static_cast<double>(n)));
  };
  const double sx_far = std::max(std::fabs(sx_min), std::fabs(sx_max));
  const double sy_far = std::max(std::fabs(sy_min), std::fabs(sy_max));
  const double s2 = sx_far * sx_far + sy_far * sy_far;
  const double mx = 3.0 + 1e-6 * (1.0 + s2) * f.width / (2.0 * t * a);
  const double my = 3.0 + 1e-6 * (1.0 + s2) * f.height / (2.0 * t);
  PixelRect r;
  r.first.x = clamp_to(std::floor(column(sx_min)) - mx, w);
  r.end.x = clamp_to(std::ceil(column(sx_max)) + mx, w);
  r.first.y = clamp_to(std::floor(row(sy_max)) - my, h);
  r.end.y = clamp_to(std::ceil(row(sy_min)) + my, h);
  return r;
}

}  // namespace rt
