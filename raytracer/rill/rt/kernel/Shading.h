// Shading as DSL functions, shared by both strategies: the surface record at a hit, the
// light loop's pieces (a light's direction and shadow ray, the lights without shadows),
// the self-intersection offset of new rays, and eq. 5.1 with the next ray. What a material
// does is its shader's (MaterialTable.h); this file is what the tracer does around it.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/MaterialTable.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/kernel/Records.h"
#include "rill/rt/kernel/Triangles.h"

namespace rt {

constexpr float kMinWeight = 1.0e-3f;  // secondary rays below this weight are not traced

// The point lights, in Rill arrays.
struct Lights {
  rill::Array<Float3> position{1, "light_pos"}, color{1, "light_col"};
  rill::Uniform<Int> count{0, "light_count"};
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

class Shading {
 public:
  Shading(const Triangles& tris, const MaterialTable& materials, const Lights& lights,
          const TracerOptions& K, const Features& F)
      : tris_(tris), materials_(materials), lights_(lights), K_(K), F_(F) {}

  rill::Uniform<Float> eps{1e-4f, "ray_epsilon"};
  rill::Uniform<Float3> background{glm::vec3(0.0f), "background"};
  rill::Uniform<Int> max_depth{5, "max_depth"};
  // Sets eps from the scene's size, and the background.
  void upload(const Scene& scene);

  // The surface at hit (a hit of ray, id >= 0).
  Surface surface(const Ray& ray, const Hit& hit) const;
  // The surface's material parameters, read once for the calls below that take them.
  MaterialTable::Slots material(const Surface& s) const { return materials_.load(s); }
  // The shader's light without the light loop (emission, ambient).
  Float3 emitted(const Surface& s, const MaterialTable::Slots* slots = nullptr) const {
    return materials_.emitted(s, slots);
  }
  // The light l sends towards the viewer through the shader, shadows aside.
  Float3 light(const Int& l, const Surface& s, const MaterialTable::Slots* slots = nullptr) const;
  // Local light when there are no shadow rays: all lights, or the headlight.
  Float3 unshadowed_light(const Surface& s, const MaterialTable::Slots* slots = nullptr) const;
  // The shadow ray towards light l.
  ShadowRay shadow_ray(const Int& l, const Surface& s) const;
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
  const TracerOptions& K_;
  const Features& F_;
};

}  // namespace rt
