// Camera rays (CameraRays.h).
#include "rill/rt/kernel/CameraRays.h"

#include <algorithm>
#include <cstring>

#include "rill/Random.h"

namespace rt {

using namespace rill;

namespace {

// Every pixel sees: one tile over the whole image.
TileMask whole_image(int width, int height) {
  TileMask m;
  m.shift = 30;
  m.tiles = glm::ivec2(1);
  m.seen = {1};
  m.bounds = PixelRect{glm::ivec2(0), glm::ivec2(width, height)};
  return m;
}

}  // namespace

CameraRays::CameraRays() {
  use(whole_image(1 << 30, 1 << 30));
}

void CameraRays::set(const Camera& camera, int width, int height, glm::ivec2 launch_origin,
                     const std::vector<Aabb>* boxes, const Aabb* moving) {
  const CameraFrame f = camera_frame(camera, width, height);
  eye.set(f.eye);
  forward.set(f.forward);
  right.set(f.right);
  up.set(f.up);
  tan_half.set(f.tan_half);
  lens_radius.set(f.lens_radius);
  lens_k.set(f.lens_k);
  aspect.set(f.aspect);
  size.set(glm::vec2(f.width, f.height));
  origin.set(launch_origin);
  const PixelRect m = moving ? pixels_seeing_box(f, moving->lo, moving->hi) : PixelRect{};
  moving_first.set(m.first);
  moving_end.set(m.empty() ? m.first : m.end);
  // Frame after frame of one view and scene (rill-trace --bench-frames), the mask is the
  // last one: projecting a thousand boxes costs about 0.1 ms, a tenth of a GPU's frame.
  // (By their bits: memcmp, which an empty list must not reach with its null data.)
  auto same_bits = [](const auto& a, const auto& b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  const bool same =
      boxes && seen_from_ && same_bits(*seen_from_, f) &&
      std::equal(boxes->begin(), boxes->end(), seen_boxes_.begin(), seen_boxes_.end(), same_bits);
  if (same) return;
  use(boxes ? tiles_seeing_boxes(f, *boxes) : whole_image(width, height));
  seen_from_.reset();
  if (boxes) {
    seen_from_ = f;
    seen_boxes_ = *boxes;
  }
}

// The mask's uniforms, and its tiles uploaded only when they changed: frame after frame of
// one view (rill-trace --bench-frames) uploads nothing.
void CameraRays::use(TileMask m) {
  seeing_first.set(m.bounds.first);
  seeing_end.set(m.bounds.empty() ? m.bounds.first : m.bounds.end);
  tile_shift.set(m.shift);
  tile_columns.set(m.tiles.x);
  if (m.seen != mask_.seen) {
    seeing_tiles.resize(static_cast<int64_t>(m.seen.size()));
    seeing_tiles.upload(m.seen);
  }
  mask_ = std::move(m);
}

Bool CameraRays::may_see_scene(const Int2& launch_pix, bool moving) const {
  const Int2 pix = launch_pix + origin;
  auto inside = [&](const Int2& first, const Int2& end) {
    return pix.x() >= first.x() && pix.y() >= first.y() && pix.x() < end.x() && pix.y() < end.y();
  };
  const Int tile = (pix.y() >> tile_shift) * tile_columns + (pix.x() >> tile_shift);
  Bool sees = inside(seeing_first, seeing_end) && seeing_tiles[tile] != 0;
  if (moving) sees = sees || inside(moving_first, moving_end);
  return sees;
}

// docs/camera.md: float32, in this order.
// (Each value made where it is declared: a DSL variable declared first and assigned later would
// add a declaration to the kernel, and the pinhole's kernels must stay as they were.)
CameraRays::ScreenPoint CameraRays::screen(const Int2& pix) const {
  if (sample_offset_var) {
    const Float2& o = *sample_offset_var;
    return ScreenPoint{((to_float(pix.x()) + o.x()) / size.x() * 2.0f - 1.0f) * tan_half * aspect,
                       (1.0f - (to_float(pix.y()) + o.y()) / size.y() * 2.0f) * tan_half};
  }
  return ScreenPoint{
      ((to_float(pix.x()) + offset.x()) / size.x() * 2.0f - 1.0f) * tan_half * aspect,
      (1.0f - (to_float(pix.y()) + offset.y()) / size.y() * 2.0f) * tan_half};
}

Float3 CameraRays::direction(const Int2& launch_pix) const {
  const Int2 pix = launch_pix + origin;
  const ScreenPoint s = screen(pix);
  return normalize(forward + s.x * right + s.y * up);
}

void CameraRays::aim(Ray& ray, const Int2& launch_pix) const {
  if (kind == CameraKind::Pinhole) {
    ray.d = direction(launch_pix);
    return;
  }
  const Int2 pix = launch_pix + origin;
  const ScreenPoint s = screen(pix);
  if (kind == CameraKind::Orthographic) {
    ray.o = eye + s.x * right + s.y * up;
    ray.d = forward;
    return;
  }
  // The thin lens (Camera.cpp's camera_ray says why these meet on the focal plane).
  const Float2 l = lens_point(pix);
  const Float ex = s.x - lens_k * l.x(), ey = s.y - lens_k * l.y();
  ray.d = normalize(forward + ex * right + ey * up);
  ray.o = eye + (lens_radius * l.x()) * right + (lens_radius * l.y()) * up;
}

// Philox4x32-10 of (pixel, sample, 0) under the key (seed, "Lens"), and the concentric mapping
// with its sine and cosine polynomials (Camera.cpp's lens_disk, the same operations).
Float2 CameraRays::lens_point(const Int2& pix) const {
  const Int& sample = lens_sample_var ? *lens_sample_var : static_cast<const Int&>(lens_sample);
  const Int4 counter(pix.x(), pix.y(), sample, Int(0));
  const Float4 u = unit_float(philox4x32(counter, Int2(lens_seed, Int(int32_t(kLensKey)))));
  const Float a = u.x() * 2.0f - 1.0f, b = u.y() * 2.0f - 1.0f;
  const Bool wide = abs(a) > abs(b);
  const Float r = select(wide, a, b);
  const Float q = select(wide, b, a) / select(r == 0.0f, Float(1.0f), r);
  const Float p = q * 0.785398185f;
  const Float p2 = p * p;
  const Float sin_p =
      p * (1.0f + p2 * (-0.166666672f +
                        p2 * (0.00833333377f + p2 * (-0.000198412701f + p2 * 2.75573188e-06f))));
  const Float cos_p =
      1.0f +
      p2 * (-0.5f + p2 * (0.0416666679f +
                          p2 * (-0.00138888892f + p2 * (2.48015876e-05f + p2 * -2.755732e-07f))));
  return Float2(r * select(wide, cos_p, sin_p), r * select(wide, sin_p, cos_p));
}

}  // namespace rt
