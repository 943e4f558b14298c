// The path integrator's DSL functions (PathIntegrator.h).
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

// The loop's state from one path vertex to the next.
struct PathIntegrator::Vertex {
  Ray ray{Float3(0.0f), Float3(0.0f), Float(kBig)};
  Float3 radiance{0.0f};
  Float3 throughput{1.0f};
  Int depth = 0;
  // The density of the BSDF sample that made `ray`, and whether it came from a delta lobe
  // (the camera ray counts as one: the light it finds is taken whole).
  Float bsdf_pdf = 0.0f;
  Bool delta = true;
  Bool done = false;
  Int rays = 0;
};

PathIntegrator::PathIntegrator(const DeviceScene& scene, const LightSampler& lights,
                               const SceneOptions& options)
    : S_(scene), lights_(lights), nee_(options.nee && lights.any()), mis_(options.mis) {
  seed.set(static_cast<int32_t>(options.seed));
}

Float4 PathIntegrator::random(const Int2& pixel, const Int& depth, int purpose) const {
  const Int4 counter(pixel.x(), pixel.y(), sample_index, depth * 4 + purpose);
  return unit_float(philox4x32(counter, Int2(seed, Int(kKey1))));
}

void PathIntegrator::light_sample(Vertex& v, const Surface& s, const MaterialTable::Slots& slots,
                                  const Int2& pixel) const {
  const Shading& sh = S_.shading;
  const Float4 u = random(pixel, v.depth, kPurposeLight);
  const Float3 o = sh.offset_origin(s.P, s.ngf);
  const LightDraw l = lights_.sample(o, Float3(u.x(), u.y(), u.z()));
  RILL_IF(l.pdf > 0.0f && max3(l.radiance) > 0.0f) {
    const Float3 f = S_.materials.bsdf_eval(s, l.wi, &slots);
    RILL_IF(max3(f) > 0.0f) {
      // Stop short of the light by the scene's epsilon, as Whitted's shadow rays do: the
      // emitting triangle itself (or a point light on a surface) does not block.
      const Ray shadow{o, l.wi, l.dist - sh.eps};
      const Bool any_hit = true;
      const Hit blocker = S_.intersector.intersect(shadow, &any_hit);
      v.rays += 1;
      RILL_IF(blocker.id < 0) {
        Float w = 1.0f;
        if (mis_ && lights_.areas()) {
          const Float p_bsdf = S_.materials.bsdf_pdf(s, l.wi, &slots);
          w = select(l.delta, Float(1.0f), power_heuristic(l.pdf, p_bsdf));
        }
        v.radiance += v.throughput * f * l.radiance * (w / l.pdf);
      }
      RILL_ENDIF;
    }
    RILL_ENDIF;
  }
  RILL_ENDIF;
}

PathResult PathIntegrator::trace(const Int2& pixel, const Ray& camera_ray) const {
  const Shading& sh = S_.shading;
  PathResult out;
  out.depth = as_float(Int(0x7f800000));
  Vertex v;
  v.ray = camera_ray;
  Int iter = 0;
  RILL_DO {
    RILL_IF(iter >= max_iterations) {
      v.done = true;
    }
    RILL_ELSE {
      Hit hit{Float(0.0f), Float2(0.0f), Int(-1)};
      if (S_.F.geometry) hit = S_.intersector.intersect(v.ray, nullptr);
      v.rays += 1;
      RILL_IF(hit.id < 0) {
        // A uniform environment of radiance `background`; nothing samples it but the BSDF,
        // so its light is taken whole.
        v.radiance += v.throughput * sh.background;
        v.done = true;
      }
      RILL_ELSE {
        const Surface s = sh.surface(v.ray, hit);
        const MaterialTable::Slots slots = sh.material(s);
        RILL_IF(v.depth == 0) {
          out.depth = hit.t;
          out.prim = hit.id;
          out.normal = s.ns;
        }
        RILL_ENDIF;
        if (lights_.areas()) {
          const Float3 le = lights_.emission(s);
          RILL_IF(max3(le) > 0.0f) {
            Float w = 1.0f;
            if (nee_) {
              // Light sampling could have found this point too (unless the BSDF sample came
              // from a delta lobe): the power heuristic, or nothing without MIS (NEE counts it).
              const Float p_light = lights_.pdf(hit.id, hit.t, v.ray.d);
              const Float w_mis = mis_ ? power_heuristic(v.bsdf_pdf, p_light) : Float(0.0f);
              w = select(v.delta, Float(1.0f), w_mis);
            }
            v.radiance += v.throughput * le * w;
          }
          RILL_ENDIF;
        }
        RILL_IF(v.depth >= sh.max_depth) {
          v.done = true;
        }
        RILL_ELSE {
          if (nee_) {
            RILL_IF(lights_.smooth(s)) {
              light_sample(v, s, slots, pixel);
            }
            RILL_ENDIF;
          }
          const Float4 u = random(pixel, v.depth, kPurposeBsdf);
          const BsdfSample b = S_.materials.bsdf_sample(s, Float3(u.x(), u.y(), u.z()), &slots);
          v.throughput = v.throughput * b.weight;
          v.bsdf_pdf = b.pdf;
          v.delta = b.delta;
          v.depth += 1;
          const Bool below = dot(b.wi, s.ngf) < 0.0f;
          v.ray = Ray{sh.offset_origin(s.P, select(below, -s.ngf, s.ngf)), b.wi, Float(kBig)};
          Float survive = 1.0f;
          RILL_IF(v.depth >= kRouletteDepth) {
            survive = min(max3(v.throughput), 0.95f);
          }
          RILL_ENDIF;
          RILL_IF(!(max3(v.throughput) > 0.0f) || u.w() >= survive) {
            v.done = true;
          }
          RILL_ELSE {
            v.throughput = v.throughput / survive;
          }
          RILL_ENDIF;
        }
        RILL_ENDIF;
      }
      RILL_ENDIF;
    }
    RILL_ENDIF;
    iter += 1;
  }
  RILL_UNTIL(v.done);
  out.radiance = v.radiance;
  out.rays = v.rays;
  return out;
}

}  // namespace rt
