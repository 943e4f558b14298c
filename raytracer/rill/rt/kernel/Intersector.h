// The closest-hit (and any-hit) search, as DSL functions over the grid (kernel/GridView.h)
// and the triangles (Triangles.h): the ray against the grid's box, then a 3D-DDA from voxel
// to voxel (Amanatides & Woo; thesis 5.1.2), a second one inside voxels with a subgrid, and
// the knob's triangle test on the triangles each voxel lists. The closest hit wins (ties:
// the smaller id, so the result does not depend on the order of the lists); a hit counts
// once its distance is within the current voxel.
//
// The megakernel calls intersect(); the multipass strategy calls the steps (ray_box,
// dda_init, leave_voxel, ...) from its traverser and intersector kernels, so both compute
// the same bits.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/BvhView.h"
#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/GridView.h"
#include "rill/rt/kernel/LightBufferView.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/kernel/Records.h"
#include "rill/rt/kernel/Triangles.h"

namespace rt {

// What a 3D-DDA step needs of a ray's direction, computed once per ray (not per step): the
// flat axes, the reciprocal, the step sign and the distance between voxel boundaries.
struct RaySteps {
  Float3 d{0.0f};
  Bool3 flat{false};
  Float3 inv{0.0f};
  Int3 step{0};
  Float3 tdl{0.0f};
};

// Where a 3D-DDA is: the voxel, the distances to its exit planes (Traversal::Recompute: the
// origin relative to the grid's corner), the steps taken, and whether the walk is over.
struct DdaState {
  Int3 vox{0};
  Float3 tmx{0.0f};
  Int steps = 0;
  Bool done = false;
};

// The part of a ray inside the grid's box: whether it enters, and the parameter range
// [t_enter, t_exit] (t_exit at most the ray's tmax).
struct BoxSpan {
  Bool inside;
  Float t_enter, t_exit;
};

class Intersector {
 public:
  Intersector(const GridView& grid, const BvhView& bvh, const LightBufferView& light_buffer,
              const rill::Array<Float3>& light_positions, const Triangles& tris,
              const TracerOptions& K, const Features& F)
      : grid_(grid),
        bvh_(bvh),
        lb_(light_buffer),
        light_pos_(light_positions),
        tris_(tris),
        K_(K),
        F_(F) {}

  // The whole search: the grid over the static triangles, then the BVH over the moving ones
  // (F.dynamic), each keeping the closest hit by test_triangle's rule, so the result is the
  // closest over all triangles whichever holds them (and whichever is searched first: the
  // multipass strategy walks the BVH first). With *any_hit true, the first hit
  // before ray.tmax ends it (shadow rays); any_hit null: closest hit only. No hit: id -1,
  // t = ray.tmax. A shadow ray towards light *light (any_hit true, light given) tests its
  // light buffer cell's list instead of walking the grid where the scene has a light
  // buffer and the cell a list (with area lights, *light -1: none, an area sample's).
  Hit intersect(const Ray& ray, const Bool* any_hit, const Int* light = nullptr) const;

  // Whether the light buffer settles a shadow ray towards light `light`: its cell's
  // entries, nearest first, until one blocks the ray (best.id >= 0) or the next lies
  // farther from the light than the ray's origin. False where the cell sends it to the grid.
  Bool occluders(const Ray& ray, const Int& light, Hit& best) const;
  bool has_light_buffer() const { return lb_.enabled(); }

  // The grid's part of intersect(): box, 3D-DDA, the voxels' lists; from the hit in best.
  // With packets on (set_packets), a lane group whose rays step the same way on every axis
  // walks together (walk_grid_together); the others walk alone.
  void walk_grid(const Ray& ray, const Bool& any_hit, Hit& best) const;
  // The lane group's shared walk (GroupWalk.cpp), from each ray's 3D-DDA state st: the same
  // hits as each ray walking alone.
  void walk_grid_together(const Float3& o, const RaySteps& r, const Float& t_exit,
                          const Bool& any_hit, DdaState& st, Hit& best) const;
  // One ray's 3D-DDA from st, voxel by voxel (the walk without packets).
  void walk_alone(const Float3& o, const Float3& d, const RaySteps& r, const Float& t_exit,
                  const Bool& any_hit, DdaState& st, Hit& best) const;
  // Whether the programs captured from now on walk lane groups together (Options.h,
  // Packets): set per program by the strategy that captures it, off by default.
  void set_packets(bool on) { packets_ = on; }
  bool packets() const { return packets_; }

  // ---- the steps --------------------------------------------------------------------------
  // The ray against the grid's box.
  BoxSpan ray_box(const Ray& ray) const;
  // 3D-DDA initialization (thesis 5.1.2): the voxel at t_enter and the distances to the
  // next voxel boundary on each axis.
  DdaState dda_init(const Float3& o, const Float3& d, const Float& t_enter) const;
  RaySteps ray_steps(const Float3& d) const;
  // The knob's triangle test against the triangle of element-list entry ref; keeps the
  // closest hit in best (ties: the smaller id).
  void test_triangle(const Float3& o, const Float3& d, const Int& ref, Hit& best) const;
  // The same against triangle (primitive id) tri.
  void test_primitive(const Float3& o, const Float3& d, const Int& tri, Hit& best) const;
  // The moving triangles' BVH (Bvh.h), walked without a stack; with any_hit true the first
  // hit ends it. Generated only for scenes with animated objects (F.dynamic).
  void walk_bvh(const Float3& o, const RaySteps& r, const Bool& any_hit, Hit& best) const;
  // The triangles of one element-list range (base, count) in order; with any_hit true the
  // first hit ends the list.
  void test_list(const Float3& o, const Float3& d, const Int2& range, const Bool& any_hit,
                 Hit& best) const;
  // The triangles of a voxel with a subgrid (entry (base, -m), Grid.h): a 3D-DDA over its
  // sub-voxels, within the voxel.
  void walk_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit, const Bool& any_hit,
                    const Int2& entry, const DdaState& at, Hit& best) const;
  // After a voxel's triangles: done when the best hit lies within the voxel (or any hit,
  // for shadow rays), the ray ends inside it, it leaves the grid or the steps run out;
  // otherwise steps to the next voxel, or, from an empty voxel far from any triangle, jumps
  // over the empty voxels around it. entry is the voxel's entry (GridView::voxel_range;
  // (0, 0) where the caller has not loaded it: a plain step).
  void leave_voxel(const RaySteps& r, const Float& t_exit, const Hit& best, const Bool& any_hit,
                   const Int2& entry, DdaState& st) const;
  const GridView& grid() const { return grid_; }

 private:
  Bool3 flat_axes(const Float3& d) const;
  Float3 inverse_dir(const Float3& d) const;
  Int3 step_dir(const Float3& d) const;
  Bool3 nearest_axis(const Float3& t) const;
  // A 3D-DDA over the cells of size `cell` from lo (the last one `last`), from the point at t:
  // no steps taken.
  DdaState dda_start(const Float3& o, const Float3& d, const Float& t, const Float3& lo,
                     const Float3& cell, const Float3& last) const;
  Float3 voxel_exits(const RaySteps& r, const Int3& vox, const Float3& tmx) const;

  const GridView& grid_;
  const BvhView& bvh_;
  const LightBufferView& lb_;
  const rill::Array<Float3>& light_pos_;
  const Triangles& tris_;
  const TracerOptions& K_;
  const Features& F_;
  bool packets_ = false;
};

}  // namespace rt
