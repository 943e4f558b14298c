// The path integrator's stages (PathIntegrator.h).
#include "rill/rt/integrator/PathIntegrator.h"

#include "rill/Random.h"
#include "rill/rt/kernel/Sampling.h"

namespace rt {

using namespace rill;

namespace {
constexpr int kPurposeBsdf = 0;        // x, y, z: the BSDF sample; w: Russian roulette
constexpr int kPurposeLight = 1;       // x: which light; y, z: where on it
constexpr int32_t kKey1 = 0x52696c6c;  // "Rill": the key's second word

Float max3(const Float3& c) {
  return max(max(c.x(), c.y()), c.z());
}
}  // namespace

PathIntegrator::PathIntegrator(const DeviceScene& scene, const LightSampler& lights,
                               const SceneOptions& options)
    : S_(scene),
      lights_(lights),
      nee_(options.nee && lights.any() && scene.F.geometry),
      mis_(options.mis),
      mutation_(scene.K.mutation) {
  seed.set(static_cast<int32_t>(options.seed));
}

Float4 PathIntegrator::random(const Int2& pixel, const Int& depth, int purpose) const {
  const Int& sample = sample_var ? *sample_var : static_cast<const Int&>(sample_index);
  const Int4 counter(pixel.x(), pixel.y(), sample, depth * 4 + purpose);
  return unit_float(philox4x32(counter, Int2(seed, Int(kKey1))));
}

PathItem PathIntegrator::start(const Ray& camera_ray) const {
  return PathItem{camera_ray,  Float3(0.0f), Float3(1.0f), Int(0),
                  Float(0.0f), Bool(true),   Bool(false),  Int(0)};
}

// One light drawn from the lights' table, its shadow ray, and what it brings if unblocked:
// throughput f Li w / pdf, with the power heuristic against the BSDF's density where BSDF
// sampling could have found the light too (not a point light).
ShadowQuery PathIntegrator::light_sample(const PathItem& path, const Surface& s,
                                         const MaterialTable::Slots& slots,
                                         const Int2& pixel) const {
  const Shading& sh = S_.shading;
  const Float4 u = random(pixel, path.depth, kPurposeLight);
  const Float3 o = sh.offset_origin(s.P, s.ngf);
  const LightDraw l = lights_.sample(o, Float3(u.x(), u.y(), u.z()));
  // Stop short of the light by the scene's epsilon, as Whitted's shadow rays do: the
  // emitting triangle itself (or a point light on a surface) does not block.
  ShadowQuery out{Ray{o, l.wi, l.dist - sh.eps}, Float3(0.0f), Bool(false)};
  RILL_IF(l.pdf > 0.0f && max3(l.radiance) > 0.0f) {
    const Float3 f = S_.materials.bsdf_eval(s, l.wi, &slots);
    RILL_IF(max3(f) > 0.0f) {
      Float w = 1.0f;
      if (mis_ && lights_.areas()) {
        const Float p_bsdf = S_.materials.bsdf_pdf(s, l.wi, &slots);
        w = select(l.delta, Float(1.0f), power_heuristic(l.pdf, p_bsdf));
      }
      if (mutation_ == PathMutation::NeeTwice) w = w * 2.0f;
      out.contribution = path.throughput * f * l.radiance * (w / l.pdf);
      out.active = true;
    }
    RILL_ENDIF;
  }
  RILL_ENDIF;
  return out;
}

// The BSDF's sample: the next ray, the throughput, and Russian roulette.
void PathIntegrator::next_ray(PathItem& path, const Surface& s, const MaterialTable::Slots& slots,
                              const Int2& pixel) const {
  const Shading& sh = S_.shading;
  const Float4 u = random(pixel, path.depth, kPurposeBsdf);
  const BsdfSample b = S_.materials.bsdf_sample(s, Float3(u.x(), u.y(), u.z()), &slots);
  path.throughput = path.throughput * b.weight;
  path.bsdf_pdf = b.pdf;
  path.delta = b.delta;
  path.depth += 1;
  const Bool below = dot(b.wi, s.ngf) < 0.0f;
  path.ray = Ray{sh.offset_origin(s.P, select(below, -s.ngf, s.ngf)), b.wi, Float(kBig)};
  Float survive = 1.0f;
  RILL_IF(path.depth >= kRouletteDepth) {
    survive = min(max3(path.throughput), 0.95f);
  }
  RILL_ENDIF;
  RILL_IF(!(max3(path.throughput) > 0.0f) || u.w() >= survive) {
    path.done = true;
  }
  RILL_ELSE {
    if (mutation_ != PathMutation::NoRouletteBoost) path.throughput = path.throughput / survive;
  }
  RILL_ENDIF;
}

ShadowQuery PathIntegrator::shade(PathItem& path, const Hit& hit, const Int2& pixel,
                                  FirstHit* first) const {
  const Shading& sh = S_.shading;
  ShadowQuery shadow{Ray{Float3(0.0f), Float3(0.0f, 0.0f, 1.0f), Float(0.0f)}, Float3(0.0f),
                     Bool(false)};
  path.rays += 1;  // the ray that found `hit`
  RILL_IF(hit.id < 0) {
    // A uniform environment of radiance `background`; nothing samples it but the BSDF, so
    // its light is taken whole.
    path.radiance += path.throughput * sh.background;
    path.done = true;
  }
  RILL_ELSE {
    const Surface s = sh.surface(path.ray, hit);
    const MaterialTable::Slots slots = sh.material(s);
    if (first != nullptr) {
      RILL_IF(first->only_if ? path.depth == 0 && *first->only_if : path.depth == 0) {
        first->depth = hit.t;
        first->prim = hit.id;
        first->normal = s.ns;
        first->albedo = S_.materials.albedo(s, &slots);
      }
      RILL_ENDIF;
    }
    if (lights_.areas()) {
      const Float3 le = lights_.emission(s);
      RILL_IF(max3(le) > 0.0f) {
        Float w = 1.0f;
        if (nee_ && mutation_ != PathMutation::NoMisAtHits) {
          // Light sampling could have found this point too (unless the BSDF sample came from a
          // delta lobe): the power heuristic, or nothing without MIS (NEE counts it alone).
          const Float p_light = lights_.pdf(hit.id, hit.t, path.ray.d);
          const Float w_mis = mis_ ? power_heuristic(path.bsdf_pdf, p_light) : Float(0.0f);
          w = select(path.delta, Float(1.0f), w_mis);
        }
        path.radiance += path.throughput * le * w;
      }
      RILL_ENDIF;
    }
    RILL_IF(path.depth >= sh.max_depth) {
      path.done = true;
    }
    RILL_ELSE {
      if (nee_) {
        RILL_IF(lights_.smooth(s)) {
          shadow = light_sample(path, s, slots, pixel);
        }
        RILL_ENDIF;
      }
      next_ray(path, s, slots, pixel);
    }
    RILL_ENDIF;
  }
  RILL_ENDIF;
  return shadow;
}

void PathIntegrator::shadow_result(PathItem& path, const ShadowQuery& query,
                                   const Hit& blocker) const {
  path.rays += 1;
  RILL_IF(blocker.id < 0) {
    path.radiance += query.contribution;
  }
  RILL_ENDIF;
}

}  // namespace rt
