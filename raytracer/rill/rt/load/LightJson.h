// One entry of a JSON scene file's "lights" (docs/scene-format.md, "lights"): a point, spot or
// directional light, each key checked, with errors that name the file and the key
// ("scene.json: lights[1].inner_angle 40 must be <= outer_angle 30").
#pragma once

#include "rill/rt/scene/JsonFields.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// where: "lights[i]".
Light read_light(const json_fields::Ctx& c, const nlohmann::json& j, const std::string& where);

}  // namespace rt
