// The grid (Grid.h) as the kernels see it: its voxel index and element list in Rill arrays,
// its box, cells and resolution in uniforms, and the traversal's step limit.
#pragma once

#include <rill/rill.h>

#include "rill/rt/accel/Grid.h"

namespace rt {

struct GridView {
  rill::Array<rill::Int2> voxels{1, "voxels"};
  rill::Array<rill::Int> elements{1, "elements"};
  rill::Uniform<rill::Float3> lo{glm::vec3(0.0f), "grid_lo"}, hi{glm::vec3(0.0f), "grid_hi"},
      cell{glm::vec3(1.0f), "grid_cell"};
  rill::Uniform<rill::Int3> res{glm::ivec3(1), "grid_res"};
  rill::Uniform<rill::Int> max_steps{3, "max_voxel_steps"};
  int64_t subgrids = 0;  // host: the second level's code is generated only where there is one
  bool empty = true;     // host: no triangle in the grid (all of them move, or none)

  void upload(const Grid& grid);
  // The voxel's entry: the index range (start, count) of its triangles, (distance to the
  // nearest non-empty voxel, 0) when it is empty, or (base, -m) for a subgrid (Grid.h).
  rill::Int2 voxel_range(const rill::Int3& vox) const;
};

}  // namespace rt
