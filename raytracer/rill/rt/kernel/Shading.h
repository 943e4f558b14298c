// Shading as DSL functions, shared by both strategies: the surface record at a hit, the
// light loop's pieces (a light's direction and shadow ray, the lights without shadows),
// the self-intersection offset of new rays, and eq. 5.1 with the next ray. What a material
// does is its shader's (MaterialTable.h); this file is what the tracer does around it.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/LightSampler.h"
#include "rill/rt/kernel/LightShape.h"
#include "rill/rt/kernel/MaterialTable.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/kernel/Records.h"
#include "rill/rt/kernel/Triangles.h"

namespace rt {

constexpr float kMinWeight = 1.0e-3f;  // secondary rays below this weight are not traced

// The lights, in Rill arrays: positions and colours, and where a scene has spot or
// directional lights or inverse-square falloff (Features::light_shapes), their shapes.
struct Lights {
  rill::Array<Float3> position{1, "light_pos"}, color{1, "light_col"};
  rill::Uniform<Int> count{0, "light_count"};
  LightShapes shapes{"light_shape", "light_axis"};
  void upload(const Scene& scene);
};

// A second ray waiting for the ray stack (refraction with reflection).
struct Branch {
  Ray ray{Float3(0.0f), Float3(0.0f), Float(0.0f)};
  Float weight = 0.0f;
  Bool wanted = false;
};

// What a path carries from surface to surface, as eq. 5.1 reads it: the colour gathered so
// far, the weight of what its next ray brings back (the product of the earlier coefficients)
// and the bounces taken.
struct PathSums {
  Float3 color;
  Float weight;
  Int depth;
};

// What shade() makes of a surface: the path with the surface's share of local light added,
// whether it goes on, with which ray (origin and direction; tmax is kBig), and, where the
// caller keeps a ray stack, the second branch.
struct Bounce {
  PathSums path;
  Bool go;
  Ray next;
  Branch second;
};

// A shadow ray towards a light, and whether it is traced at all (false when the light is
// behind the surface).
struct ShadowRay {
  Ray ray;
  Bool active;
};

// What keys an area light sample's random numbers besides its number: the pixel (image
// coordinates) and the surface's bounce.
struct LightKey {
  Int2 pixel;
  Int depth;
};

// The light loop (Whitted): light l of a surface, as its shader sees it and its shadow ray.
struct LoopLight {
  LightSample sample;
  ShadowRay shadow;
};

// Whitted's area lights (Features::area_lights; docs/scene-format.md, "emission" and
// "light_samples"). Emitting materials are lights too: the light loop's lights l in
// [point lights, point lights + light_samples) are each one point y drawn on the emitting
// triangles alone (LightSampler::sample_area: the power table restricted to them, then
// uniformly on the triangle), with Philox keyed by the pixel (image coordinates), the frame's
// sample index, the bounce depth and the sample number k (counter (x, y, sample, depth * 1024
// + k), key (seed, "Whit")): a pixel's samples are the same whichever backend, loop or window
// computes them, and the first k of a larger light_samples are the same points. Each acts as
// a point light at y of colour
//     Le |cos_l| / (pi d^2 p_area) / light_samples,
// where d is the distance from the shaded point, cos_l the cosine at y and p_area the
// point's density over area (the solid-angle density times |cos_l| / d^2). Point lights'
// colours are Whitted's non-radiometric 'irradiance at normal incidence without falloff'
// (a Lambertian phong surface of diffuse Kd gets Kd C cos); this weighting makes the
// sum over the samples Kd E / pi on such a surface, E the irradiance from the emitters: the
// path integrator's direct light for f = Kd / pi. So an emitter of area A and radiance Le
// facing a point from distance D far away lights it as a point light of colour
// Le A / (pi D^2) would. A point behind a one-sided emitter gives 0. The shadow ray starts
// off the surface and stops eps short of y, as a point light's does, and walks the grid (the
// light buffer is per point light). Two surfaces at one depth of one path (a ray stack's
// branches) see the same points.
class Shading {
 public:
  Shading(const Triangles& tris, const MaterialTable& materials, const Lights& lights,
          const LightSampler& area_lights, const TracerOptions& K, const Features& F)
      : tris_(tris),
        materials_(materials),
        lights_(lights),
        area_lights_(area_lights),
        K_(K),
        F_(F) {}

