// The path tracer's own rays after a given number of scatterings, as a render traced them
// (RenderSettings::bounce_rays): for benchmarks that trace exactly those rays with another
// intersector (rill-bench-trace --sections bounce, against Embree) and for tests. Plain data,
// below the strategies that fill it in.
//
// Only the wavefront strategy fills it (wavefront/Wavefront.h): its paths wait in streams
// between its stages, so the rays are read back from the path records after the stage that
// made them, by the very operations that render the image (the megakernel keeps its paths in
// registers; Tracer::render refuses the request for any other strategy). Bounce k is the ray
// that leaves the k-th surface hit of a camera path, made by PathIntegrator::next_ray from
// the BSDF's sample there: bounce 2 is the ray after two scatterings, the one the path's third
// intersection traces. Bounce 0 is the camera ray. A path that ended before it (a miss, an
// absorbing or emitting-only surface, max_depth, Russian roulette, which starts at
// kRouletteDepth) has no such ray, so there are at most width x height x spp of them.
// Next-event estimation's shadow rays are not included.
#pragma once

#include <rill/rill.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rt {

struct BounceRays {
  // Asked for: the number of scatterings before the rays (0: the camera rays).
  int bounce = 2;
  // Filled in by the render (cleared first): one entry per path still going after `bounce`
  // scatterings, sample after sample, and within a sample in the order of the rendered
  // pixels (row-major over the window). The origin is the hit point offset off the surface
  // as the integrator offsets it (Shading::offset_origin) and the direction is unit length;
  // the rays are unbounded, as the integrator traces them.
  std::vector<glm::vec3> origins, directions;
  std::vector<int32_t> pixels;   // y * window width + x
  std::vector<int32_t> samples;  // the sample index within the pixel

  size_t size() const { return origins.size(); }
  void clear() {
    origins.clear();
    directions.clear();
    pixels.clear();
    samples.clear();
  }
};

}  // namespace rt
