// The classic material and its mapping onto the built-in shaders (ClassicMaterial.h).
#include "rill/rt/scene/ClassicMaterial.h"

#include <cmath>

namespace rt {

Material ClassicMaterial::material(const std::string& name) const {
  Material m;
  m.name = name;
  m.shader = transmit > 0.0f ? "glass" : "phong";
  m.set("diffuse", diffuse).set("specular", specular).set("shininess", shininess);
  m.set("reflect", reflect);
  if (m.shader == "glass") m.set("transmit", transmit).set("ior", ior);
  return m;
}

std::string ClassicMaterial::problem() const {
  auto finite = [](const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
  };
  if (!finite(diffuse) || !finite(specular) || !std::isfinite(shininess) ||
      !std::isfinite(reflect) || !std::isfinite(transmit) || !std::isfinite(ior))
    return "values must be finite numbers";
  // Colours are reflectances: a negative one would render negative radiance.
  auto negative = [](const glm::vec3& c) { return c.x < 0.0f || c.y < 0.0f || c.z < 0.0f; };
  if (negative(diffuse) || negative(specular))
    return (negative(diffuse) ? "diffuse " + vec_str(diffuse) : "specular " + vec_str(specular)) +
           " has a negative component; colours must be >= 0";
  if (reflect < 0 || transmit < 0 || reflect + transmit > 1.0f)
    return "reflect and transmit must be >= 0 with reflect + transmit <= 1";
  if (shininess < 0 || shininess > 1e4f) return "shininess must be in [0, 10000]";
  if (!(ior > 0.0f) || ior > 100.0f) return "ior must be in (0, 100]";
  return {};
}

bool is_classic_key(const std::string& key) {
  for (const char* k : kClassicKeys)
    if (key == k) return true;
  return false;
}

bool is_classic_color(const std::string& key) {
  return key == "diffuse" || key == "specular";
}

void set_classic(ClassicMaterial& m, const std::string& key, const ParamValue& v) {
  if (key == "diffuse") m.diffuse = v.color;
  if (key == "specular") m.specular = v.color;
  if (key == "shininess") m.shininess = v.number;
  if (key == "reflect") m.reflect = v.number;
  if (key == "transmit") m.transmit = v.number;
  if (key == "ior") m.ior = v.number;
}

}  // namespace rt
