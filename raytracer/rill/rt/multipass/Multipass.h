// The thesis's multipass strategy (sections 5.4-5.6): a sequence of small kernels over
// per-pixel state streams instead of one kernel with a loop (Multipass.cpp describes the
// passes). Built from the same DSL building blocks (kernel/) as the megakernel, it gives
// the same bits. Refraction is left to the megakernel, as in the thesis (5.2.2).
#pragma once

#include <rill/rill.h>

#include <map>
#include <string>

#include "rill/rt/Tracer.h"
#include "rill/rt/kernel/DeviceScene.h"

namespace rt {

class Multipass {
 public:
  // Captures the passes' programs; throws std::runtime_error for a scene with refraction.
  explicit Multipass(DeviceScene& scene);
  // Renders spp samples through the camera set in the scene's CameraRays.
  RenderResult render(const RenderSettings& rs, int width, int height, int depth, int spp);

 private:
  struct Kernels {
    rill::Kernel raygen, setup, traverse, intersect, finish, surface, shadow_gen, shadow_acc,
        combine;
  };
  struct Buffers;
  void capture();
  Kernels& kernels(const std::string& backend, rill::Accuracy a);

  DeviceScene& S_;
  rill::Uniform<Int> light_{0, "light_index"};
  // 1 while tracing shadow rays (any hit ends the search), 0 for closest hits.
  rill::Uniform<Int> any_hit_{0, "any_hit"};
  rill::Program raygen_, setup_, traverse_, intersect_, finish_, surface_, shadow_gen_, shadow_acc_,
      combine_;
  std::map<std::string, Kernels> compiled_;
};

}  // namespace rt
