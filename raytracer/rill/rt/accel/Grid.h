// The uniform grid (thesis section 5.1), built on the CPU.
//
// The scene's bounding box (padded slightly) is cut into res.x * res.y * res.z voxels. A
// triangle is referenced in every voxel it overlaps, decided by an exact separating-axis
// triangle-box test (Akenine-Moller: the 3 box axes, the triangle normal and the 9 edge x
// axis cross products) in double precision, on voxels enlarged by a tiny margin (1e-4 of a
// voxel) so that the float 3D-DDA never misses a triangle lying on a voxel face.
//
// Storage, as in the thesis: a voxel index (per voxel: start and count in the element
// list), the element list (triangle ids, ascending within a voxel) and the triangle data
// (kernel/Triangles.h). Voxel (x, y, z) has index x + res.x * (y + res.y * z).
//
// Empty-space skipping (a "proximity cloud", Cohen & Sheffer 1994): an empty voxel has no
// use for its start, so its entry holds instead its chessboard distance to the nearest
// non-empty voxel (max over the axes of |index difference|; 0 never occurs, and a grid
// with no triangles at all has 0 everywhere). Every voxel closer than that is empty, so the
// traversal may jump across them in one step (kernel/Intersector.cpp, leave_voxel) instead of
// visiting them one by one; the entry it loads anyway tells it how far.
//
// Two levels, optional (Jevans & Wyvill 1989; Kalojanov, Billeter & Slusallek 2011 on GPUs):
// a uniform grid suits the empty space between objects, but a surface mesh puts many
// triangles in the few voxels its surface crosses (the bunny: about 10 per voxel a ray
// reaches). With subgrids on (build_grid's subgrid_min, --subgrids; off by default, see
// kSubgridMin), a voxel listing more than subgrid_min triangles gets its own m x m x m subgrid (m
// from kSubgridDensity sub-voxels per triangle, 2..kSubgridMaxRes), built with the same exact
// overlap test and margin on the sub-voxels; the ray walks it with a second 3D-DDA confined
// to the voxel (kernel/Intersector.cpp, walk_subgrid). Subgrid entries follow the top level's in
// `voxels`: sub-voxel (i, j, k) of a subgrid at base b is voxels[b + i + m (j + m k)].
//
// A voxel entry is (start, count) into the element list when count > 0; (distance, 0) when
// the voxel is empty; (base, -m) when it has a subgrid. Sub-voxel entries are (start, count)
// (count 0: empty).
//
// Resolution: --grid N gives N^3 voxels. "auto" chooses cells of equal size, about
// `density` voxels per triangle (--grid-density; by default chosen by grid_density_for): with the
// box extents d and n triangles, res_a = round(d_a * cbrt(density * n / (d_x d_y d_z))), each
// clamped to 1..256 and the total to 2^22 voxels (flat extents are taken as 1/256 of the
// largest). Denser grids trade memory for fewer triangle tests per ray: measured in
// docs/raytracer.md; the default rule gives simd 16 on large scenes (grid_density_for).
//
// Triangles with a non-finite vertex or zero area (in double precision) are left out of the
// grid: they are never hit, but keep their primitive ids.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

// The threshold when subgrids are on: more triangles than this in a voxel, a subgrid.
// Measured (docs/raytracer.md, Performance settings), they help backends that run on the CPU
// (thesis C 1.4-1.5x) but cost NVIDIA's OpenCL 16-35%, and take 2.5x the memory and 2-3x the
// build time. So by default (kSubgridsAuto) a grid gets them for a backend on the CPU and not
// for one on a GPU (subgrid_min_for).
constexpr int32_t kSubgridMin = 12;
constexpr double kSubgridDensity = 4.0;  // sub-voxels per triangle of the voxel
constexpr int32_t kSubgridMaxRes = 8;

struct Grid {
  glm::vec3 lo{0.0f}, hi{0.0f};  // hi = lo + res * cell (float32)
  glm::vec3 cell{1.0f};
  glm::ivec3 res{1};
  std::vector<glm::ivec2> voxels;  // (start, count) into elements; (distance, 0) if empty
  std::vector<int32_t> elements;
  int64_t subgrids = 0;   // voxels with a subgrid
  size_t usable = 0;      // triangles in the grid
  size_t degenerate = 0;  // zero area: left out
  size_t non_finite = 0;  // a NaN or infinite vertex: left out
  size_t moving = 0;      // in animated objects (Scene::animation): left to the tracer's BVH
  double build_ms = 0;
  // What the user should know about the grid they asked for (a resolution that is mostly
  // empty space); rill-trace prints them and puts them in --stats-json.
  std::vector<std::string> warnings;
  bool empty() const { return usable == 0; }
  int64_t voxel_count() const { return int64_t{res.x} * res.y * res.z; }
};

