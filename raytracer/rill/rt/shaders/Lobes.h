// The BSDF lobes the built-in shaders are made of (Shader.h, Bsdf), as DSL functions of the
// shading point: Lambertian diffuse, the perfect mirror, Schlick's Fresnel term and the GGX
// microfacet lobe (Trowbridge and Reitz 1975, Walter et al. 2007) with Smith's
// height-correlated masking and Heitz's (2018) sampling of visible normals. A shader combines
// them (BsdfMix) and gets eval, sample and pdf that agree by construction: sample draws a lobe
// by its probability, then a direction from it, and weighs it by the mixture's eval / pdf.
#pragma once

#include <functional>
#include <vector>

#include "rill/rt/kernel/Sampling.h"
#include "rill/rt/kernel/Shader.h"

namespace rt {

// Whether wi leaves on the side the ray came from, by both the shading and the geometric
// normal (a reflection lobe is 0 elsewhere: no light leaks through a smooth-shaded edge).
Bool reflects(const Surface& s, const Float3& wi);

// Lambertian reflection of albedo kd: f = kd / pi, sampled cosine-weighted about nf.
Float3 lambert_eval(const Surface& s, const Float3& kd, const Float3& wi);
Float lambert_pdf(const Surface& s, const Float3& wi);
Float3 lambert_sample(const Surface& s, const Float2& u);

// The mirror direction of V about nf.
Float3 mirror_direction(const Surface& s);
// Schlick's Fresnel approximation for reflectance f0 at cos_theta.
Float3 schlick(const Float3& f0, const Float& cos_theta);

// GGX with alpha = roughness^2 (kept at 1e-3 or more: below, D's denominator would leave
// float's normal range and a backend that flushes denormals would differ). F0 = specular.
struct Ggx {
  Ggx(const Surface& s, const Float& roughness, const Float3& f0);
  Float3 eval(const Float3& wi) const;  // f cos, 0 below the surface
  Float pdf(const Float3& wi) const;    // the visible normals' density, reflected
  Float3 sample(const Float2& u) const;
  const Surface& s;
  Basis frame;
  Float alpha;
  Float3 f0;
  Float3 wo;  // V in the frame

 private:
  Float d(const Float3& h) const;       // the normal distribution
  Float lambda(const Float3& w) const;  // Smith's Lambda
};

// A shader's BSDF as a mixture of lobes, each chosen with a probability (the probabilities
// sum to 1 or less: the rest absorbs). A smooth lobe has eval, pdf and a direction sampler; a
// delta lobe only a direction and a weight (its reflectance over its probability is what the
// throughput takes on).
struct Lobe {
  explicit Lobe(const Float& p, bool is_delta = false) : probability(p), delta(is_delta) {}
  Float probability;
  bool delta = false;
  std::function<Float3(const Float3& wi)> eval;  // smooth lobes
  std::function<Float(const Float3& wi)> pdf;    // smooth lobes
  std::function<Float3(const Float2& u)> sample;
  Float3 delta_weight{0.0f};  // delta lobes: reflectance / probability
};

// The mixture's three functions over `lobes` (at least one). eval and pdf sum the smooth
// lobes (pdf weighted by their probabilities); sample picks a lobe with u.x.
Float3 mix_eval(const std::vector<Lobe>& lobes, const Float3& wi);
Float mix_pdf(const std::vector<Lobe>& lobes, const Float3& wi);
BsdfSample mix_sample(const Surface& s, const std::vector<Lobe>& lobes, const Float3& u);

// A Bsdf whose three functions build `lobes(sp)` where they are called.
Bsdf mixture_bsdf(std::function<std::vector<Lobe>(const ShadingPoint&)> lobes,
                  std::function<bool(const MaterialParams&)> smooth);

}  // namespace rt
