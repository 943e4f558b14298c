// Keyframe tracks and time (Animation.h).
#include "rill/rt/scene/Animation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rt {

Interpolation parse_interpolation(const std::string& s) {
  if (s == "linear") return Interpolation::Linear;
  if (s == "smooth") return Interpolation::Smooth;
  throw std::invalid_argument("unknown interpolation '" + s + "' (linear, smooth)");
}

int TimeRange::frame_count() const {
  if (!(end >= start) || !(fps > 0)) return 0;
  // The tolerance keeps a range of exactly k frames' length from losing its last frame to
  // rounding ((2.0 - 0.0) * 24 is exact, but (1.1 - 0.1) * 30 need not be).
  const double n = std::floor((end - start) * fps + 1e-9);
  return n >= 1e9 ? 1000000000 : static_cast<int>(n) + 1;
}

double TimeRange::time_of(int frame) const {
  return start + static_cast<double>(frame) / fps;
}

glm::vec3 Pose::apply_point(const glm::vec3& p) const {
  return glm::vec3(translate + rotation * (scale * glm::dvec3(p)));
}

glm::vec3 Pose::apply_point(const glm::vec3& p, const glm::dvec3& pivot) const {
  if (pivot == glm::dvec3(0.0)) return apply_point(p);
  return glm::vec3(translate + pivot + rotation * (scale * (glm::dvec3(p) - pivot)));
}

glm::vec3 Pose::apply_normal(const glm::vec3& n) const {
  const glm::dvec3 m = rotation * (glm::dvec3(n) / scale);
  const double l = glm::length(m);
  return l > 0 && std::isfinite(l) ? glm::vec3(m / l) : glm::vec3(n);
}

double segment_parameter(double time, double t0, double t1, Interpolation how) {
  double u = std::clamp((time - t0) / (t1 - t0), 0.0, 1.0);
  if (how == Interpolation::Smooth) u = u * u * (3.0 - 2.0 * u);
  return u;
}

namespace {

// The keys around `time`: i and i + 1 with keys[i].time <= time < keys[i + 1].time, and the
// parameter between them; a time outside the keys holds the nearest key (u = 0 at it).
template <class Key>
size_t segment(const std::vector<Key>& keys, double time, Interpolation how, double& u) {
  u = 0.0;
  // NaN compares false everywhere: it would pass both tests and run off the end.
  if (keys.size() < 2 || !(time > keys.front().time)) return 0;
  if (time >= keys.back().time) return keys.size() - 1;
  auto after = std::upper_bound(keys.begin(), keys.end(), time,
                                [](double t, const Key& k) { return t < k.time; });
  const size_t i = static_cast<size_t>(after - keys.begin()) - 1;
  u = segment_parameter(time, keys[i].time, keys[i + 1].time, how);
  return i;
}

glm::dvec3 lerp(const glm::dvec3& a, const glm::dvec3& b, double u) {
  return a + (b - a) * u;
}

}  // namespace

Pose PoseTrack::at(double time) const {
  if (keys.empty()) return Pose{};
  double u = 0.0;
  const size_t i = segment(keys, time, interpolation, u);
  if (u == 0.0) return keys[i].pose;
  const Pose& a = keys[i].pose;
  const Pose& b = keys[i + 1].pose;
  Pose p;
  p.translate = lerp(a.translate, b.translate, u);
  p.scale = lerp(a.scale, b.scale, u);
  p.rotation = glm::normalize(glm::slerp(a.rotation, b.rotation, u));  // the shorter arc
  return p;
}

CameraPose CameraTrack::at(double time) const {
  if (keys.empty()) return CameraPose{};
  double u = 0.0;
  const size_t i = segment(keys, time, interpolation, u);
  if (u == 0.0) return keys[i].camera;
  const CameraPose& a = keys[i].camera;
  const CameraPose& b = keys[i + 1].camera;
  auto mix3 = [&](const glm::vec3& x, const glm::vec3& y) {
    return glm::vec3(lerp(glm::dvec3(x), glm::dvec3(y), u));
  };
  CameraPose c;
  c.eye = mix3(a.eye, b.eye);
  c.look_at = mix3(a.look_at, b.look_at);
  c.up = mix3(a.up, b.up);
  c.fov_y = static_cast<float>(a.fov_y + (static_cast<double>(b.fov_y) - a.fov_y) * u);
  return c;
}

size_t AnimatedObject::shape_at(double time, double start, double fps) const {
  if (shapes.empty()) return 0;
  const double rate = shape_fps > 0 ? shape_fps : fps;
  // The tolerance keeps frame k's own time (start + k / fps, rounded) on shape k.
  const double k = std::floor((time - start) * rate + 1e-6);
  if (!(k > 0)) return 0;  // NaN too
  return std::min(static_cast<size_t>(std::min(k, 1e9)), shapes.size() - 1);
}

size_t Animation::moving_triangles() const {
  size_t n = 0;
  for (const AnimatedObject& o : objects) n += o.count;
  return n;
}

}  // namespace rt
