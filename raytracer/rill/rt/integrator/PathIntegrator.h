// Unidirectional path tracing (docs/path-tracing.md), as DSL functions over the scene on the
// device: next-event estimation to point and area lights (kernel/LightSampler.h), multiple
// importance sampling of light and BSDF samples by the power heuristic, and Russian roulette
// from kRouletteDepth bounces on.
//
// A path is a work item (PathItem) that goes through two stages per vertex, as in pbrt-v4's
// wavefront integrator:
//   shade(path, hit)      what the ray found: the background, or a surface's emission (MIS
//                         weighted), then at a surface one light sample (a ShadowRay whose
//                         contribution is ready) and the BSDF's next ray
//   shadow_result(path, query, blocker)
//                         the shadow ray came back: its contribution counts if unblocked
// The megakernel runs both in one loop (megakernel/); a wavefront strategy runs each as a
// kernel over streams of these records. The float operations and their order are the same,
// so every strategy gives the same bits.
//
// The random numbers are Philox4x32-10 (rill/Random.h), keyed by the scene's seed and counted
// by (pixel x, pixel y, sample index, 4 * bounce + purpose), with the pixel in the whole
// image's coordinates: a pixel's path is the same whichever window, tile, thread, backend or
// pass computes it, so images are bitwise identical across all of them under strict.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/kernel/LightSampler.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// From this many bounces on, a path survives each further bounce with probability
// min(max component of its throughput, 0.95) and is weighted up by its inverse.
constexpr int kRouletteDepth = 3;

// A path between its stages (a work item): the ray to trace next, the radiance gathered, the
// throughput of what the ray brings back, the bounces taken, the density of the BSDF sample that
// made the ray and whether it came from a delta lobe (the camera ray counts as one: the light it
// finds is taken whole), whether the path has ended, and the rays it traced.
RILL_STRUCT(PathItem, (Ray, ray), (Float3, radiance), (Float3, throughput), (Int, depth),
            (Float, bsdf_pdf), (Bool, delta), (Bool, done), (Int, rays));

// Next-event estimation's shadow ray, and what it adds to the path's radiance if nothing
// blocks it (inactive: no light sample at this vertex).
RILL_STRUCT(ShadowQuery, (Ray, ray), (Float3, contribution), (Bool, active));

// The camera ray's first hit, for the AOV outputs.
struct FirstHit {
  Float depth = 0.0f;  // distance (+inf: none)
  Int prim = -1;
  Float3 normal{0.0f};
  Float3 albedo{0.0f};  // the shader's albedo (SurfaceShader::albedo); 0 for a miss
  // If set, the camera ray's hit is recorded only where this holds (a kernel of several
  // samples records its first sample's).
  const Bool* only_if = nullptr;
};

class PathIntegrator {
 public:
  // TracerOptions::mutation (scene.K) picks a broken variant, for the validation tests only.
  PathIntegrator(const DeviceScene& scene, const LightSampler& lights, const SceneOptions& options);
  // The sample's index within its pixel (a uniform per launch): the random counter's third
  // field. Where in the pixel the camera ray goes is the camera's sample offset.
  rill::Uniform<Int> sample_index{0, "sample_index"};
  rill::Uniform<Int> seed{0, "path_seed"};
  // Set while a kernel that runs several samples per launch is captured: its variable holding
  // the sample's index, used instead of sample_index.
  const Int* sample_var = nullptr;

  // A new path along the camera ray.
  PathItem start(const Ray& camera_ray) const;
  // The path's ray hit `hit` (id -1: nothing); pixel in image coordinates. Writes the first
  // hit's AOVs into `first` (if given) when this was the camera ray.
  ShadowQuery shade(PathItem& path, const Hit& hit, const Int2& pixel,
                    FirstHit* first = nullptr) const;
  // The active shadow ray of `query` was traced and found `blocker` (id -1: nothing, and the
  // light counts).
  void shadow_result(PathItem& path, const ShadowQuery& query, const Hit& blocker) const;
  bool shadow_rays() const { return nee_; }  // host: whether shade() makes any

 private:
  Float4 random(const Int2& pixel, const Int& depth, int purpose) const;
  ShadowQuery light_sample(const PathItem& path, const Surface& s,
                           const MaterialTable::Slots& slots, const Int2& pixel) const;
  void next_ray(PathItem& path, const Surface& s, const MaterialTable::Slots& slots,
                const Int2& pixel) const;

  const DeviceScene& S_;
  const LightSampler& lights_;
  const bool nee_, mis_;
  const PathMutation mutation_;
};

}  // namespace rt
