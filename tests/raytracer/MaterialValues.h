// A material's parameter values as its shader sees them, for tests: the value the material
// gives, else the shader's default (MaterialParams over the registered shader).
#pragma once

#include <string>

#include "rill/rt/kernel/Shader.h"
#include "rill/rt/shaders/Registry.h"

namespace rt::testing {

inline rt::ParamValue param_of(const rt::Material& m, const std::string& name) {
  return rt::MaterialParams(m, rt::material_shader(m).params).get(name);
}
inline glm::vec3 color_of(const rt::Material& m, const std::string& name) {
  return param_of(m, name).color;
}
inline float number_of(const rt::Material& m, const std::string& name) {
  return param_of(m, name).number;
}

}  // namespace rt::testing
