// Uploads the grid for the kernels (GridView.h).
#include "rill/rt/kernel/GridView.h"

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

void GridView::upload(const Grid& grid) {
  upload_padded(voxels, grid.voxels);
  upload_padded(elements, grid.elements);
  lo.set(grid.lo);
  hi.set(grid.hi);
  cell.set(grid.cell);
  res.set(grid.res);
  subgrids = grid.subgrids;
  empty = grid.empty();
  // The traversal's step limit, a proof rather than a guess: every step moves the voxel by
  // one along one axis, never against the sign of d, and the loop ends when the voxel
  // leaves [0, res). So a ray (any ray, whatever rounding did to tMax) takes at most
  // (res.x - 1) + (res.y - 1) + (res.z - 1) steps inside and one more out: res.x + res.y +
  // res.z - 2 steps. The limit (with 5 to spare) never cuts a real traversal short; it ends
  // the loop for rays whose steps are 0 on the chosen axis (NaN directions), which would
  // otherwise stay in one voxel forever. Every loop iteration counts a step, so the loop
  // runs at most max_voxel_steps + 1 times on any input.
  max_steps.set(grid.res.x + grid.res.y + grid.res.z + 3);
}

rill::Int2 GridView::voxel_range(const rill::Int3& vox) const {
  return voxels[vox.x() + res.x() * (vox.y() + res.y() * vox.z())];
}

}  // namespace rt
