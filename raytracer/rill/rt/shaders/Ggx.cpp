// The ggx shader (Builtin.h): a microfacet conductor, or plastic with a diffuse base.
//
// Path tracing: f = f_ggx + (1 - max(specular)) diffuse / pi, where f_ggx is the GGX lobe
// with Schlick's Fresnel term of F0 = specular and Smith's height-correlated masking
// (Lobes.h). The diffuse base is scaled by 1 - max(F0) so that the sum never reflects more
// than it receives; it ignores the light the specular layer sends back in (a documented
// simplification, not a layered model). The specular lobe is chosen with probability
// lum(F0) / (lum(F0) + lum(base)). Roughness 0 is a perfect mirror (a delta lobe of
// reflectance F(cos)). Under Whitted the surface's local light is pi f per point light (so
// that the diffuse base reads as phong's diffuse), and nothing is reflected recursively.
#include "rill/rt/shaders/Builtin.h"
#include "rill/rt/shaders/Lobes.h"
#include "rill/rt/shaders/PhongLight.h"

#include <memory>

namespace rt {

namespace {

std::vector<Lobe> ggx_lobes(const ShadingPoint& sp) {
  const Surface& s = sp.s;
  const Float roughness = sp.number("roughness");
  const Float3 f0 = sp.color("specular");
  auto ggx = std::make_shared<Ggx>(s, roughness, f0);
  const bool base = sp.may_be_nonzero("diffuse");
  Float3 kd(0.0f);
  Float p_spec = 1.0f;
  if (base) {
    kd = phong_diffuse(sp) * (1.0f - max(max(f0.x(), f0.y()), f0.z()));
    const Float ls = luminance(f0), ld = luminance(kd);
    p_spec = select(ls + ld > 0.0f, ls / select(ls + ld > 0.0f, ls + ld, Float(1.0f)), Float(1.0f));
  }
  const Bool mirror = roughness == 0.0f;
  std::vector<Lobe> lobes;
  Lobe spec{select(mirror, Float(0.0f), p_spec)};
  spec.eval = [ggx](const Float3& wi) { return ggx->eval(wi); };
  spec.pdf = [ggx](const Float3& wi) { return ggx->pdf(wi); };
  spec.sample = [ggx](const Float2& u) { return ggx->sample(u); };
  lobes.push_back(spec);
  // Roughness 0: the same probability goes to a perfect mirror instead.
  Lobe delta{select(mirror, p_spec, Float(0.0f)), true};
  delta.sample = [&s](const Float2&) { return mirror_direction(s); };
  delta.delta_weight = schlick(f0, dot(s.V, s.nf)) / select(p_spec > 0.0f, p_spec, Float(1.0f));
  lobes.push_back(delta);
  if (base) {
    Lobe d{1.0f - p_spec};
    d.eval = [&s, kd](const Float3& wi) { return lambert_eval(s, kd, wi); };
    d.pdf = [&s](const Float3& wi) { return lambert_pdf(s, wi); };
    d.sample = [&s](const Float2& u) { return lambert_sample(s, u); };
    lobes.push_back(d);
  }
  return lobes;
}

}  // namespace

SurfaceShader ggx_shader() {
  SurfaceShader s;
  s.name = "ggx";
  s.doc = "GGX microfacet reflection (conductor, or plastic with a diffuse base)";
  s.params = {
      {"roughness", ParamType::Number, ParamValue::of(0.3f),
       "0 (a perfect mirror) to 1; GGX alpha = roughness^2, at least 0.001"},
      {"specular", ParamType::Color, ParamValue::of(glm::vec3(0.9f)),
       "reflectance at normal incidence (F0): about 0.04 for plastic, 0.5-1 for metals"},
      {"diffuse", ParamType::Color, ParamValue::of(glm::vec3(0.0f)),
       "the diffuse base under the specular layer (0: a conductor)"},
  };
  s.emitted = phong_emitted;
  s.reflected = [](const ShadingPoint& sp, const LightSample& light) {
    const Float3 f = mix_eval(ggx_lobes(sp), light.L);
    return f * kPi * light.color;
  };
  s.bsdf = mixture_bsdf(ggx_lobes, [](const MaterialParams& p) {
    return p.number("roughness") > 0.0f || p.nonzero("diffuse");
  });
  // F0 plus the base as the BSDF weighs it.
  s.albedo = [](const ShadingPoint& sp) {
    const Float3 f0 = sp.color("specular");
    if (!sp.may_be_nonzero("diffuse")) return f0;
    return Float3(f0 + phong_diffuse(sp) * (1.0f - max(max(f0.x(), f0.y()), f0.z())));
  };
  s.check = [](const MaterialParams& p) -> std::string {
    const float r = p.number("roughness");
    if (!(r >= 0.0f && r <= 1.0f)) return "roughness must be in [0, 1]";
    for (const char* c : {"specular", "diffuse"}) {
      const ParamValue v = p.get(c);
      if (v.kind == ParamValue::Kind::Color &&
          (v.color.x > 1.0f || v.color.y > 1.0f || v.color.z > 1.0f))
        return std::string(c) + " must be at most 1";
    }
    return "";
  };
  return s;
}

}  // namespace rt
