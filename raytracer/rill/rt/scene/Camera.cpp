// Built with -ffp-contract=off (see CMakeLists.txt): every operation rounds to float32.
#include "rill/rt/scene/Camera.h"

#include <algorithm>
#include <array>
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

CameraKind camera_kind(const Camera& c) {
  if (c.projection == Projection::Orthographic) return CameraKind::Orthographic;
  return c.aperture > 0.0f ? CameraKind::ThinLens : CameraKind::Pinhole;
}

const char* camera_kind_name(CameraKind k) {
  switch (k) {
    case CameraKind::Orthographic:
      return "orthographic";
    case CameraKind::ThinLens:
      return "thin lens";
    case CameraKind::Pinhole:
      break;
  }
  return "pinhole";
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
  f.kind = camera_kind(c);
  if (f.kind == CameraKind::Orthographic) {
    f.tan_half = c.ortho_height * 0.5f;
    return f;
  }
  const float arg = c.fov_y * 0.5f * 0.0174532924f;
  f.tan_half = static_cast<float>(std::tan(static_cast<double>(arg)));
  if (f.kind == CameraKind::ThinLens) {
    const glm::vec3 v = c.look_at - c.eye;
    const float focus = c.focus_distance > 0.0f ? c.focus_distance : std::sqrt(dot3(v, v));
    f.lens_radius = c.aperture;
    f.lens_k = c.aperture / focus;
  }
  return f;
}

glm::vec3 camera_ray(const CameraFrame& f, int i, int j, float ox, float oy) {
  const float sx = ((static_cast<float>(i) + ox) / f.width * 2.0f - 1.0f) * f.tan_half * f.aspect;
  const float sy = (1.0f - (static_cast<float>(j) + oy) / f.height * 2.0f) * f.tan_half;
  glm::vec3 d = f.forward + sx * f.right;
  d = d + sy * f.up;
  return normalize3(d);
}

CameraRay camera_ray(const CameraFrame& f, int i, int j, float ox, float oy, glm::vec2 lens) {
  if (f.kind == CameraKind::Pinhole) return CameraRay{f.eye, camera_ray(f, i, j, ox, oy)};
  const float sx = ((static_cast<float>(i) + ox) / f.width * 2.0f - 1.0f) * f.tan_half * f.aspect;
  const float sy = (1.0f - (static_cast<float>(j) + oy) / f.height * 2.0f) * f.tan_half;
  if (f.kind == CameraKind::Orthographic) {
    glm::vec3 o = f.eye + sx * f.right;
    o = o + sy * f.up;
    return CameraRay{o, f.forward};
  }
  // The thin lens: the pinhole's ray through the screen point moved against the lens point
  // by k = R / focus meets the pinhole's own ray on the focal plane.
  const float ex = sx - f.lens_k * lens.x, ey = sy - f.lens_k * lens.y;
  glm::vec3 d = f.forward + ex * f.right;
  d = d + ey * f.up;
  glm::vec3 o = f.eye + (f.lens_radius * lens.x) * f.right;
  o = o + (f.lens_radius * lens.y) * f.up;
  return CameraRay{o, normalize3(d)};
}

namespace {

// Philox4x32-10 (rill/Random.h) on the host, for lens_point.
std::array<uint32_t, 4> philox(std::array<uint32_t, 4> c, uint32_t k0, uint32_t k1) {
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k0 += 0x9E3779B9u;
      k1 += 0xBB67AE85u;
    }
    const uint64_t p0 = uint64_t{0xD2511F53u} * c[0], p1 = uint64_t{0xCD9E8D57u} * c[2];
    c = {static_cast<uint32_t>(p1 >> 32) ^ c[1] ^ k0, static_cast<uint32_t>(p1),
         static_cast<uint32_t>(p0 >> 32) ^ c[3] ^ k1, static_cast<uint32_t>(p0)};
  }
  return c;
}

}  // namespace

