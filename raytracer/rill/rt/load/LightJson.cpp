// A JSON scene file's light (LightJson.h).
#include "rill/rt/load/LightJson.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rt {

using nlohmann::json;
using namespace json_fields;

namespace {

LightType light_type(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_string()) fail(c, where + " must be a string: \"point\", \"spot\" or \"directional\"");
  const std::string t = j.get<std::string>();
  if (t == "point") return LightType::Point;
  if (t == "spot") return LightType::Spot;
  if (t == "directional") return LightType::Directional;
  fail(c, where + " '" + clipped(t) + "' is not a light type (point, spot, directional)");
}

Falloff falloff(const Ctx& c, const json& j, const std::string& where) {
  if (j.is_string() && j.get<std::string>() == "none") return Falloff::None;
  if (j.is_string() && j.get<std::string>() == "inverse_square") return Falloff::InverseSquare;
  fail(c, where + " must be \"none\" or \"inverse_square\"");
}

// A direction that must not be zero (it is normalized when the kernels get it).
glm::vec3 direction(const Ctx& c, const json& j, const std::string& where) {
  const glm::vec3 d = vec3(c, j, where);
  if (!(glm::length(glm::dvec3(d)) > 0.0)) fail(c, where + " must not be zero");
  return d;
}

float angle(const Ctx& c, const json& j, const std::string& where) {
  const float a = num(c, j, where);
  if (!(a >= 0.0f && a <= kMaxSpotDeg)) fail(c, where + " must be in [0, 90] degrees");
  return a;
}

}  // namespace

Light read_light(const Ctx& c, const json& l, const std::string& where) {
  Light light;
  if (l.is_object() && l.contains("type")) light.type = light_type(c, l["type"], where + ".type");
  // Each type's keys alone: a directional light's position or a point light's cone would be
  // ignored, surely a mistake.
  switch (light.type) {
    case LightType::Point:
      check_keys(c, l, where, {"type", "position", "color", "falloff"});
      break;
    case LightType::Spot:
      check_keys(c, l, where,
                 {"type", "position", "color", "direction", "look_at", "inner_angle", "outer_angle",
                  "falloff"});
      break;
    case LightType::Directional:
      check_keys(c, l, where, {"type", "direction", "color"});
      break;
  }
  if (light.type != LightType::Directional) {
    if (!l.contains("position")) fail(c, where + " needs a position");
    light.position = vec3(c, l["position"], where + ".position");
  }
  if (l.contains("color")) light.color = vec3_or_scalar(c, l["color"], where + ".color");
  if (l.contains("falloff")) light.falloff = falloff(c, l["falloff"], where + ".falloff");
  if (light.type == LightType::Spot && l.contains("direction") && l.contains("look_at"))
    fail(c, where + " has both direction and look_at: give one");
  if (light.type != LightType::Point) {
    if (l.contains("direction")) {
      light.direction = direction(c, l["direction"], where + ".direction");
    } else if (light.type == LightType::Spot && l.contains("look_at")) {
      const glm::vec3 at = vec3(c, l["look_at"], where + ".look_at");
      if (!(glm::length(glm::dvec3(at) - glm::dvec3(light.position)) > 0.0))
        fail(c, where + ".look_at must not be the light's position");
      light.direction = at - light.position;
    } else {
      fail(c, where + " needs a direction" +
                  (light.type == LightType::Spot ? std::string(" or a look_at point") : ""));
    }
  }
  if (light.type == LightType::Spot) {
    if (l.contains("outer_angle"))
      light.outer_deg = angle(c, l["outer_angle"], where + ".outer_angle");
    if (!(light.outer_deg > 0.0f)) fail(c, where + ".outer_angle must be more than 0 degrees");
    // pbrt's default soft edge: 5 degrees (its conedelta), within the cone.
    light.inner_deg = std::max(0.0f, light.outer_deg - 5.0f);
    if (l.contains("inner_angle"))
      light.inner_deg = angle(c, l["inner_angle"], where + ".inner_angle");
    if (light.inner_deg > light.outer_deg)
      fail(c, where + ".inner_angle " + json(light.inner_deg).dump() + " must be <= outer_angle " +
                  json(light.outer_deg).dump());
  }
  return light;
}

}  // namespace rt
