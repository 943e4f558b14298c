// Material parameters on the device and the dispatch into shaders (MaterialTable.h).
#include "rill/rt/kernel/MaterialTable.h"

#include <stdexcept>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

using namespace rill;

void MaterialTable::upload(const Scene& scene, const Features& F, const MaterialShaders& shaders) {
  shaders_.clear();
  std::vector<bool> used =
      F.geometry ? used_materials(scene) : std::vector<bool>(scene.materials.size(), false);
  // The used shaders, in the order their first material appears.
  std::vector<int> shader_index(scene.materials.size(), 0);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    if (!used[m]) continue;
    const SurfaceShader& sh = *shaders.at(m);
    size_t i = 0;
    while (i < shaders_.size() && shaders_[i].shader != &sh) ++i;
    if (i == shaders_.size()) {
      Layout l;
      l.shader = &sh;
      int numbers = 0;
      for (const ShaderParam& p : sh.params)
        if (p.type == ParamType::Color) l.params[p.name] = Param{p.type, l.slots++, 0};
      for (const ShaderParam& p : sh.params)
        if (p.type == ParamType::Number) {
          l.params[p.name] = Param{p.type, l.slots + numbers / 4, numbers % 4};
          ++numbers;
        }
      l.slots += (numbers + 3) / 4;
      shaders_.push_back(std::move(l));
    }
    shader_index[m] = static_cast<int>(i);
  }
  stride_ = 1;
  for (const Layout& l : shaders_) stride_ = std::max(stride_, l.slots);

  std::vector<glm::vec4> block(scene.materials.size() * static_cast<size_t>(stride_),
                               glm::vec4(0.0f));
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    if (!used[m]) continue;
    Layout& l = shaders_[static_cast<size_t>(shader_index[m])];
    const MaterialParams values(scene.materials[m], l.shader->params);
    for (auto& [name, p] : l.params) {
      const ParamValue v = values.get(name);
      glm::vec4& slot = block[m * static_cast<size_t>(stride_) + static_cast<size_t>(p.slot)];
      p.nonzero = p.nonzero || values.nonzero(name);
      if (p.type == ParamType::Number) {
        slot[p.lane] = v.number;
      } else if (v.kind == ParamValue::Kind::Texture) {
        if (v.texture < 0 || static_cast<size_t>(v.texture) >= scene.textures.size())
          throw SceneError("material '" + scene.materials[m].name + "': parameter '" + name +
                           "' names texture " + std::to_string(v.texture) + " of " +
                           std::to_string(scene.textures.size()));
        slot = glm::vec4(0.0f, 0.0f, 0.0f, static_cast<float>(v.texture));
        p.textured = true;
      } else {
        slot = glm::vec4(v.color, -1.0f);
      }
    }
  }
  // Features forced on (TracerOptions::extra_features, for benchmarks of the specialized
  // against the generic kernel): specular keeps the highlight code of every shader that has
  // a `specular` parameter.
  if (F.specular)
    for (Layout& l : shaders_)
      if (auto it = l.params.find("specular"); it != l.params.end()) it->second.nonzero = true;
  upload_padded(params_, block);
  upload_padded(shader_of_, std::vector<int32_t>(shader_index.begin(), shader_index.end()));
  textures_.upload(scene);
  ambient.set(scene.options.ambient);
  vertex_colors_ = F.vertex_colors;
}

std::vector<std::string> MaterialTable::used_shaders() const {
  std::vector<std::string> names;
  for (const Layout& l : shaders_) names.push_back(l.shader->name);
  return names;
}

const MaterialTable::Param& MaterialTable::param(int shader, const std::string& name,
                                                 ParamType type) const {
  const Layout& l = shaders_.at(static_cast<size_t>(shader));
  auto it = l.params.find(name);
  if (it == l.params.end())
    throw std::invalid_argument("shader '" + l.shader->name + "' reads parameter '" + name +
                                "', which it does not declare");
  if (it->second.type != type)
    throw std::invalid_argument("shader '" + l.shader->name + "' reads parameter '" + name +
                                "' as a " + param_type_name(type) + ", but declares it a " +
                                param_type_name(it->second.type));
  return it->second;
}

MaterialTable::Slots MaterialTable::load(const Surface& s) const {
  Slots slots;
  if (shaders_.empty()) return slots;
  Int row = s.material * stride_;
  for (int i = 0; i < stride_; ++i) slots.push_back(params_[row + i]);
  return slots;
}

Float4 MaterialTable::slot(const Surface& s, int i, const Slots* slots) const {
  if (slots != nullptr) return (*slots)[static_cast<size_t>(i)];
  return params_[s.material * stride_ + i];
}

Float3 MaterialTable::color(int shader, const std::string& name, const Surface& s,
                            const Slots* slots) const {
  const Param& p = param(shader, name, ParamType::Color);
  Float4 v = slot(s, p.slot, slots);
  Float3 c(v.x(), v.y(), v.z());
  if (p.textured) {
    RILL_IF(v.w() >= 0.0f) {
      c = textures_.sample(to_int(v.w()), s.uv, s.P);
    }
    RILL_ENDIF;
  }
  return c;
}

Float MaterialTable::number(int shader, const std::string& name, const Surface& s,
                            const Slots* slots) const {
  const Param& p = param(shader, name, ParamType::Number);
  Float4 v = slot(s, p.slot, slots);
  switch (p.lane) {
    case 0:
      return v.x();
    case 1:
      return v.y();
    case 2:
      return v.z();
    default:
      return v.w();
  }
}

