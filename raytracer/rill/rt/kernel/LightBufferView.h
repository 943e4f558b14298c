// The light buffer (LightBuffer.h) as the kernels see it: its cells and entries in Rill
// arrays, its resolution in a uniform.
#pragma once

#include <rill/rill.h>

#include "rill/rt/accel/LightBuffer.h"

namespace rt {

struct LightBufferView {
  rill::Array<rill::Int2> cells{1, "lb_cells"};
  rill::Array<rill::Int> tris{1, "lb_tris"};
  rill::Array<rill::Float> near{1, "lb_near"};
  rill::Uniform<rill::Int> res{1, "lb_res"};
  rill::Uniform<rill::Float> reach{0.0f, "lb_reach"};  // LightBuffer::reach
  // Host: whether there is one (the shadow rays' code uses it only then), and what it holds.
  LightBufferStats stats;
  bool enabled() const { return stats.res > 0; }

  void upload(const LightBuffer& lb);
  // The cell of a shadow ray towards light `light` whose origin is q away from the light:
  // (start, count) into tris and near, or (start, -1): walk the grid.
  rill::Int2 cell(const rill::Int& light, const rill::Float3& q) const;
};

}  // namespace rt