glm::vec2 lens_disk(glm::vec2 u) {
  const float a = u.x * 2.0f - 1.0f, b = u.y * 2.0f - 1.0f;
  const bool wide = std::fabs(a) > std::fabs(b);
  const float r = wide ? a : b;
  const float q = (wide ? b : a) / (r == 0.0f ? 1.0f : r);
  const float p = q * 0.785398185f;  // pi/4 in float32
  const float p2 = p * p;
  const float sin_p =
      p * (1.0f + p2 * (-0.166666672f +
                        p2 * (0.00833333377f + p2 * (-0.000198412701f + p2 * 2.75573188e-06f))));
  const float cos_p =
      1.0f +
      p2 * (-0.5f + p2 * (0.0416666679f +
                          p2 * (-0.00138888892f + p2 * (2.48015876e-05f + p2 * -2.755732e-07f))));
  return wide ? glm::vec2(r * cos_p, r * sin_p) : glm::vec2(r * sin_p, r * cos_p);
}

glm::vec2 lens_point(uint32_t seed, int i, int j, int k) {
  const std::array<uint32_t, 4> bits =
      philox({static_cast<uint32_t>(i), static_cast<uint32_t>(j), static_cast<uint32_t>(k), 0u},
             seed, kLensKey);
  auto unit = [](uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; };
  return lens_disk(glm::vec2(unit(bits[0]), unit(bits[1])));
}

float camera_origin_reach(const CameraFrame& f) {
  const double eye = glm::length(glm::dvec3(f.eye));
  double spread = 0;
  if (f.kind == CameraKind::ThinLens) spread = f.lens_radius;
  if (f.kind == CameraKind::Orthographic)
    spread = double(f.tan_half) * std::sqrt(1.0 + double(f.aspect) * f.aspect);
  return static_cast<float>((eye + spread) * (1.0 + 1e-6));
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
  // An orthographic camera's rays start on the eye's plane and run along forward: a corner's
  // (sx, sy) is its place on that plane, whatever its depth, and only a box wholly behind the
  // plane is never hit. A thin lens's ray from lens point R (lx, ly) through screen point
  // (sx, sy) is at R lx + z (sx - k lx) at depth z: a point at x / z on the pinhole's screen is
  // seen from sx within R |1/focus - 1/z| of it, widest at the box's nearest or farthest
  // corner (lens_widen).
  const bool ortho = f.kind == CameraKind::Orthographic;
  int behind = 0;
  bool near_plane = false;
  double lens_widen = 0, z_far = 0;
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 p((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    const glm::dvec3 v = p - eye;
    const double z = glm::dot(v, fw), clear = 1e-3 * std::max(size, glm::length(v));
    z_far = std::max(z_far, std::fabs(z));
    if (z < -clear) {
      ++behind;
      if (!ortho) continue;
    }
    if (!ortho && !(z > clear)) {
      near_plane = true;
      continue;
    }
    const double depth = ortho ? 1.0 : z;
    const double sx = glm::dot(v, rt) / depth, sy = glm::dot(v, up) / depth;
    if (f.kind == CameraKind::ThinLens)
      lens_widen = std::max(lens_widen, std::fabs(double(f.lens_k) - f.lens_radius / z));
    sx_min = std::min(sx_min, sx);
    sx_max = std::max(sx_max, sx);
    sy_min = std::min(sy_min, sy);
    sy_max = std::max(sy_max, sy);
  }
  if (behind == 8) return PixelRect{};
  if (!ortho && (behind > 0 || near_plane)) return all;
  lens_widen *= 1.0 + 1e-5;
  sx_min -= lens_widen;
  sx_max += lens_widen;
  sy_min -= lens_widen;
  sy_max += lens_widen;
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
  // An orthographic ray's origin rounds by a few ulps of |eye| + |s|, and forward is
  // orthogonal to right and up only to rounding, a drift of 1e-7 per unit of depth.
  const double slack = ortho ? 1e-5 * (glm::length(eye) + std::sqrt(s2) + z_far)
                             : 1e-6 * (1.0 + s2) * (1.0 + f.lens_radius);
  const double mx = 3.0 + slack * f.width / (2.0 * t * a);
  const double my = 3.0 + slack * f.height / (2.0 * t);
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
