// The glass shader (Builtin.h): phong's local light, and the rest of the path weight split
// between a reflected and a refracted ray by Schlick's approximation of the Fresnel term;
// total internal reflection sends it all to the reflected ray.
#include "rill/rt/shaders/Builtin.h"
#include "rill/rt/shaders/Lobes.h"
#include "rill/rt/shaders/PhongLight.h"

namespace rt {

namespace {

// The refracted direction and Schlick's Fresnel reflectance (1 under total internal
// reflection), which Whitted's scatter and the path-traced lobes share.
struct Refraction {
  Float3 direction;
  Float fresnel;
};

Refraction refraction(const Surface& su, const Float3& inc, const Float& ior) {
  Float eta = select(su.entering, 1.0f / ior, ior);
  Float cosi = dot(su.V, su.nf);
  Float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
  Bool tir = k < 0.0f;
  Float sk = sqrt(max(k, 0.0f));
  Float3 dir = eta * inc + (eta * cosi - sk) * su.nf;
  Float r0 = (ior - 1.0f) / (ior + 1.0f);
  r0 = r0 * r0;
  Float c = 1.0f - select(su.entering, cosi, sk);
  Float c2 = c * c;
  return Refraction{dir, select(tir, 1.0f, r0 + (1.0f - r0) * (c2 * c2 * c))};
}

}  // namespace

SurfaceShader glass_shader() {
  SurfaceShader s;
  s.name = "glass";
  s.doc = "refraction with Fresnel reflection (Schlick), plus phong's local light";
  s.params = phong_params();
  s.params.push_back(
      {"transmit", ParamType::Number, ParamValue::of(0.9f), "share of the light refracted"});
  s.params.push_back({"ior", ParamType::Number, ParamValue::of(1.5f), "index of refraction"});
  s.emitted = phong_emitted;
  s.reflected = phong_reflected;
  // Whitted. (Written out rather than through refraction(): the Whitted kernels' generated
  // source stays byte-identical to the one before the path integrator, which the identity
  // script in docs/benchmarks checks.)
  s.scatter = [](const ShadingPoint& sp, const Float& weight) {
    const Surface& su = sp.s;
    Float refl = sp.number("reflect"), trans = sp.number("transmit"), ior = sp.number("ior");
    Scatter out;
    out.local_weight = weight * (1.0f - refl - trans);
    const Float3 inc = -su.V;
    out.reflect_dir = reflect(inc, su.nf);
    Float eta = select(su.entering, 1.0f / ior, ior);
    Float cosi = dot(su.V, su.nf);
    Float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
    Bool tir = k < 0.0f;
    Float sk = sqrt(max(k, 0.0f));
    out.transmit_dir = eta * inc + (eta * cosi - sk) * su.nf;
    Float r0 = (ior - 1.0f) / (ior + 1.0f);
    r0 = r0 * r0;
    Float c = 1.0f - select(su.entering, cosi, sk);
    Float c2 = c * c;
    Float fres = select(tir, 1.0f, r0 + (1.0f - r0) * (c2 * c2 * c));
    out.reflect_weight = weight * (refl + trans * fres);
    out.transmit_weight = weight * trans * (1.0f - fres);
    return out;
  };
  // Path tracing: diffuse with probability (and share) 1 - reflect - transmit, a perfect
  // mirror with reflect + transmit F, and the refraction with transmit (1 - F), both delta
  // lobes of weight 1. Radiance is not scaled by 1 / eta^2 across the surface (a path that
  // enters a closed glass object leaves it again, where the two factors cancel).
  s.bsdf = mixture_bsdf(
      [](const ShadingPoint& sp) {
        const Surface& su = sp.s;
        const Float refl = sp.number("reflect"), trans = sp.number("transmit");
        const Refraction rf = refraction(su, -su.V, sp.number("ior"));
        Lobe through{trans * (1.0f - rf.fresnel), true};
        const Float3 dir = rf.direction;
        through.sample = [dir](const Float2&) { return dir; };
        through.delta_weight = Float3(1.0f);
        return std::vector<Lobe>{diffuse_lobe(sp, 1.0f - refl - trans),
                                 mirror_lobe(sp, refl + trans * rf.fresnel), through};
      },
      [](const MaterialParams& p) { return p.number("reflect") + p.number("transmit") < 1.0f; });
  s.albedo = [](const ShadingPoint& sp) {
    const Float specular = sp.number("reflect") + sp.number("transmit");
    return Float3(phong_diffuse(sp) * (1.0f - specular) + specular);
  };
  s.lobes = [](const MaterialParams& p) { return Lobes{true, p.nonzero("transmit")}; };
  s.check = [](const MaterialParams& p) -> std::string {
    const float reflect = p.number("reflect"), transmit = p.number("transmit");
    if (!(reflect >= 0 && transmit >= 0 && reflect + transmit <= 1.0f))
      return "reflect and transmit must be >= 0 with reflect + transmit <= 1";
    if (std::string why = shininess_problem(p.number("shininess")); !why.empty()) return why;
    const float ior = p.number("ior");
    return ior > 0.0f && ior <= 100.0f ? "" : "ior must be in (0, 100]";
  };
  return s;
}

}  // namespace rt
