// Camera rays (CameraRays.h).
#include "rill/rt/kernel/CameraRays.h"

namespace rt {

using namespace rill;

void CameraRays::set(const Camera& camera, int width, int height, glm::ivec2 launch_origin) {
  const CameraFrame f = camera_frame(camera, width, height);
  frame_ = f;
  eye.set(f.eye);
  forward.set(f.forward);
  right.set(f.right);
  up.set(f.up);
  tan_half.set(f.tan_half);
  aspect.set(f.aspect);
  size.set(glm::vec2(f.width, f.height));
  origin.set(launch_origin);
  seeing_first.set(glm::ivec2(0));
  seeing_end.set(glm::ivec2(width, height));
}

void CameraRays::set_bounds(const glm::vec3& lo, const glm::vec3& hi) {
  const PixelRect r = pixels_seeing_box(frame_, lo, hi);
  seeing_first.set(r.first);
  seeing_end.set(r.empty() ? r.first : r.end);
}

Bool CameraRays::may_see_scene(const Int2& launch_pix) const {
  const Int2 pix = launch_pix + origin;
  return pix.x() >= seeing_first.x() && pix.y() >= seeing_first.y() && pix.x() < seeing_end.x() &&
         pix.y() < seeing_end.y();
}

// docs/camera.md: float32, in this order.
Float3 CameraRays::direction(const Int2& launch_pix) const {
  const Int2 pix = launch_pix + origin;
  Float sx = ((to_float(pix.x()) + offset.x()) / size.x() * 2.0f - 1.0f) * tan_half * aspect;
  Float sy = (1.0f - (to_float(pix.y()) + offset.y()) / size.y() * 2.0f) * tan_half;
  return normalize(forward + sx * right + sy * up);
}

}  // namespace rt
