// Reading a JSON camera's projection and lens keys (docs/camera.md, docs/scene-format.md):
// "type" ("perspective" or "orthographic"), "height" (the orthographic view's height),
// "aperture" (the thin lens's radius) and "focus_distance", each checked with an error that
// names the file and the key.
#pragma once

#include "rill/rt/scene/JsonFields.h"

namespace rt::json_fields {

// The keys of `cam` (a scene file's "camera" object) that set the projection and the lens,
// over what k has. Throws SceneError naming the key (camera.aperture, ...).
void camera_projection(const Ctx& c, const json& cam, Camera& k);

}  // namespace rt::json_fields
