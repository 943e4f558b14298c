// BsdfProbe: one material's BSDF (kernel/Shader.h, Bsdf) run on a backend, outside any
// render, for tests and for users writing a shader: what sample gives for chosen wo and u, and
// what eval and pdf give for chosen wo and wi.
//
//   rt::Material m;
//   m.shader = "ggx";
//   m.set("roughness", 0.3f).set("specular", glm::vec3(0.9f));
//   rt::BsdfProbe probe(m, "cpu");              // throws SceneError for a bad material
//   std::vector<rt::ProbeSample> s = probe.sample(wo, us);  // wi, weight, pdf, delta per u
//   std::vector<rt::ProbeEval> e = probe.eval(wo, wis);     // eval (f |cos|) and pdf per wi
//
// The shader is resolved through the registry (shaders/Registry.h) when the probe is built,
// so a shader registered under a new name (a test's mutant, a user's draft) is probed as it
// is then. Internally the probe holds a one-triangle Scene with the material, so that
// MaterialTable::upload lays out and uploads exactly that material, and two Rill programs
// over the table: "rill_bsdf_probe_sample" (inputs wo, u; outputs wi, weight, pdf, delta) and
// "rill_bsdf_probe_eval" (inputs wo, wi; outputs eval, pdf), compiled for the backend at the
// first call (and then cached like every kernel).
//
// The surface every element sees: P = 0, ns = nf = ngf = (0, 0, 1), V = wo, uv = 0,
// entering = true, vertex_color = 1, material 0. So directions are in the local frame of the
// surface: z is the normal, and wo should be a unit vector (the probe does not normalize it);
// u is three uniform numbers in [0, 1) as Bsdf::sample takes them. Vector overloads take one
// wo per element (the sizes must agree); the others use one wo for every element.
#pragma once

#include <glm/glm.hpp>

#include <memory>
#include <string>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

// What Bsdf::sample gave for one (wo, u).
struct ProbeSample {
  glm::vec3 wi{0.0f};
  glm::vec3 weight{0.0f};  // eval / pdf, or a delta lobe's weight; 0: the path ends
  float pdf = 0.0f;        // solid-angle density, or a delta lobe's probability
  bool delta = false;
};

// What Bsdf::eval and Bsdf::pdf gave for one (wo, wi).
struct ProbeEval {
  glm::vec3 eval{0.0f};  // f(wo, wi) |cos(wi)|, without delta lobes
  float pdf = 0.0f;
};

class BsdfProbe {
 public:
  // Throws SceneError when the material's shader is not registered or its values are bad
  // (resolve_shaders), std::invalid_argument when the shader has no BSDF.
  explicit BsdfProbe(const Material& material, const std::string& backend = "cpu");
  ~BsdfProbe();
  BsdfProbe(const BsdfProbe&) = delete;
  BsdfProbe& operator=(const BsdfProbe&) = delete;

  std::vector<ProbeSample> sample(const std::vector<glm::vec3>& wo,
                                  const std::vector<glm::vec3>& u);
  std::vector<ProbeSample> sample(const glm::vec3& wo, const std::vector<glm::vec3>& u);
  std::vector<ProbeEval> eval(const std::vector<glm::vec3>& wo, const std::vector<glm::vec3>& wi);
  std::vector<ProbeEval> eval(const glm::vec3& wo, const std::vector<glm::vec3>& wi);

  const std::string& backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
};

}  // namespace rt
