// A JSON camera's projection and lens keys (CameraJson.h).
#include "rill/rt/scene/CameraJson.h"

namespace rt::json_fields {

void camera_projection(const Ctx& c, const json& cam, Camera& k) {
  if (cam.contains("type")) {
    const json& t = cam["type"];
    const std::string name = t.is_string() ? t.get<std::string>() : std::string();
    if (name == "perspective")
      k.projection = Projection::Perspective;
    else if (name == "orthographic")
      k.projection = Projection::Orthographic;
    else
      fail(c, "camera.type must be \"perspective\" or \"orthographic\"");
  }
  if (cam.contains("height")) {
    if (k.projection != Projection::Orthographic)
      fail(c, "camera.height is the orthographic view's height: give \"type\": \"orthographic\"");
    k.ortho_height = num(c, cam["height"], "camera.height");
    if (!(k.ortho_height > 0.0f)) fail(c, "camera.height must be > 0 (scene units)");
  } else if (k.projection == Projection::Orthographic) {
    fail(c, "an orthographic camera needs camera.height, its view's height in scene units");
  }
  if (cam.contains("aperture")) {
    if (k.projection == Projection::Orthographic)
      fail(c, "camera.aperture is for a perspective camera, not an orthographic one");
    k.aperture = num(c, cam["aperture"], "camera.aperture");
    if (!(k.aperture >= 0.0f))
      fail(c, "camera.aperture must be >= 0 (the lens's radius in scene units; 0 is a pinhole)");
  }
  if (cam.contains("focus_distance")) {
    if (k.projection == Projection::Orthographic)
      fail(c, "camera.focus_distance is for a perspective camera, not an orthographic one");
    k.focus_distance = num(c, cam["focus_distance"], "camera.focus_distance");
    if (!(k.focus_distance > 0.0f))
      fail(c, "camera.focus_distance must be > 0 (scene units from the eye)");
  }
}

}  // namespace rt::json_fields
