// The BVH (Bvh.h) as the kernels see it: its nodes and triangle list in Rill arrays, and its
// node count in a uniform, so a new tree each frame is an upload, never a recompile.
#pragma once

#include <rill/rill.h>

#include "rill/rt/accel/Bvh.h"

namespace rt {

struct BvhView {
  rill::Array<rill::Float3> lo{1, "bvh_lo"}, hi{1, "bvh_hi"};
  // (skip, first, count, 0): Bvh.h's BvhNode.
  rill::Array<rill::Int4> link{1, "bvh_link"};
  rill::Array<rill::Int> tris{1, "bvh_tris"};
  rill::Uniform<rill::Int> nodes{0, "bvh_nodes"};

  void upload(const Bvh& bvh);
};

}  // namespace rt
