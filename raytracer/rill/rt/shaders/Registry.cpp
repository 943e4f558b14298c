// The shader registry (Registry.h): a name -> shader map, with the built-in shaders
// registered through register_shader the first time it is used.
#include "rill/rt/shaders/Registry.h"

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include "rill/rt/shaders/Builtin.h"

namespace rt {

namespace {

struct Registry {
  std::mutex mutex;
  std::map<std::string, const SurfaceShader*> by_name;
  // Every shader ever registered, replaced ones too: find_shader's pointers stay valid.
  std::vector<std::unique_ptr<const SurfaceShader>> all;
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

void add(Registry& r, SurfaceShader shader, bool replace) {
  check(shader);
  std::lock_guard lock(r.mutex);
  if (!replace && r.by_name.count(shader.name))
    throw std::invalid_argument("register_shader: a shader named '" + shader.name +
                                "' is registered already (replace_shader replaces it)");
  r.all.push_back(std::make_unique<const SurfaceShader>(std::move(shader)));
  r.by_name[r.all.back()->name] = r.all.back().get();
}

Registry& registry() {
  static Registry* r = [] {
    auto* reg = new Registry;  // never destroyed: shaders may be looked up during exit
    for (SurfaceShader& s : builtin_shaders()) add(*reg, std::move(s), false);
    return reg;
  }();
  return *r;
}

}  // namespace

void register_shader(SurfaceShader shader) {
  add(registry(), std::move(shader), false);
}

void replace_shader(SurfaceShader shader) {
  add(registry(), std::move(shader), true);
}

const SurfaceShader* find_shader(const std::string& name) {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  auto it = r.by_name.find(name);
  return it == r.by_name.end() ? nullptr : it->second;
}

std::vector<std::string> shader_names() {
  Registry& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, s] : r.by_name) names.push_back(name);
  return names;
}

const SurfaceShader& material_shader(const Material& m) {
  const SurfaceShader* s = find_shader(m.shader);
  if (s == nullptr)
    throw SceneError("material '" + m.name + "': no shader named '" + m.shader + "'");
  return *s;
}

std::string material_problem(const Material& m, const SurfaceShader& shader) {
  for (const auto& [name, v] : m.params) {
    const ShaderParam* decl = nullptr;
    for (const ShaderParam& p : shader.params)
      if (p.name == name) decl = &p;
    if (decl == nullptr) continue;  // another shader's (Material::params)
    const bool number = v.kind == ParamValue::Kind::Number;
    if ((decl->type == ParamType::Number) != number)
      return name + " must be a " + param_type_name(decl->type) +
             (decl->type == ParamType::Number ? "" : " or a texture");
  }
  for (const ShaderParam& p : shader.params)
    if (p.required && !m.params.count(p.name))
      return "shader '" + shader.name + "' needs parameter '" + p.name + "' (a " +
             param_type_name(p.type) + ")";
  return shader.check ? shader.check(MaterialParams(m, shader.params)) : std::string();
}

MaterialShaders resolve_shaders(const Scene& scene) {
  MaterialShaders shaders;
  for (const Material& m : scene.materials) {
    const SurfaceShader& s = material_shader(m);
    if (std::string why = material_problem(m, s); !why.empty())
      throw SceneError("material '" + m.name + "': " + why);
    shaders.push_back(&s);
  }
  return shaders;
}

}  // namespace rt
