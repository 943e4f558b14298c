// Unidirectional path tracing (docs/path-tracing.md), as DSL functions over the scene on the
// device: the radiance one path brings back through a pixel, with next-event estimation to
// point and area lights (LightSampler.h), multiple importance sampling of light and BSDF
// samples by the power heuristic, and Russian roulette from kRouletteDepth bounces on.
//
// The random numbers are Philox4x32-10 (rill/Random.h), keyed by the scene's seed and counted
// by (pixel x, pixel y, sample index, 4 * bounce + purpose), with the pixel in the whole
// image's coordinates: a pixel's path is the same whichever window, tile, thread, backend or
// pass computes it, so images are bitwise identical across all of them under strict.
//
// A strategy runs trace() for each pixel and sample: the megakernel in one kernel
// (megakernel/), a wavefront strategy stage by stage through the same functions.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/kernel/LightSampler.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// From this many bounces on, a path survives each further bounce with probability
// min(max component of its throughput, 0.95) and is weighted up by its inverse.
constexpr int kRouletteDepth = 3;

// What one path gives: its radiance, the rays it traced, and the first hit's AOVs.
struct PathResult {
  Float3 radiance{0.0f};
  Int rays = 0;
  Float depth = 0.0f;  // distance to the first hit (+inf: none)
  Int prim = -1;       // the first hit's triangle
  Float3 normal{0.0f};
};

class PathIntegrator {
 public:
  PathIntegrator(const DeviceScene& scene, const LightSampler& lights, const SceneOptions& options);
  // The sample's index within its pixel (a uniform per launch): the random counter's third
  // field. The pixel position within the pixel is the camera's sample offset.
  rill::Uniform<Int> sample_index{0, "sample_index"};
  rill::Uniform<Int> seed{0, "path_seed"};
  // Iterations of the path loop at most (a backstop: max_depth + 2 suffices; 0 traces nothing).
  rill::Uniform<Int> max_iterations{0, "path_max_iterations"};

  // The path through image pixel `pixel` starting with camera ray `ray`.
  PathResult trace(const Int2& pixel, const Ray& ray) const;

 private:
  struct Vertex;  // the loop's state
  Float4 random(const Int2& pixel, const Int& depth, int purpose) const;
  // Next-event estimation at surface s: one light sample, its shadow ray, weighted.
  void light_sample(Vertex& v, const Surface& s, const MaterialTable::Slots& slots,
                    const Int2& pixel) const;

  const DeviceScene& S_;
  const LightSampler& lights_;
  const bool nee_, mis_;
};

}  // namespace rt
