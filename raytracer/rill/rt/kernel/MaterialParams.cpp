// A material's parameter values as the host sees them (Shader.h, MaterialParams), and the
// names of the parameter types.
#include <algorithm>
#include <stdexcept>

#include "rill/rt/kernel/Shader.h"

namespace rt {

const char* param_type_name(ParamType t) {
  return t == ParamType::Number ? "number" : "colour";
}

ParamValue MaterialParams::get(const std::string& name) const {
  auto d = std::find_if(decl_.begin(), decl_.end(),
                        [&](const ShaderParam& p) { return p.name == name; });
  if (d == decl_.end())
    throw std::out_of_range("shader '" + m_.shader + "' has no parameter '" + name + "'");
  if (auto it = m_.params.find(name); it != m_.params.end()) return it->second;
  return d->default_value;
}

bool MaterialParams::nonzero(const std::string& name) const {
  const ParamValue v = get(name);
  switch (v.kind) {
    case ParamValue::Kind::Number:
      return v.number != 0.0f;
    case ParamValue::Kind::Color:
      return v.color != glm::vec3(0.0f);
    case ParamValue::Kind::Texture:
      return true;
  }
  return true;
}

}  // namespace rt
