// Camera rays (CameraRays.h).
#include "rill/rt/kernel/CameraRays.h"

namespace rt {

using namespace rill;

void CameraRays::set(const Camera& camera, int width, int height, glm::ivec2 launch_origin) {
  const CameraFrame f = camera_frame(camera, width, height);
  eye.set(f.eye);
  forward.set(f.forward);
  right.set(f.right);
  up.set(f.up);
  tan_half.set(f.tan_half);
  aspect.set(f.aspect);
  size.set(glm::vec2(f.width, f.height));
  origin.set(launch_origin);
}

// docs/camera.md: float32, in this order.
Float3 CameraRays::direction(const Int2& launch_pix) const {
  const Int2 pix = launch_pix + origin;
  Float sx = ((to_float(pix.x()) + offset.x()) / size.x() * 2.0f - 1.0f) * tan_half * aspect;
  Float sy = (1.0f - (to_float(pix.y()) + offset.y()) / size.y() * 2.0f) * tan_half;
  return normalize(forward + sx * right + sy * up);
}

}  // namespace rt
