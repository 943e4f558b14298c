// The diffuse shader (Builtin.h): a Lambertian surface. Under Whitted its local light is
// phong's without highlights (ambient and N.L); under the path integrator f = diffuse / pi.
#include "rill/rt/shaders/Builtin.h"
#include "rill/rt/shaders/Lobes.h"
#include "rill/rt/shaders/PhongLight.h"

#include <memory>

namespace rt {

// The diffuse lobe of the colour phong_diffuse gives (the parameter, its texture, vertex
// colours), chosen with probability p.
Lobe diffuse_lobe(const ShadingPoint& sp, const Float& p) {
  const Surface& s = sp.s;
  const Float3 kd = phong_diffuse(sp);
  Lobe l{p};
  l.eval = [&s, kd, p](const Float3& wi) { return lambert_eval(s, kd * p, wi); };
  l.pdf = [&s](const Float3& wi) { return lambert_pdf(s, wi); };
  l.sample = [&s](const Float2& u) { return lambert_sample(s, u); };
  return l;
}

SurfaceShader diffuse_shader() {
  SurfaceShader s;
  s.name = "diffuse";
  s.doc = "a Lambertian surface (path: f = diffuse / pi)";
  s.params = {{"diffuse", ParamType::Color, ParamValue::of(glm::vec3(0.8f)),
               "reflectance (albedo), 0 to 1"}};
  s.emitted = phong_emitted;
  s.reflected = [](const ShadingPoint& sp, const LightSample& light) {
    return phong_diffuse(sp) * max(dot(sp.s.nf, light.L), 0.0f) * light.color;
  };
  s.bsdf = mixture_bsdf(
      [](const ShadingPoint& sp) { return std::vector<Lobe>{diffuse_lobe(sp, Float(1.0f))}; },
      nullptr);
  s.albedo = phong_diffuse;
  s.check = [](const MaterialParams& p) -> std::string {
    const glm::vec3 kd = p.get("diffuse").color;
    return kd.x <= 1.0f && kd.y <= 1.0f && kd.z <= 1.0f ? "" : "diffuse must be at most 1";
  };
  return s;
}

}  // namespace rt
