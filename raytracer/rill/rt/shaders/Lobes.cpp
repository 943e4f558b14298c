// The built-in shaders' lobes and their mixture (Lobes.h).
#include "rill/rt/shaders/Lobes.h"

namespace rt {

using namespace rill;

Bool reflects(const Surface& s, const Float3& wi) {
  return dot(s.nf, wi) > 0.0f && dot(s.ngf, wi) > 0.0f;
}

Float3 lambert_eval(const Surface& s, const Float3& kd, const Float3& wi) {
  const Float c = dot(s.nf, wi);
  return select(reflects(s, wi), kd * (c * kInvPi), Float3(0.0f));
}

Float lambert_pdf(const Surface& s, const Float3& wi) {
  const Float c = dot(s.nf, wi);
  return select(reflects(s, wi), c * kInvPi, Float(0.0f));
}

Float3 lambert_sample(const Surface& s, const Float2& u) {
  return Basis(s.nf).to_world(cosine_hemisphere(u));
}

Float3 mirror_direction(const Surface& s) {
  return reflect(-s.V, s.nf);
}

Float3 schlick(const Float3& f0, const Float& cos_theta) {
  const Float c = 1.0f - clamp(cos_theta, 0.0f, 1.0f);
  const Float c2 = c * c;
  return f0 + (Float3(1.0f) - f0) * (c2 * c2 * c);
}

// ---- GGX ------------------------------------------------------------------------------------

Ggx::Ggx(const Surface& surface, const Float& roughness, const Float3& specular)
    : s(surface), frame(surface.nf), alpha(max(roughness * roughness, 1e-3f)), f0(specular) {
  wo = frame.to_local(s.V);
}

Float Ggx::d(const Float3& h) const {
  // h is a unit vector, so cos^2 (a2 - 1) + 1 = sin^2 + a2 cos^2; written so, with sin^2 from
  // h.x and h.y, it has no cancellation: near the peak of a narrow lobe 1 - cos^2 in float
  // loses the digits that a2 (down to 1e-6) needs.
  const Float a2 = alpha * alpha;
  const Float t = (h.x() * h.x() + h.y() * h.y()) + h.z() * h.z() * a2;
  return a2 / (kPi * t * t);
}

Float Ggx::lambda(const Float3& w) const {
  const Float z2 = max(w.z() * w.z(), 1e-12f);
  const Float tan2 = (w.x() * w.x() + w.y() * w.y()) / z2;
  return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

Float3 Ggx::eval(const Float3& wi_world) const {
  const Float3 wi = frame.to_local(wi_world);
  const Bool ok = reflects(s, wi_world) && wo.z() > 0.0f;
  const Float3 h = normalize(wo + wi);
  const Float g2 = 1.0f / (1.0f + lambda(wo) + lambda(wi));
  // f cos(wi) = F D G2 / (4 cos(wo) cos(wi)) cos(wi)
  const Float3 f = schlick(f0, dot(wo, h)) * (d(h) * g2 / (4.0f * max(wo.z(), 1e-12f)));
  return select(ok, f, Float3(0.0f));
}

Float Ggx::pdf(const Float3& wi_world) const {
  const Float3 wi = frame.to_local(wi_world);
  const Bool ok = reflects(s, wi_world) && wo.z() > 0.0f;
  const Float3 h = normalize(wo + wi);
  // Visible normals: D_wo(h) = G1(wo) max(wo.h, 0) D(h) / cos(wo), times the reflection's
  // Jacobian 1 / (4 wo.h): G1(wo) D(h) / (4 cos(wo)).
  const Float g1 = 1.0f / (1.0f + lambda(wo));
  return select(ok, g1 * d(h) / (4.0f * max(wo.z(), 1e-12f)), Float(0.0f));
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)).
Float3 Ggx::sample(const Float2& u) const {
  const Float3 vh = normalize(Float3(alpha * wo.x(), alpha * wo.y(), max(wo.z(), 0.0f)));
  const Float lensq = vh.x() * vh.x() + vh.y() * vh.y();
  const Float inv = 1.0f / sqrt(select(lensq > 0.0f, lensq, Float(1.0f)));
  const Float3 t1 =
      select(lensq > 0.0f, Float3(-vh.y() * inv, vh.x() * inv, 0.0f), Float3(1.0f, 0.0f, 0.0f));
  const Float3 t2 = cross(vh, t1);
  const Float r = sqrt(u.x());
  const Float phi = (2.0f * kPi) * u.y();
  const Float p1 = r * cos(phi);
  const Float sh = 0.5f * (1.0f + vh.z());
  const Float p2 = (1.0f - sh) * sqrt(max(1.0f - p1 * p1, 0.0f)) + sh * (r * sin(phi));
  const Float3 nh = t1 * p1 + t2 * p2 + vh * sqrt(max(1.0f - p1 * p1 - p2 * p2, 0.0f));
  const Float3 m = normalize(Float3(alpha * nh.x(), alpha * nh.y(), max(nh.z(), 0.0f)));
  const Float3 wi = m * (2.0f * dot(wo, m)) - wo;
  return frame.to_world(wi);
}

// ---- Mixtures -------------------------------------------------------------------------------

Float3 mix_eval(const std::vector<Lobe>& lobes, const Float3& wi) {
  Float3 sum(0.0f);
  for (const Lobe& l : lobes)
    if (!l.delta) sum += l.eval(wi);
  return sum;
}

Float mix_pdf(const std::vector<Lobe>& lobes, const Float3& wi) {
  Float sum = 0.0f;
  for (const Lobe& l : lobes)
    if (!l.delta) sum += l.probability * l.pdf(wi);
  return sum;
}

BsdfSample mix_sample(const Surface& s, const std::vector<Lobe>& lobes, const Float3& u) {
  (void)s;
  BsdfSample out;
  const Float2 uv(u.y(), u.z());
  bool any_smooth = false, any_delta = false;
  for (const Lobe& l : lobes) (l.delta ? any_delta : any_smooth) = true;
  if (lobes.size() == 1 && !any_delta) {  // one smooth lobe: no choice to make
    out.wi = lobes[0].sample(uv);
  } else {
    Bool taken = false;
    Float end = 0.0f;
    for (const Lobe& l : lobes) {
      end = end + l.probability;
      RILL_IF(!taken && u.x() < end) {
        taken = true;
        out.wi = l.sample(uv);
        if (l.delta) {
          out.weight = l.delta_weight;
          out.pdf = l.probability;
          out.delta = true;
        }
      }
      RILL_ENDIF;
    }
    if (any_smooth) out.delta = out.delta || !taken;  // nothing taken: absorbed (weight 0)
  }
  if (any_smooth) {
    // A smooth lobe's direction weighs by the whole mixture: eval / pdf of every smooth lobe
    // (one-sample MIS between the lobes, so sample agrees with pdf by construction).
    RILL_IF(!out.delta) {
      const Float p = mix_pdf(lobes, out.wi);
      const Float3 e = mix_eval(lobes, out.wi);
      out.pdf = p;
      out.weight = select(p > 0.0f, e / select(p > 0.0f, p, Float(1.0f)), Float3(0.0f));
    }
    RILL_ENDIF;
  }
  return out;
}

Bsdf mixture_bsdf(std::function<std::vector<Lobe>(const ShadingPoint&)> lobes,
                  std::function<bool(const MaterialParams&)> smooth) {
  Bsdf b;
  b.eval = [lobes](const ShadingPoint& sp, const Float3& wi) { return mix_eval(lobes(sp), wi); };
  b.pdf = [lobes](const ShadingPoint& sp, const Float3& wi) { return mix_pdf(lobes(sp), wi); };
  b.sample = [lobes](const ShadingPoint& sp, const Float3& u) {
    return mix_sample(sp.s, lobes(sp), u);
  };
  b.smooth = std::move(smooth);
  return b;
}

}  // namespace rt
