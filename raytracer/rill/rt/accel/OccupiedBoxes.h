// Boxes that hold every triangle of a grid, tighter than the grid's own box: the grid's
// voxels are grouped into at most max_boxes blocks, and each block gets the box of the parts
// of its triangles' boxes that lie inside it (empty blocks get none).
//
// What they are for: a camera ray that meets none of them hits no static triangle, so the
// megakernel skips the pixels that see none of them (scene/Camera.h, tiles_seeing_boxes).
// The grid's box alone leaves the empty space between a scene's objects to be traced: thesis
// A's three boxes fill about half of the pixels inside their grid's box on screen.
//
// Conservative, exactly: a triangle's box is cut along block faces that are the same float
// numbers on both sides (the outermost faces at infinity), with min and max alone, which do
// not round; so every point of every triangle lies in the box of some block.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// At most this many boxes: the host projects each one's 8 corners for every frame.
constexpr int kMaxOccupiedBoxes = 1024;
// Cutting a triangle's box into blocks visits at most this many (triangle, block) pairs in
// all; past it (huge overlapping triangles), the result is the grid's box alone.
constexpr uint64_t kOccupiedBoxesMaxVisits = uint64_t{1} << 24;

// Widened for a view from `eye`: the kernels' triangle test rounds, and reports hits a little
// outside the exact triangle, by a few ulps of the eye's distance from the triangle's
// vertices, more for rays that graze it (measured: 4e-5 beyond an edge for vertices 1400 from
// the eye). Each box grows by 1e-4 of (|eye| + the largest coordinate of any box), which is
// over 800 such ulps, rounded outwards. So that is the margin for any box of any list passed
// together (the static ones and a dynamic scene's moving box, if any).
float hit_margin(const std::vector<Aabb>& boxes, const Aabb* moving, const glm::vec3& eye);
Aabb widened(const Aabb& b, float margin);

// The boxes of the triangles the grid holds (the static, usable ones); none for an empty
// grid.
std::vector<Aabb> occupied_boxes(const Scene& s, const Grid& grid,
                                 int max_boxes = kMaxOccupiedBoxes,
                                 uint64_t max_visits = kOccupiedBoxesMaxVisits);

}  // namespace rt
