// The megakernel strategy (Sh style, after Moreno-Fortuny and McCool): one kernel instance
// per pixel. It makes the camera ray, then a RILL_DO ... RILL_UNTIL loop traces one ray per
// iteration and reacts to what it hit: a camera or secondary ray gets its shader's emitted
// light and then one shadow ray per light; when the lights are done, the local colour is
// weighted as in the thesis's eq. 5.1 and the path continues with the shader's reflected or
// transmitted ray (a second branch goes on a small ray stack), until the path ends, the
// stack is empty and the loop finishes.
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <set>
#include <string>

#include "rill/rt/Tracer.h"
#include "rill/rt/film/Film.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/kernel/PerBackend.h"

namespace rt {

class Megakernel {
 public:
  explicit Megakernel(DeviceScene& scene);
  ~Megakernel();
  const rill::Program& program() const { return program_; }
  // Compiled once per backend and accuracy.
  rill::Kernel& kernel(const std::string& backend, rill::Accuracy a);
  // Renders spp samples through the camera set in the scene's CameraRays; the samples meet
  // on `film`.
  void render(const RenderSettings& rs, Film& film, int width, int height, int depth, int spp,
              RenderResult& r);

 private:
  struct PathLoop;
  struct Aovs;
  struct Frame;  // a backend's output streams (PerBackend.h: buffers_for)
  rill::Program capture() const;
  // The loop body's steps, in order (Megakernel.cpp).
  Hit trace(PathLoop& L) const;
  void set_surface(Surface& to, const Surface& from) const;
  void camera_or_secondary_ray(PathLoop& L, const Hit& hit, Aovs& aovs) const;
  void shadow_ray_back(PathLoop& L, const Hit& hit) const;
  void next_ray(PathLoop& L, const MaterialTable::Slots* slots = nullptr) const;
  void pop_or_finish(PathLoop& L) const;

  DeviceScene& S_;
  // The loop's iteration limit; 0 skips all tracing (render()'s warm-up launch).
  rill::Uniform<Int> max_iter_{64, "max_iterations"};
  rill::Program program_;
  std::map<std::string, rill::Kernel> kernels_;
  std::map<std::string, std::unique_ptr<Frame>> frames_;  // per backend and accuracy
  std::set<std::pair<std::string, int64_t>> warmed_;      // kernels launched at a size before
};

}  // namespace rt
