// The thesis's multipass strategy (sections 5.4-5.6): a sequence of small kernels over
// per-pixel state streams instead of one kernel with a loop. Multipass.cpp describes the
// passes and runs them; TracePasses.cpp and ShadePasses.cpp build them; States.h holds the
// state values and records. Built from the same DSL building blocks (kernel/) as the megakernel, it
// gives the same bits. Refraction is left to the megakernel, as in the thesis (5.2.2).
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <string>

#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/strategy/RenderStrategy.h"

namespace rt {

class Multipass final : public RenderStrategy {
 public:
  // Captures the passes' programs; throws std::runtime_error for a scene with refraction or
  // under the path integrator.
  explicit Multipass(DeviceScene& scene);
  ~Multipass() override;
  void render(const Frame& frame, RenderResult& r) override;

 private:
  struct Kernels {
    rill::Kernel raygen, setup, traverse, intersect, finish, surface, shadow_gen, shadow_acc,
        combine;
  };
  struct Buffers;
  // The passes' programs (TracePasses.cpp, ShadePasses.cpp).
  rill::Program capture_raygen() const;
  rill::Program capture_setup() const;
  rill::Program capture_traverse() const;
  rill::Program capture_intersect() const;
  rill::Program capture_finish() const;
  rill::Program capture_surface() const;
  rill::Program capture_shadow_gen() const;
  rill::Program capture_shadow_acc() const;
  rill::Program capture_combine() const;
  // Walks a subgrid whose entry (base, -m) is the cursor (c, end); then the cursor is empty.
  void walk_pending_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit,
                            const Bool& any_hit, const DdaState& at, Int& c, Int& end,
                            Hit& best) const;
  Kernels& kernels(const std::string& backend, rill::Accuracy a);

  DeviceScene& S_;
  rill::Uniform<Int> light_{0, "light_index"};
  // 1 while tracing shadow rays (any hit ends the search), 0 for closest hits.
  rill::Uniform<Int> any_hit_{0, "any_hit"};
  rill::Program raygen_, setup_, traverse_, intersect_, finish_, surface_, shadow_gen_, shadow_acc_,
      combine_;
  std::map<std::string, Kernels> compiled_;
  // Per backend and accuracy, the state streams of its last frame, reused at the same size.
  std::map<std::string, std::unique_ptr<Buffers>> buffers_;
};

}  // namespace rt