// True if the triangle overlaps the box (centre c, half sizes h), touching included.
bool triangle_box_overlap(const glm::dvec3& c, const glm::dvec3& h, const glm::dvec3 tri[3]);
// Non-finite or zero-area triangles are not traced.
bool triangle_usable(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c);
// The automatic resolution for n triangles in a box of extent d.
glm::ivec3 auto_grid_resolution(const glm::dvec3& extent, size_t n, double density = kGridDensity);

// Replaces each voxel listing more than min_count triangles by a subgrid (above).
void build_subgrids(Grid& g, const Scene& s, int32_t min_count = kSubgridMin);
// Writes into each empty voxel's entry its chessboard distance to the nearest non-empty
// voxel (exact: two raster passes over the 26-neighbourhood, capped at kMaxSkip).
void compute_empty_distances(Grid& g);
constexpr int32_t kMaxSkip = 1 << 16;

// A grid resolution as a command line gives it (rill-trace's --grid, rill-bench-trace's
// --grids): "auto" (or empty) is 0, else voxels per axis in 1..512; throws SceneError naming
// `option` and the bad value.
int parse_grid_resolution(const std::string& s, const std::string& option);
// The --subgrids value: "auto" (kSubgridsAuto), "off" (kNoSubgrids) or a triangle count in
// 1..2^20; throws SceneError naming the option and the bad value.
int32_t parse_subgrid_min(const std::string& s);
// The --grid-density value: "auto" (kGridDensityAuto) or voxels per triangle in
// kGridDensityMin..Max; throws SceneError naming the option and the bad value.
double parse_grid_density(const std::string& s);
double checked_grid_density(double d);  // the same range check on a number

// The density rule (--grid-density auto, the default), measured in
// docs/benchmarks/2026-12-07-simd-gathers.md: the simd backend gets kGridDensitySimdLarge
// voxels per triangle for a scene of at least kGridDensityLargeScene triangles (the bunny:
// 0.54 against 0.44 of Embree's speed on primary rays), every other case kGridDensity: denser
// grids did not pay on scenes of a few thousand triangles, nor for `cpu` (thesis C slower),
// and cost NVIDIA's OpenCL (docs/gpu.md). Images never depend on it: the grid is exact.
// Under the path integrator simd keeps kGridDensity: its bounces' rays are incoherent, and
// the lanes of a group (8 or 16) wait for the longest walk, which a denser grid lengthens
// (thesis C, with or without an area light: 1.2-1.4x the frame at 16;
// docs/benchmarks/2026-12-08-simd-path-default.md).
constexpr double kGridDensitySimdLarge = 16.0;
constexpr size_t kGridDensityLargeScene = 10000;
// The density a grid for `backend` gets: `density` itself unless it is kGridDensityAuto, then
// the rule above for a scene of `triangles` triangles rendered by `integrator`.
double grid_density_for(double density, const std::string& backend, size_t triangles,
                        Integrator integrator = Integrator::Whitted);

// The subgrid threshold a grid for `backend` gets: `subgrid_min` itself unless it is
// kSubgridsAuto, then kSubgridMin when the backend runs on the CPU and kNoSubgrids when it
// runs on a GPU (Backend::runs_on_gpu).
int32_t subgrid_min_for(int32_t subgrid_min, const std::string& backend);

// The memory a grid may take while it is built and traced, in bytes: RILL_MAX_GRID_MB, else
// half the machine's physical memory. build_grid refuses a grid whose estimate is over it
// before allocating, with a SceneError giving the estimate and the limit.
uint64_t grid_memory_limit();
// The estimate: bytes per voxel (the cell table, the build's counters, the empty-space
// distances and the tracer's copy, measured at about 24) and per triangle reference.
constexpr uint64_t kGridBytesPerVoxel = 24;
constexpr uint64_t kGridBytesPerReference = 12;

// resolution: voxels per axis, 0 = auto (at `density` voxels per triangle; kGridDensityAuto,
// with no backend to choose for: kGridDensity). subgrid_min:
// voxels listing more triangles than this get a subgrid (kNoSubgrids, or any value <= 0,
// kSubgridsAuto included: a one-level grid; build_grid_for resolves kSubgridsAuto).
Grid build_grid(const Scene& s, int resolution = 0, int32_t subgrid_min = kNoSubgrids,
                double density = kGridDensity);
// The grid the scene's options ask for (grid, subgrid_min, grid_density), with the settings
// left to the renderer chosen for `backend` (subgrid_min_for, grid_density_for). Images never
// depend on them.
Grid build_grid_for(const Scene& s, const std::string& backend = "cpu");

}  // namespace rt
