// The process's surface shaders (Shader.h): a name -> shader map, with the built-in ones
// registered the first time it is used.
#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "rill/rt/kernel/Shader.h"
#include "rill/rt/shaders/Builtin.h"

namespace rt {

namespace {

struct Registry {
  std::mutex mutex;
  // unique_ptr: find_shader's pointers stay valid while others register.
  std::map<std::string, std::unique_ptr<SurfaceShader>> shaders;
};

void check(const SurfaceShader& s) {
  if (s.name.empty()) throw std::invalid_argument("register_shader: the shader has no name");
  for (size_t i = 0; i < s.params.size(); ++i) {
    const ShaderParam& p = s.params[i];
    const std::string where = "register_shader: shader '" + s.name + "', parameter '" + p.name;
    if (p.name.empty() || p.name == "shader")
      throw std::invalid_argument("register_shader: shader '" + s.name +
                                  "' declares a parameter named '" + p.name + "'");
    for (size_t j = 0; j < i; ++j)
      if (s.params[j].name == p.name) throw std::invalid_argument(where + "' is declared twice");
    const bool number = p.default_value.kind == ParamValue::Kind::Number;
    if ((p.type == ParamType::Number) != number)
      throw std::invalid_argument(where + "': the default is not a " + param_type_name(p.type));
  }
}

Registry& registry() {
  static Registry* r = [] {
    auto* reg = new Registry;
    for (SurfaceShader& s : builtin_shaders()) {
      check(s);
      std::string name = s.name;
      reg->shaders.emplace(name, std::make_unique<SurfaceShader>(std::move(s)));
    }
    return reg;
  }();
  return *r;
}

}  // namespace

const char* param_type_name(ParamType t) {
  return t == ParamType::Number ? "number" : "colour";
}

void register_shader(SurfaceShader shader) {
  check(shader);
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  if (r.shaders.count(shader.name))
    throw std::invalid_argument("register_shader: a shader named '" + shader.name +
                                "' is registered already");
  std::string name = shader.name;
  r.shaders.emplace(name, std::make_unique<SurfaceShader>(std::move(shader)));
}

const SurfaceShader* find_shader(const std::string& name) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto it = r.shaders.find(name);
  return it == r.shaders.end() ? nullptr : it->second.get();
}

std::vector<std::string> shader_names() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, s] : r.shaders) names.push_back(name);
  return names;
}

// The shader of a material (by its shader_name()).
const SurfaceShader& material_shader(const Material& m) {
  const SurfaceShader* s = find_shader(m.shader_name());
  if (s == nullptr)
    throw SceneError("material '" + m.name + "': no shader named '" + m.shader_name() + "'");
  return *s;
}

// ---- MaterialParams --------------------------------------------------------------------------

namespace {

// The classic Material fields, which the built-in shaders' parameters of the same names read.
bool classic_field(const Material& m, const std::string& name, ParamValue& v) {
  if (name == "diffuse")
    v = ParamValue::of(m.diffuse);
  else if (name == "specular")
    v = ParamValue::of(m.specular);
  else if (name == "shininess")
    v = ParamValue::of(m.shininess);
  else if (name == "reflect")
    v = ParamValue::of(m.reflect);
  else if (name == "transmit")
    v = ParamValue::of(m.transmit);
  else if (name == "ior")
    v = ParamValue::of(m.ior);
  else
    return false;
  return true;
}

}  // namespace

ParamValue MaterialParams::get(const std::string& name) const {
  auto d = std::find_if(decl_.begin(), decl_.end(),
                        [&](const ShaderParam& p) { return p.name == name; });
  if (d == decl_.end())
    throw std::out_of_range("shader '" + m_.shader_name() + "' has no parameter '" + name + "'");
  if (auto it = m_.params.find(name); it != m_.params.end()) return it->second;
  ParamValue v;
  if (is_builtin_shader(m_.shader_name()) && classic_field(m_, name, v)) return v;
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

const std::string& Material::shader_name() const {
  static const std::string phong = "phong", glass = "glass";
  if (!shader.empty()) return shader;
  return transmit > 0.0f ? glass : phong;
}

}  // namespace rt
