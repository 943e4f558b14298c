// Animation: a scene's time range, the keyframed rigid motion of its animated objects, and
// its camera's keyframes (docs/dynamic-scenes.md).
//
// A track holds keys at strictly increasing times. Between two keys a value is interpolated:
// linearly (positions, scales and fields of view by lerp, rotations by slerp along the shorter
// arc), or smoothly (the same, with the segment's parameter eased by 3u^2 - 2u^3, so motion
// starts and stops gently at every key). Before the first key the first key's value holds,
// after the last the last's. Everything is computed in double and rounded to float once, so
// posing is deterministic: the renderer and a scene baked at the same time get the same bits.
//
// An animated object is a range of the scene's triangles, stored at rest (its mesh's own
// "transform" applied) and moved each frame by its track's pose: scale, then rotate, then
// translate. Posing the scene and baking it are in scene/Pose.h.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace rt {

enum class Interpolation { Linear, Smooth };
// "linear" or "smooth"; throws std::invalid_argument naming the bad value.
Interpolation parse_interpolation(const std::string& s);

// The frames of an animation: frame k is at time start + k / fps (seconds), for k in
// 0..frame_count() - 1, the last at or before end.
struct TimeRange {
  double start = 0.0, end = 0.0;
  double fps = 24.0;
  int frame_count() const;
  double time_of(int frame) const;
};

// A rigid motion: p -> translate + rotation * (scale * p).
struct Pose {
  glm::dvec3 translate{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};  // unit (w, x, y, z)
  glm::dvec3 scale{1.0};
  glm::vec3 apply_point(const glm::vec3& p) const;
  // The same motion with its rotation and scale about `pivot`:
  // p -> translate + pivot + rotation * (scale * (p - pivot)). A zero pivot is apply_point(p),
  // bit for bit (the sums with 0 would turn a -0 into +0).
  glm::vec3 apply_point(const glm::vec3& p, const glm::dvec3& pivot) const;
  // The normal of a surface moved by the pose, normalized (inverse transpose: rotation of
  // n / scale).
  glm::vec3 apply_normal(const glm::vec3& n) const;
};

struct PoseKey {
  double time = 0.0;
  Pose pose;
};

struct PoseTrack {
  std::vector<PoseKey> keys;  // strictly increasing times, at least one
  Interpolation interpolation = Interpolation::Linear;
  Pose at(double time) const;
};

// What a camera key sets; each key gives all of them (the JSON fills gaps from the camera).
struct CameraPose {
  glm::vec3 eye{0.0f}, look_at{0.0f}, up{0.0f, 1.0f, 0.0f};
  float fov_y = 45.0f;
};

struct CameraKey {
  double time = 0.0;
  CameraPose camera;
};

struct CameraTrack {
  std::vector<CameraKey> keys;  // empty: the scene's camera does not move
  Interpolation interpolation = Interpolation::Linear;
  CameraPose at(double time) const;
};

// Triangles [first, first + count) of the scene, moved by `track`. A deforming mesh (an OBJ
// sequence) also has its corners' positions and normals for each file of the sequence
// (3 * count each; normals empty when the mesh has none): at a time t the file
// floor((t - start) * shape_fps) (clamped to the sequence) replaces the rest pose, and the
// track moves that.
struct AnimatedObject {
  std::string name;  // for messages and stats: the mesh's or instance's name, or its place
  size_t first = 0, count = 0;
  PoseTrack track;
  // The point (in the scene, as the triangles stand at rest) that the track's rotations and
  // scales act about: an instance's "pivot" as its "transform" placed it. Zero for a mesh.
  glm::dvec3 pivot{0.0};
  std::vector<std::vector<glm::vec3>> shapes, shape_normals;
  double shape_fps = 0;  // 0: the time range's fps
  // The shape shown at `time` for a time range starting at `start` at `fps` frames per second.
  size_t shape_at(double time, double start, double fps) const;
};

struct Animation {
  TimeRange time;
  std::vector<AnimatedObject> objects;
  CameraTrack camera;
  bool animated() const { return !objects.empty() || !camera.keys.empty(); }
  // Triangles that move (the sum of the objects' counts).
  size_t moving_triangles() const;
};

// The segment parameter in [0, 1] of `time` between the keys at t0 < t1, eased for Smooth.
double segment_parameter(double time, double t0, double t1, Interpolation how);

}  // namespace rt