  rill::Uniform<Float> eps{1e-4f, "ray_epsilon"};
  rill::Uniform<Float3> background{glm::vec3(0.0f), "background"};
  rill::Uniform<Int> max_depth{5, "max_depth"};
  // Sets eps from the scene's size, and the background.
  void upload(const Scene& scene);
  // Sets eps for triangles within [lo, hi] (any: there are some): what upload() sets for a
  // scene of those bounds. A dynamic scene's frame sets it from its posed triangles, so that
  // it equals the scene baked at that time.
  void set_eps(bool any, const glm::vec3& lo, const glm::vec3& hi);
  // Area lights (F.area_lights): the samples per surface and the random sequence's seed.
  rill::Uniform<Int> light_samples{16, "light_samples"};
  rill::Uniform<Int> seed{0, "whitted_seed"};
  rill::Uniform<Int> sample_index{0, "whitted_sample"};  // the frame's sample: set per launch
  void area_samples(const SceneOptions& options);

  // The surface at hit (a hit of ray, id >= 0).
  Surface surface(const Ray& ray, const Hit& hit) const;
  // The surface's material parameters, read once for the calls below that take them.
  MaterialTable::Slots material(const Surface& s) const { return materials_.load(s); }
  // The shader's light without the light loop (emission, ambient).
  Float3 emitted(const Surface& s, const MaterialTable::Slots* slots = nullptr) const {
    return materials_.emitted(s, slots);
  }
  // The light l sends towards the viewer through the shader, shadows aside. With
  // F.light_shapes: a spot's colour times its cone factor (LightShape.h), a directional
  // light's from its fixed direction, either times 1 / d^2 under inverse-square falloff (d
  // the distance to the light); the same Phong terms as a point light's.
  Float3 light(const Int& l, const Surface& s, const MaterialTable::Slots* slots = nullptr) const;
  // Local light when there are no shadow rays: all lights, or the headlight. key: needed
  // with area lights.
  Float3 unshadowed_light(const Surface& s, const MaterialTable::Slots* slots = nullptr,
                          const LightKey* key = nullptr) const;
  // The shadow ray towards light l (a directional light's: along its direction without end).
  ShadowRay shadow_ray(const Int& l, const Surface& s) const;

  // The light loop: the point lights, then (F.area_lights) the area light samples.
  // Without area lights, these are exactly light() and shadow_ray() over the point lights.
  Int loop_lights() const;
  // Light l's share towards the viewer, shadows aside.
  // key: needed with area lights (null without).
  Float3 loop_light(const Int& l, const Surface& s, const LightKey* key,
                    const MaterialTable::Slots* slots = nullptr) const;
  ShadowRay loop_shadow_ray(const Int& l, const Surface& s, const LightKey* key) const;
  // The light buffer's light for loop light l: l for a point light, -1 for an area sample.
  Int buffer_light(const Int& l) const;
  // Area light sample k (0 <= k < light_samples) from s.
  LoopLight area_light(const Int& k, const Surface& s, const LightKey& key) const;
  // Eq. 5.1 and the next ray: adds the surface's share of local light to the path's colour,
  // then (if some material reflects) makes the reflected and refracted rays. With `branches`
  // (the caller has a ray stack), refraction with reflection makes a second branch, the
  // reflection; without, the path follows the refraction alone. `slots`: the material's
  // parameters if they were read already (MaterialTable::material).
  Bounce shade(const Surface& s, const Float3& local, const PathSums& path, bool branches,
               const MaterialTable::Slots* slots = nullptr) const;
  // A new ray's origin: p moved off the surface along n (the knob's fixed epsilon or
  // scale-aware offset).
  Float3 offset_origin(const Float3& p, const Float3& n) const;

 private:
  const Triangles& tris_;
  const MaterialTable& materials_;
  const Lights& lights_;
  const LightSampler& area_lights_;
  const TracerOptions& K_;
  const Features& F_;
};

}  // namespace rt
