// Posing a dynamic scene (Pose.h).
#include "rill/rt/scene/Pose.h"

#include <tbb/parallel_for.h>

namespace rt {

Camera camera_at(const Scene& s, double time) {
  if (s.animation.camera.keys.empty()) return s.camera;
  const CameraPose p = s.animation.camera.at(time);
  Camera c = s.camera;
  c.eye = p.eye;
  c.look_at = p.look_at;
  c.up = p.up;
  c.fov_y = p.fov_y;
  return c;
}

void pose_objects(const Scene& rest, double time, Scene& posed) {
  const TimeRange& range = rest.animation.time;
  // Objects in parallel too: a scene of many small objects (a hundred balls) has little to
  // split within each.
  const std::vector<AnimatedObject>& objects = rest.animation.objects;
  tbb::parallel_for(size_t{0}, objects.size(), [&](size_t which) {
    const AnimatedObject& o = objects[which];
    if (o.count == 0) return;  // (its first corner may be one past the end)
    const Pose pose = o.track.at(time);
    const bool normals = !rest.normals.empty();
    // A deforming mesh's shape at this time, else the rest pose; corners from 3 * o.first.
    const glm::vec3* from = &rest.positions[3 * o.first];
    const glm::vec3* from_n = normals ? &rest.normals[3 * o.first] : nullptr;
    if (!o.shapes.empty()) {
      const size_t k = o.shape_at(time, range.start, range.fps);
      from = o.shapes[k].data();
      if (normals && !o.shape_normals.empty()) from_n = o.shape_normals[k].data();
    }
    // Each corner on its own: the same bits whatever the split into tasks.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, 3 * o.count, 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t i = r.begin(); i != r.end(); ++i) {
                          posed.positions[3 * o.first + i] = pose.apply_point(from[i], o.pivot);
                          if (from_n != nullptr)
                            posed.normals[3 * o.first + i] = pose.apply_normal(from_n[i]);
                        }
                      });
  });
}

Scene bake(const Scene& s, double time) {
  Scene b = s;
  pose_objects(s, time, b);
  b.camera = camera_at(s, time);
  b.animation = Animation{};
  return b;
}

}  // namespace rt
