// Built with -ffp-contract=off (see CMakeLists.txt): every operation rounds to float32.
#include "rill/rt/scene/Camera.h"

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

}  // namespace rt
