// The phong shader (Builtin.h) and the Phong local light it shares with glass.
#include "rill/rt/shaders/Builtin.h"
#include "rill/rt/shaders/Lobes.h"
#include "rill/rt/shaders/PhongLight.h"

#include "rill/StrictMath.h"

namespace rt {

std::vector<ShaderParam> phong_params() {
  return {
      {"diffuse", ParamType::Color, ParamValue::of(glm::vec3(0.8f)), "diffuse colour (Kd)"},
      {"specular", ParamType::Color, ParamValue::of(glm::vec3(0.0f)),
       "colour of the highlights (Ks)"},
      {"shininess", ParamType::Number, ParamValue::of(32.0f),
       "Phong exponent (Ns): larger, smaller highlights"},
      {"reflect", ParamType::Number, ParamValue::of(0.0f), "mirror reflection, 0 to 1"},
  };
}

std::string reflect_problem(float reflect) {
  return reflect >= 0.0f && reflect <= 1.0f ? "" : "reflect must be in [0, 1]";
}

std::string shininess_problem(float shininess) {
  return shininess >= 0.0f && shininess <= 1e4f ? "" : "shininess must be in [0, 10000]";
}

Scatter mirror_scatter(const ShadingPoint& sp, const Float& weight, const Float& r) {
  Scatter out;
  out.local_weight = weight * (1.0f - r);
  out.reflect_weight = weight * r;
  out.reflect_dir = reflect(-sp.s.V, sp.s.nf);
  return out;
}

Lobe mirror_lobe(const ShadingPoint& sp, const Float& p) {
  const Surface& s = sp.s;
  Lobe l{p, true};
  l.sample = [&s](const Float2&) { return mirror_direction(s); };
  l.delta_weight = Float3(1.0f);  // reflectance p over probability p
  return l;
}

Float3 phong_diffuse(const ShadingPoint& sp) {
  if (!sp.has_vertex_colors()) return sp.color("diffuse");
  return sp.color("diffuse") * sp.s.vertex_color;
}

Float3 phong_emitted(const ShadingPoint& sp) {
  return sp.ambient() * phong_diffuse(sp);
}

Float3 phong_reflected(const ShadingPoint& sp, const LightSample& light) {
  Float ndl = dot(sp.s.nf, light.L);
  Float3 c = phong_diffuse(sp) * max(ndl, 0.0f);
  if (!light.headlight && sp.may_be_nonzero("specular")) {
    Float3 R = reflect(-light.L, sp.s.nf);
    Float rv = max(dot(R, sp.s.V), 0.0f);
    const Float n = sp.number("shininess");
    const Float3 ks = sp.color("specular");
    // pow is the light's costliest step (in strict mode Rill's own routine, about a hundred
    // operations), so it runs only where its term can change the colour. rv is 0 wherever
    // the mirror direction faces away from the eye, where pow_of_zero gives pow's bits in a
    // few selects (zero is told as pow tells it, by the bits, so a backend that flushes
    // denormals in comparisons still sends one to pow). Away from the highlight's peak, ks
    // times pow is below half an ulp of the diffuse term it is added to (pow_term_is_lost),
    // and the sum is the diffuse term with or without it; there, too, pow_of_zero's 0 takes
    // its place. Only the bits that cannot change are left out: the images stay the same.
    Bool lost = true;
    for (int k = 0; k < 3; ++k) lost = lost && rill::strict::pow_term_is_lost(c[k], ks[k], rv, n);
    lost = lost || !(ndl > 0.0f);  // the select below drops the term
    Float highlight = rill::strict::pow_of_zero(rv, n);
    RILL_IF(!rill::strict::is_zero(rv) && !lost) {
      highlight = pow(rv, n);
    }
    RILL_ENDIF;
    c = c + select(ndl > 0.0f, ks * highlight, Float3(0.0f));
  }
  return Float3(c * light.color);
}

SurfaceShader phong_shader() {
  SurfaceShader s;
  s.name = "phong";
  s.doc = "Phong diffuse and highlights, with optional mirror reflection";
  s.params = phong_params();
  s.emitted = phong_emitted;
  s.reflected = phong_reflected;
  s.scatter = [](const ShadingPoint& sp, const Float& weight) {
    if (!sp.may_be_nonzero("reflect")) {  // no material reflects: the path ends here
      Scatter out;
      out.local_weight = weight;
      return out;
    }
    return mirror_scatter(sp, weight, sp.number("reflect"));
  };
  s.lobes = [](const MaterialParams& p) { return Lobes{p.nonzero("reflect"), false}; };
  // Path tracing: diffuse (1 - reflect) and a perfect mirror (reflect); the highlights of
  // specular and shininess belong to Whitted's point lights and are not part of it.
  s.bsdf = mixture_bsdf(
      [](const ShadingPoint& sp) {
        if (!sp.may_be_nonzero("reflect")) return std::vector<Lobe>{diffuse_lobe(sp, Float(1.0f))};
        const Float r = sp.number("reflect");
        return std::vector<Lobe>{diffuse_lobe(sp, 1.0f - r), mirror_lobe(sp, r)};
      },
      [](const MaterialParams& p) { return p.number("reflect") < 1.0f; });
  s.albedo = [](const ShadingPoint& sp) {
    if (!sp.may_be_nonzero("reflect")) return phong_diffuse(sp);
    const Float r = sp.number("reflect");
    return Float3(phong_diffuse(sp) * (1.0f - r) + r);
  };
  s.check = [](const MaterialParams& p) {
    std::string why = reflect_problem(p.number("reflect"));
    return why.empty() ? shininess_problem(p.number("shininess")) : why;
  };
  return s;
}

}  // namespace rt
