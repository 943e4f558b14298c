// The tracer's side of shading (Shading.h).
#include "rill/rt/kernel/Shading.h"

#include <stdexcept>

#include "rill/Random.h"
#include "rill/rt/kernel/DeviceArrays.h"
#include "rill/rt/kernel/Sampling.h"

namespace rt {

using namespace rill;

void Lights::upload(const Scene& scene) {
  std::vector<glm::vec3> lp, lc;
  for (const Light& l : scene.lights) {
    lp.push_back(l.position);
    lc.push_back(l.color);
  }
  upload_padded(position, lp);
  upload_padded(color, lc);
  count.set(static_cast<int32_t>(scene.lights.size()));
  if (any_light_shaped(scene)) shapes.upload(scene.lights);
}

void Shading::upload(const Scene& scene) {
  glm::vec3 lo, hi;
  const bool any = scene_bounds(scene, lo, hi);
  set_eps(any, lo, hi);
  background.set(scene.background);
}

void Shading::set_eps(bool any, const glm::vec3& lo, const glm::vec3& hi) {
  // Secondary rays start a little off the surface: 2e-5 of the scene's size (and at least
  // a few ulps of its coordinates).
  float e = 1e-4f;
  if (any) {
    double diag = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
    double mag = std::max(glm::length(glm::dvec3(lo)), glm::length(glm::dvec3(hi)));
    e = static_cast<float>(std::max(2e-5 * diag, 1e-6 * mag));
    if (!(e > 0)) e = 1e-4f;
  }
  eps.set(e);
}

// Wachter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
// Gems, ch. 6): move each coordinate a number of ulps proportional to the normal (integer
// steps on the float's bits, so the offset scales with the coordinate's magnitude: it
// suffices at 1e4 as at 1e-4); where a coordinate is near zero and its ulps are tiny, a
// fixed step instead. Two changes from the published constants, both measured (HardCases
// tests, docs/accuracy.md): the point comes from the barycentrics (surface()), so its error
// is about 2 ulps per coordinate and kIntScale = 8 ulps suffices where the paper's 256
// (for points from o + t d after instance transforms) moved rays 0.25 units at 1e4 and lost
// contact shadows; and the near-zero step is the scene-relative eps instead of 2^-16
// absolute, which was 15% of a scene scaled to 1e-3 units.
Float3 Shading::offset_origin(const Float3& p, const Float3& n) const {
  if (K_.offset == SelfIntersection::Epsilon) return p + n * eps;
  constexpr float kOrigin = 1.0f / 32.0f, kIntScale = 8.0f;
  Int3 of = to_int(kIntScale * n);
  Float3 pi = as_float(as_int(p) + select(p < 0.0f, -of, of));
  return select(abs(p) < kOrigin, p + n * eps, pi);
}

Surface Shading::surface(const Ray& ray, const Hit& hit) const {
  const Float3& rd = ray.d;
  const Int& hid = hit.id;
  const Float hu = hit.uv.x(), hv = hit.uv.y();
  // Every field is computed into its own value and the record built at the end: a record
  // default-constructed and then filled would assign each field twice (on simd, twice per
  // lane under the branch's mask).
  Float3 P = K_.offset == SelfIntersection::Scaled
                 // On the triangle, from the barycentrics: the error does not grow with the
                 // distance.
                 ? Float3(tris_.v0[hid] + hu * tris_.e1[hid] + hv * tris_.e2[hid])
                 : Float3(ray.o + hit.t * rd);
  Float3 ng = tris_.ng[hid];
  Float3 ns = ng;
  if (F_.vertex_normals) {
    Float w = 1.0f - hu - hv;
    Float3 nn = tris_.n0[hid] * w + tris_.n1[hid] * hu + tris_.n2[hid] * hv;
    Float nl = length(nn);
    ns = select(nl > 0.0f, nn / select(nl > 0.0f, nl, 1.0f), ng);
    ng = select(dot(ng, ns) < 0.0f, -ng, ng);  // the vertex normals tell outside
  }
  Bool entering = dot(ng, rd) < 0.0f;
  Float3 nf = select(entering, ns, -ns);
  Float3 ngf = select(entering, ng, -ng);
  Float3 V = -rd;
  Int material = tris_.material[hid];
  Float3 vertex_color(1.0f);
  if (F_.vertex_colors) {
    Float w = 1.0f - hu - hv;
    vertex_color = tris_.c0[hid] * w + tris_.c1[hid] * hu + tris_.c2[hid] * hv;
  }
  Float2 uv(0.0f);
  if (F_.texcoords) {
    Float w = 1.0f - hu - hv;
    uv = tris_.uv[3 * hid] * w + tris_.uv[3 * hid + 1] * hu + tris_.uv[3 * hid + 2] * hv;
  }
  return Surface{P, ns, nf, ngf, V, uv, entering, vertex_color, material};
}

Float3 Shading::light(const Int& l, const Surface& s, const MaterialTable::Slots* slots) const {
  if (!F_.light_shapes) {
    Float3 L = normalize(lights_.position[l] - s.P);
    return materials_.reflected(s, LightSample{L, lights_.color[l], false}, slots);
  }
  const LightShapes& shapes = lights_.shapes;
  const Float3 to = lights_.position[l] - s.P;
  const Bool directional = shapes.directional(l);
  const Float3 L = select(directional, -shapes.axis[l], normalize(to));
  const Float d2 = dot(to, to);
  const Float falloff = select(shapes.inverse_square(l) && d2 > 0.0f,
                               1.0f / select(d2 > 0.0f, d2, Float(1.0f)), Float(1.0f));
  const Float3 color = lights_.color[l] * (shapes.cone(l, L) * falloff);
  return materials_.reflected(s, LightSample{L, color, false}, slots);
}

void Shading::area_samples(const SceneOptions& options) {
  light_samples.set(options.light_samples);
  seed.set(static_cast<int32_t>(options.seed));
}

Float3 Shading::unshadowed_light(const Surface& s, const MaterialTable::Slots* slots,
                                 const LightKey* key) const {
  Float3 sum(0.0f);
  if (F_.area_lights) {
    RILL_FOR(Int l = 0, l < loop_lights(), l += 1) {
      sum += loop_light(l, s, key, slots);
    }
    RILL_ENDFOR;
  } else if (F_.lights) {
    RILL_FOR(Int l = 0, l < lights_.count, l += 1) {
      sum += light(l, s, slots);
    }
    RILL_ENDFOR;
  } else {
    sum = materials_.reflected(s, LightSample{s.V, Float3(1.0f), true}, slots);
  }
  return sum;
}

ShadowRay Shading::shadow_ray(const Int& l, const Surface& s) const {
  Float3 so = offset_origin(s.P, s.ngf);
  Float3 L = lights_.position[l] - so;
  Float dist = length(L);
  Float3 rd = L / dist;
  if (F_.light_shapes) {  // a directional light's: towards it, as far as the scene goes
    const Bool directional = lights_.shapes.directional(l);
    rd = select(directional, -lights_.shapes.axis[l], rd);
    dist = select(directional, Float(kBig), dist);
  }
  Bool active = dist > 0.0f && dot(s.nf, rd) > 0.0f;
  // Stop short of the light by the same offset: a light on a surface (as on an area
  // light's quad) is not shadowed by that surface.
  return ShadowRay{Ray{so, rd, dist - eps}, active};
}

namespace {
constexpr int32_t kWhittedKey = 0x57686974;  // "Whit": the key's second word

const LightKey& need_key(const LightKey* key) {
  if (key == nullptr) throw std::logic_error("Shading: area lights need a LightKey");
  return *key;
}
}  // namespace

Int Shading::loop_lights() const {
  if (!F_.area_lights) return lights_.count;
  return lights_.count + light_samples;
}

Int Shading::buffer_light(const Int& l) const {
  if (!F_.area_lights) return l;
  return select(l < lights_.count, l, Int(-1));
}

LoopLight Shading::area_light(const Int& k, const Surface& s, const LightKey& key) const {
  const Int4 counter(key.pixel.x(), key.pixel.y(), sample_index, key.depth * kMaxLightSamples + k);
  const Float4 u = unit_float(philox4x32(counter, Int2(seed, Int(kWhittedKey))));
  const AreaPoint a = area_lights_.sample_area(Float3(u.x(), u.y(), u.z()));
  // The light's direction and colour from the surface point, as a point light's.
  const Float3 to = a.y - s.P;
  const Float d2 = dot(to, to);
  const Float d = sqrt(d2);
  const Float3 L = to / select(d > 0.0f, d, Float(1.0f));
  const Float cos_l = dot(a.n, L);  // < 0: the point sees the front side
  const Bool lit = cos_l < 0.0f || (a.two_sided && cos_l > 0.0f);
  // Le |cos_l| / (pi d^2 p_area) / light_samples (Shading.h's top says why).
  const Float denom = kPi * d2 * a.p_area * to_float(light_samples);
  const Bool shines = lit && denom > 0.0f;
  const Float3 color =
      select(shines, a.le * (abs(cos_l) / select(denom > 0.0f, denom, Float(1.0f))), Float3(0.0f));
  // The shadow ray as towards a point light: off the surface, stopping eps short of y.
  const Float3 so = offset_origin(s.P, s.ngf);
  const Float3 sl = a.y - so;
  const Float dist = length(sl);
  const Float3 rd = sl / select(dist > 0.0f, dist, Float(1.0f));
  const Bool active = shines && dist > 0.0f && dot(s.nf, rd) > 0.0f;
  return LoopLight{LightSample{L, color, false}, ShadowRay{Ray{so, rd, dist - eps}, active}};
}

Float3 Shading::loop_light(const Int& l, const Surface& s, const LightKey* key_or_null,
                           const MaterialTable::Slots* slots) const {
  if (!F_.area_lights) return light(l, s, slots);
  const LightKey& key = need_key(key_or_null);
  Float3 out(0.0f);
  if (F_.lights) {
    RILL_IF(l < lights_.count) {
      out = light(l, s, slots);
    }
    RILL_ELSE {
      out = materials_.reflected(s, area_light(l - lights_.count, s, key).sample, slots);
    }
    RILL_ENDIF;
  } else {
    out = materials_.reflected(s, area_light(l, s, key).sample, slots);
  }
  return out;
}

ShadowRay Shading::loop_shadow_ray(const Int& l, const Surface& s,
                                   const LightKey* key_or_null) const {
  if (!F_.area_lights) return shadow_ray(l, s);
  const LightKey& key = need_key(key_or_null);
  if (!F_.lights) return area_light(l, s, key).shadow;
  ShadowRay out{Ray{Float3(0.0f), Float3(0.0f, 0.0f, 1.0f), Float(0.0f)}, Bool(false)};
  RILL_IF(l < lights_.count) {
    out = shadow_ray(l, s);
  }
  RILL_ELSE {
    out = area_light(l - lights_.count, s, key).shadow;
  }
  RILL_ENDIF;
  return out;
}

Bounce Shading::shade(const Surface& s, const Float3& local, const PathSums& path, bool branches,
                      const MaterialTable::Slots* slots) const {
  const Scatter sc = materials_.scatter(s, path.weight, slots);
  // Eq. 5.1: this surface contributes M_j (1 - r_j) times the product of the earlier
  // coefficients (the shader's local_weight).
  Bounce b{PathSums{path.color + sc.local_weight * local, path.weight, path.depth}, Bool(false),
           Ray{Float3(0.0f), Float3(0.0f), Float(kBig)}, Branch{}};
  if (!F_.reflection) return b;
  RILL_IF(path.depth < max_depth) {
    Float wr = sc.reflect_weight;
    Float wt = 0.0f;
    Float3 tdir(0.0f);
    if (F_.refraction) {
      wt = sc.transmit_weight;
      tdir = sc.transmit_dir;
    }
    Bool go_r = wr > kMinWeight;
    Bool go_t = wt > kMinWeight;
    if (branches) {  // both: the reflection is the second branch
      b.second.wanted = go_r && go_t;
      b.second.ray.o = offset_origin(s.P, s.ngf);
      b.second.ray.d = sc.reflect_dir;
      b.second.weight = wr;
    }
    RILL_IF(go_t) {
      b.next.o = offset_origin(s.P, -s.ngf);
      b.next.d = tdir;
      b.path.weight = wt;
      b.go = true;
    }
    RILL_ELSE_IF(go_r) {
      b.next.o = offset_origin(s.P, s.ngf);
      b.next.d = sc.reflect_dir;
      b.path.weight = wr;
      b.go = true;
    }
    RILL_ENDIF;
    b.path.depth += 1;
  }
  RILL_ENDIF;
  return b;
}

}  // namespace rt
