// The lane group's shared grid walk (Intersector::walk_grid_together; docs/raytracer.md,
// "Coherent traversal"): the rays of a lane group that step the same way on every axis
// visit the union of their voxels one voxel at a time, and every ray tests each visited
// voxel's triangles, so the group loads one voxel entry and one triangle list per step
// instead of one per ray, and no lane idles while another finishes a longer list. On simd it
// measured slower than the lanes walking side by side, each its own voxel (they already share
// a voxel's loads when they are in it, and the shared walk visits different voxels one after
// the other: docs/benchmarks/2026-12-07-coherent.md), so it runs only under --packets on.
//
// Why the hits are exactly those of each ray walking alone. Each ray keeps its own 3D-DDA
// state and steps it (leave_voxel) only when the group visits the voxel the ray is in; the
// group visits, each time, a voxel some ray is in, so every ray still passes through its own
// voxels in its own order, and ends by walk_alone's rule (the best hit within its voxel, the
// end of the ray, the grid's edge, the step limit). A ray also tests the triangles of voxels
// its neighbours are in: each is a real hit of the ray, kept by test_triangle's rule (the
// smaller t, ties the smaller id), so it can only stand in for a hit that is as close. What
// makes the walk alone exact (every triangle the ray meets before leaving a voxel is listed
// in that voxel or one before it) makes this one exact too: when a ray stops, the closest
// hit is among the triangles it tested, and the extra tests change neither the triangle nor
// its t (test_triangle's t depends only on the ray and the triangle). Shadow rays stop at
// any hit before tmax: a hit exists either way.
//
// Which voxel: the one furthest behind along the group's common direction (the smallest
// sum of the voxel's coordinates times the step signs; ties: the smallest voxel index), so
// rays in the same voxel move on together and the rays ahead wait for the others to catch
// up. Every visit moves at least one ray on, so the walk ends: each ray's own step limit
// bounds its visits, and the loop ends when every ray of the group is done.
//
// On a backend whose group is one element, the voxel visited is always the ray's own: the
// walk is walk_alone's, step for step.
#include <cstdint>

#include "rill/rt/kernel/Intersector.h"

namespace rt {

using namespace rill;

void Intersector::walk_grid_together(const Float3& o, const RaySteps& rs, const Float& t_exit,
                                     const Bool& any, DdaState& st, Hit& best) const {
  const Float3& d = rs.d;
  RILL_DO {
    const Int3& v = st.vox;
    // How far along the common direction: each step adds 1 (a jump more).
    const Int progress = v.x() * rs.step.x() + v.y() * rs.step.y() + v.z() * rs.step.z();
    const Int behind = group_min(progress);
    const Int index = v.x() + grid_.res.x() * (v.y() + grid_.res.y() * v.z());
    const Int visit = group_min(select(progress == behind, index, Int(INT32_MAX)));
    const Bool here = index == visit;
    // The visited voxel's entry: the same element in every lane.
    const Int2 range = grid_.voxels[visit];
    test_list(o, d, range, any, best);
    if (grid_.subgrids > 0) {  // the second level's code only where the grid has one
      // A subgrid's sub-voxels are walked by each ray in the voxel, along its own line.
      RILL_IF(here && range.y() < 0) {
        walk_subgrid(o, rs, t_exit, any, range, st, best);
      }
      RILL_ENDIF;
    }
    RILL_IF(here) {
      leave_voxel(rs, t_exit, best, any, range, st);
    }
    RILL_ENDIF;
  }
  RILL_UNTIL(st.done);
}

}  // namespace rt
