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
  // Every camera ray heads forward (its direction's forward part is 1 against at most
  // tan(fov / 2) sideways, far above the rounding): a box wholly behind the eye's plane is
  // never hit.
  // One pass over the corners: their projections, and whether each is clearly in front or
  // clearly behind; a corner on neither side makes the whole image.
  int behind = 0;
  bool near_plane = false;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec3 v = p - eye;
    const double z = glm::dot(v, fw), clear = 1e-3 * std::max(size, glm::length(v));
    if (z < -clear) {
      ++behind;
      continue;
    }
    if (!(z > clear)) {
      near_plane = true;
      continue;
    }
    const double sx = glm::dot(v, rt) / z, sy = glm::dot(v, up) / z;
    sx_min = std::min(sx_min, sx);
    sx_max = std::max(sx_max, sx);
    sy_min = std::min(sy_min, sy);
    sy_max = std::max(sy_max, sy);
  }
  if (behind == 8) return PixelRect{};
  if (behind > 0 || near_plane) return all;
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

TileMask tiles_seeing_boxes(const CameraFrame& f, const std::vector<Aabb>& boxes) {
  const int w = static_cast<int>(f.width), h = static_cast<int>(f.height);
  TileMask m;
  m.shift = 3;
  auto tiles_for = [&](int shift) {
    const int t = 1 << shift;
    return glm::ivec2((w + t - 1) / t, (h + t - 1) / t);
  };
  while (int64_t{tiles_for(m.shift).x} * tiles_for(m.shift).y > (int64_t{1} << 18)) ++m.shift;
  m.tiles = tiles_for(m.shift);
  // Each box's rectangle of tiles as +1 and -1 at its corners, then running sums along both
  // axes: a tile's sum counts the rectangles over it, in time linear in boxes and tiles.
  const int cols = m.tiles.x + 1;
  std::vector<int32_t> count(static_cast<size_t>(cols) * (m.tiles.y + 1), 0);
  auto at = [&](int x, int y) -> int32_t& { return count[static_cast<size_t>(y) * cols + x]; };
  m.bounds = PixelRect{};
  for (const Aabb& b : boxes) {
    const PixelRect r = pixels_seeing_box(f, b.lo, b.hi);
    if (r.empty()) continue;
    if (m.bounds.empty()) {
      m.bounds = r;
    } else {
      m.bounds.first = glm::min(m.bounds.first, r.first);
      m.bounds.end = glm::max(m.bounds.end, r.end);
    }
    const glm::ivec2 t0 = r.first >> m.shift, t1 = ((r.end - 1) >> m.shift) + 1;
    at(t0.x, t0.y) += 1;
    at(t1.x, t0.y) -= 1;
    at(t0.x, t1.y) -= 1;
    at(t1.x, t1.y) += 1;
  }
  for (int y = 0; y <= m.tiles.y; ++y)
    for (int x = 1; x <= m.tiles.x; ++x) at(x, y) += at(x - 1, y);
  for (int y = 1; y <= m.tiles.y; ++y)
    for (int x = 0; x <= m.tiles.x; ++x) at(x, y) += at(x, y - 1);
  m.seen.resize(static_cast<size_t>(m.tiles.x) * m.tiles.y);
  for (int y = 0; y < m.tiles.y; ++y)
    for (int x = 0; x < m.tiles.x; ++x)
      m.seen[static_cast<size_t>(y) * m.tiles.x + x] = at(x, y) > 0 ? 1 : 0;
  return m;
}

}  // namespace rt
