// The wavefront strategy (after Laine, Karras and Aila's "Megakernels considered harmful" and
// pbrt-v4's wavefront integrator): the path integrator's stages (integrator/PathIntegrator.h)
// as one kernel each over the frame's pixels, the paths waiting in streams of records
// between them (Records.h). Per sample:
//
//   camera     (Camera.cpp)     a path per pixel along the camera ray; a pixel whose ray
//                               cannot reach the scene (CameraRays::may_see_scene) gets the
//                               miss's shading at once and its path is done
//   then per bounce, while a path is not done (at most max depth + 2 bounces, the
//   megakernel's iteration limit):
//   intersect  (Intersect.cpp)  the closest hit of each path's ray
//   shade      (Shade.cpp)      PathIntegrator::shade: emission, the light sample's shadow
//                               query, the next ray or the end; the camera ray's AOVs
//   shadow     (Shadow.cpp)     the active shadow queries traced for any hit, then
//                               PathIntegrator::shadow_result (not launched when the
//                               integrator makes no shadow rays)
//
// and the paths' radiance is the sample's colour, handed to the film (no kernel of its own).
// With RenderSettings::bounce_rays, the rays of the paths not done are read back after the
// stage that made the bounce asked for (BounceRays.cpp; render/BounceRays.h).
// Each launch is masked (rill::where) to the elements it works on: intersect and shade to the
// paths not done, shadow to the active queries. A pixel's operations are the megakernel's
// (capture_path), in the same order, so the image has its bits on every backend under
// strict. Whitted's tracer is not a sequence of these stages: the constructor refuses it.
//
// Compaction and sorting of the work items (queues instead of masks) are left for later:
// each stage reads and writes its records by name, so a queue can take the place of the
// per-pixel streams without changing the stages' bodies.
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "rill/rt/integrator/PathIntegrator.h"
#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/strategy/RenderStrategy.h"

namespace rt {

class Wavefront final : public RenderStrategy {
 public:
  // Throws std::runtime_error unless the scene's integrator is the path integrator.
  explicit Wavefront(DeviceScene& scene);
  ~Wavefront() override;
  void render(const Frame& frame, RenderResult& r) override;

 private:
  struct Programs {
    rill::Program camera, intersect, shade, shadow;  // intersect, shadow: invalid if unused
  };
  struct Kernels {
    rill::Kernel camera, intersect, shade, shadow;
  };
  struct Buffers;
  // The stages' programs (one file each), with the AOV outputs whatever a render reads back:
  // one set of kernels for every output (megakernel/Megakernel.h says why).
  rill::Program capture_camera() const;
  rill::Program capture_intersect() const;
  rill::Program capture_shade() const;
  rill::Program capture_shadow() const;
  const Programs& programs();
  Kernels& kernels(const std::string& backend, rill::Accuracy a);

  DeviceScene& S_;
  std::unique_ptr<PathIntegrator> path_;
  std::optional<Programs> programs_;
  std::map<std::string, Kernels> kernels_;
  std::map<std::string, std::unique_ptr<Buffers>> buffers_;  // per backend and accuracy
  std::set<std::pair<std::string, int64_t>> warmed_;         // kernels launched at a size before
};

}  // namespace rt