bool MaterialTable::may_be_nonzero(int shader, const std::string& name) const {
  const Layout& l = shaders_.at(static_cast<size_t>(shader));
  auto it = l.params.find(name);
  if (it == l.params.end())
    throw std::invalid_argument("shader '" + l.shader->name + "' asks about parameter '" + name +
                                "', which it does not declare");
  return it->second.nonzero;
}

template <class F>
void MaterialTable::dispatch(const Surface& s, F&& f) const {
  if (shaders_.empty()) return;  // no geometry: nothing is ever shaded
  if (shaders_.size() == 1) {
    f(0);
    return;
  }
  Int which = shader_of_[s.material];
  for (size_t i = 0; i < shaders_.size(); ++i) {
    RILL_IF(which == static_cast<int32_t>(i)) {
      f(static_cast<int>(i));
    }
    RILL_ENDIF;
  }
}

Float3 MaterialTable::emitted(const Surface& s, const Slots* slots) const {
  if (shaders_.size() == 1) {  // called directly: no copy into a shared result
    const SurfaceShader& sh = *shaders_[0].shader;
    return sh.emitted ? sh.emitted(ShadingPoint(s, *this, 0, slots)) : Float3(0.0f);
  }
  Float3 out(0.0f);
  dispatch(s, [&](int i) {
    const SurfaceShader& sh = *shaders_[static_cast<size_t>(i)].shader;
    if (sh.emitted) out = sh.emitted(ShadingPoint(s, *this, i, slots));
  });
  return out;
}

Float3 MaterialTable::reflected(const Surface& s, const LightSample& light,
                                const Slots* slots) const {
  if (shaders_.size() == 1) {
    const SurfaceShader& sh = *shaders_[0].shader;
    return sh.reflected ? sh.reflected(ShadingPoint(s, *this, 0, slots), light) : Float3(0.0f);
  }
  Float3 out(0.0f);
  dispatch(s, [&](int i) {
    const SurfaceShader& sh = *shaders_[static_cast<size_t>(i)].shader;
    if (sh.reflected) out = sh.reflected(ShadingPoint(s, *this, i, slots), light);
  });
  return out;
}

Scatter MaterialTable::scatter(const Surface& s, const Float& weight, const Slots* slots) const {
  if (shaders_.size() == 1 && shaders_[0].shader->scatter)
    return shaders_[0].shader->scatter(ShadingPoint(s, *this, 0, slots), weight);
  Scatter out;
  out.local_weight = weight;
  dispatch(s, [&](int i) {
    const SurfaceShader& sh = *shaders_[static_cast<size_t>(i)].shader;
    if (!sh.scatter) {
      out.local_weight = weight;
      return;
    }
    Scatter r = sh.scatter(ShadingPoint(s, *this, i, slots), weight);
    out.local_weight = r.local_weight;
    out.reflect_weight = r.reflect_weight;
    out.reflect_dir = r.reflect_dir;
    out.transmit_weight = r.transmit_weight;
    out.transmit_dir = r.transmit_dir;
  });
  return out;
}

// The BSDF's calls: one shader is called directly, several through the dispatch into a
// shared result (each branch assigns every field, so the result is the chosen shader's).
template <class R, class Call>
R MaterialTable::call_bsdf(const Surface& s, const Slots* slots, R zero, Call&& call) const {
  if (shaders_.size() == 1) return call(shaders_[0].shader->bsdf, ShadingPoint(s, *this, 0, slots));
  R out = zero;
  dispatch(s, [&](int i) {
    out = call(shaders_[static_cast<size_t>(i)].shader->bsdf, ShadingPoint(s, *this, i, slots));
  });
  return out;
}

Float3 MaterialTable::bsdf_eval(const Surface& s, const Float3& wi, const Slots* slots) const {
  return call_bsdf<Float3>(s, slots, Float3(0.0f),
                           [&](const Bsdf& b, const ShadingPoint& sp) { return b.eval(sp, wi); });
}

BsdfSample MaterialTable::bsdf_sample(const Surface& s, const Float3& u, const Slots* slots) const {
  return call_bsdf<BsdfSample>(s, slots, BsdfSample{}, [&](const Bsdf& b, const ShadingPoint& sp) {
    return b.sample(sp, u);
  });
}

Float MaterialTable::bsdf_pdf(const Surface& s, const Float3& wi, const Slots* slots) const {
  return call_bsdf<Float>(s, slots, Float(0.0f),
                          [&](const Bsdf& b, const ShadingPoint& sp) { return b.pdf(sp, wi); });
}

Float3 MaterialTable::albedo(const Surface& s, const Slots* slots) const {
  auto one = [&](int i) {
    const SurfaceShader& sh = *shaders_[static_cast<size_t>(i)].shader;
    return sh.albedo ? sh.albedo(ShadingPoint(s, *this, i, slots)) : Float3(1.0f);
  };
  if (shaders_.size() == 1) return one(0);
  Float3 out(1.0f);
  dispatch(s, [&](int i) { out = one(i); });
  return out;
}

// ---- ShadingPoint --------------------------------------------------------------------------

ShadingPoint::ShadingPoint(const Surface& surface, const MaterialTable& table, int shader,
                           const std::vector<Float4>* slots)
    : s(surface), table_(table), shader_(shader), slots_(slots) {}

Float3 ShadingPoint::color(const std::string& name) const {
  return table_.color(shader_, name, s, slots_);
}

Float ShadingPoint::number(const std::string& name) const {
  return table_.number(shader_, name, s, slots_);
}

bool ShadingPoint::has_vertex_colors() const {
  return table_.vertex_colors();
}

bool ShadingPoint::may_be_nonzero(const std::string& name) const {
  return table_.may_be_nonzero(shader_, name);
}

Float ShadingPoint::ambient() const {
  return table_.ambient;
}

}  // namespace rt
