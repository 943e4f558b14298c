// The framing camera: the camera of a scene that sets none (an OBJ rendered alone, a JSON
// scene without "camera"), from its triangles, and the light placed for it. The rules are
// docs/camera.md's "The framing camera".
#pragma once

#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt {

// The up axis of the framing camera. Auto: y, unless the box is a standing z-up object (its
// z extent at least 1.2 times each other extent, and y not its thinnest: a y-up mesh longer
// in z than tall, like a car, is thinnest in y).
enum class UpAxis { Auto, X, Y, Z };
UpAxis parse_up_axis(const std::string& s);  // auto, x, y or z; throws std::invalid_argument
int resolve_up_axis(UpAxis up, const glm::vec3& lo, const glm::vec3& hi);  // 0, 1 or 2

// Whether the triangles enclose their box's centre from inside, like a room: more than half
// of their area faces the centre (a triangle faces it when its winding's normal points from
// its centroid towards the centre).
bool is_room(const Scene& s);

// The framing camera for an image of width x height pixels. Throws SceneError for a scene of
// no extent or one too large to frame in floats; a scene without finite triangles gets
// Camera{}.
Camera framing_camera(const Scene& s, int width, int height, UpAxis up = UpAxis::Auto);

// The light an OBJ rendered alone gets: above and to the left of the eye, off the view axis
// so that shadows show: eye + d (0.5 up - 0.35 right), d = |look_at - eye|.
glm::vec3 framing_light_position(const Camera& c);

}  // namespace rt
