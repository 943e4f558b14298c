// The light buffer (Haines & Greenberg 1986): for each point light, a cube of directions
// around it, each cube face cut into res x res cells, and per cell the triangles that a
// segment from the light through that cell can hit, nearest first. A shadow ray then tests
// the short list of its cell instead of walking the grid (kernel/Intersector.cpp), and
// stops at the first entry farther from the light than its own origin.
//
// Why it pays: a shadow ray starts on a surface inside the grid and walks to the light
// through every voxel on the way, testing the triangles of the surface it leaves again in
// each voxel that surface crosses. From the light's side the same ray meets only the few
// triangles between the light and the surface (thesis A: about 3x fewer triangle tests and
// no 3D-DDA; docs/raytracer.md, "Shadow rays").
//
// Exact, not approximate: a cell lists every triangle whose projection, clipped to the
// face's pyramid and widened by a margin, touches the cell; the margin covers the float
// lookup of the cell and the triangle test's own rounding (both far below it), and a
// triangle that reaches the light itself is listed in every cell of the faces it touches.
// An entry's distance is a lower bound of the distance from the light of the triangle's part
// that the cell's rays can reach. So the list holds every triangle the shadow ray could hit, and
// "is something in the way" has the grid walk's answer: shadows are the same bits with or without
// the light buffer. A spot light's cube is a point light's; a directional light has no point
// to look from, so each of its cells sends the shadow rays to the grid (count -1).
//
// Cells whose list would be longer than max_list (a dense mesh seen from far away) are
// marked (start, -1): their shadow rays walk the grid as before. Face f = 2 * axis + (the
// direction's component along the axis is negative); in-face coordinates (u, v) are the
// other two components in x, y, z order, divided by the major one's magnitude; cell (i, j)
// has index ((light * 6 + f) * res + j) * res + i.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// SceneOptions::light_buffer and --light-buffer (scene/Scene.h): kLightBufferAuto gives
// kLightBufferRes cells per face edge where the scene has shadows.
constexpr int kLightBufferRes = 64;
constexpr int kLightBufferMaxList = 48;
constexpr uint64_t kLightBufferMaxVisits = uint64_t{1} << 27;
// Up to this many entries per light, each is tightened to its cell (LightBuffer.cpp).
constexpr size_t kLightBufferMaxTightened = size_t{1} << 22;

// What a light buffer holds, for --stats-json and warnings.
struct LightBufferStats {
  int res = 0;  // cells per face edge; 0: none
  size_t entries = 0, fallback_cells = 0;
  double build_ms = 0;
  std::string skipped;  // why there is none although one was asked for
};

struct LightBuffer {
  int res = 0;                    // cells per face edge; 0: no light buffer
  std::vector<glm::ivec2> cells;  // (start, count) into tris/near; count -1: walk the grid
  std::vector<int32_t> tris;      // per cell, nearest first (ties: smaller id)
  std::vector<float> near;        // a lower bound of each entry's distance from the light
  size_t fallback_cells = 0;      // cells marked (start, -1)
  float reach = 0;                // farthest ray origin from a light that the margins cover
  std::string skipped;            // why there is none although one was asked for
  double build_ms = 0;
  bool empty() const { return res == 0; }
  LightBufferStats stats() const { return {res, tris.size(), fallback_cells, build_ms, skipped}; }
};

// The light buffer of the scene's lights over the triangles the grid holds (the static
// ones; moving triangles stay with the BVH), res cells per face edge; max_list as above.
// Its time and memory are bounded: when the triangles' rectangles of cells add up to more
// than max_visits (huge triangles close to a light, at a high resolution), it gives up and
// returns none, saying why in `skipped` (the shadow rays then walk the grid); the entries
// it keeps are at most max_list + 1 per cell while it builds.
//
// Each entry's distance is then tightened to the part of its triangle that the cell's rays
// can reach, and entries whose triangle misses the cell's directions (they were listed for
// the box of cells around the triangle) are dropped, where a light's entries number at most
// max_tightened: a lit point's shadow ray then tests about half as many triangles (thesis A:
// 3566 entries instead of 6116).
LightBuffer build_light_buffer(const Scene& s, const Grid& grid, int res,
                               int max_list = kLightBufferMaxList,
                               uint64_t max_visits = kLightBufferMaxVisits,
                               size_t max_tightened = kLightBufferMaxTightened);

// The resolution SceneOptions::light_buffer asks for (auto: kLightBufferRes, fewer where
// many lights would make more than 2^22 cells, and 0, none, where even 8 would or lights times
// triangles pass 2^26: the build would take seconds).
int light_buffer_res(const Scene& s);

// The cell of direction q (a point minus the light's position), as the kernels compute it:
// face f, then (i, j); for tests and for the kernels' reference.
glm::ivec3 light_buffer_cell(const glm::vec3& q, int res);

// "auto", "off" or a resolution 1..kLightBufferMaxRes; throws std::invalid_argument naming
// the value.
int parse_light_buffer(const std::string& s);

}  // namespace rt
