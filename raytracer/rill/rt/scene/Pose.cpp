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
  for (const AnimatedObject& o : rest.animation.objects) {
    const Pose pose = o.track.at(time);
    const bool normals = !rest.normals.empty();
    // Each corner on its own: the same bits whatever the split into tasks.
    tbb::parallel_for(tbb::blocked_range<size_t>(3 * o.first, 3 * (o.first + o.count), 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t i = r.begin(); i != r.end(); ++i) {
                          posed.positions[i] = pose.apply_point(rest.positions[i]);
                          if (normals) posed.normals[i] = pose.apply_normal(rest.normals[i]);
                        }
                      });
  }
}

Scene bake(const Scene& s, double time) {
  Scene b = s;
  pose_objects(s, time, b);
  b.camera = camera_at(s, time);
  b.animation = Animation{};
  return b;
}

}  // namespace rt
