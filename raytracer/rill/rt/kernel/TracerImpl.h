// Internals of the tracer shared by its two strategies (Tracer.cpp: the single kernel;
// Multipass.cpp: the thesis's kernel sequence). Both are built from the DSL functions
// declared here, so that they compute the same bits.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>

#include "rill/rt/Tracer.h"

namespace rt {

using namespace rill;

constexpr float kBig = 3.0e38f;        // "no limit" for ray extents (finite on every backend)
constexpr float kMinWeight = 1.0e-3f;  // secondary rays below this weight are not traced

// The shading state of a hit: position, normals, material.
struct Surface {
  Float3 P{0.0f}, ns{0.0f}, nf{0.0f}, ngf{0.0f}, V{0.0f}, kd{0.0f}, ks{0.0f};
  Float shin = 0.0f, refl = 0.0f, trans = 0.0f, ior = 1.0f;
  Bool entering = true;
};

// What a 3D-DDA step needs of a ray's direction, computed once per ray (not per step): the
// flat axes, the reciprocal, the step sign and the distance between voxel boundaries.
struct RaySteps {
  Float3 d{0.0f};
  Bool3 flat{false};
  Float3 inv{0.0f};
  Int3 step{0};
  Float3 tdl{0.0f};
};

// The traversal state of a ray between kernels of the multipass strategy is the same as the
// single kernel's loop variables: the current voxel, the distances to the next boundaries,
// where the ray leaves the grid, the steps taken, the best hit so far.
struct Multipass;

struct Tracer::Impl {
  Impl();
  ~Impl();

  Scene scene;  // materials, lights, options (the triangles live in the arrays)
  Grid grid;
  Features F;
  TracerOptions K;  // the accuracy knobs: which code the DSL functions below generate

  // Grid (thesis section 5.3): voxel index, element list; triangle data.
  Array<Int2> voxels{1, "voxels"};
  Array<Int> elements{1, "elements"};
  Array<Float3> tri_v0{1, "tri_v0"}, tri_e1{1, "tri_e1"}, tri_e2{1, "tri_e2"}, tri_ng{1, "tri_ng"};
  // The watertight test needs the vertices themselves: v0 + e1 rounds, and a shared edge
  // must be computed from the same bits in both of its triangles.
  Array<Float3> tri_v1{1, "tri_v1"}, tri_v2{1, "tri_v2"};
  Array<Float3> tri_n0{1, "tri_n0"}, tri_n1{1, "tri_n1"}, tri_n2{1, "tri_n2"};
  Array<Float3> tri_c0{1, "tri_c0"}, tri_c1{1, "tri_c1"}, tri_c2{1, "tri_c2"};
  Array<Int> tri_mat{1, "tri_mat"};
  Array<Float3> mat_kd{1, "mat_kd"}, mat_ks{1, "mat_ks"};
  Array<Float4> mat_p{1, "mat_p"};  // shininess, reflect, transmit, ior
  Array<Float3> light_pos{1, "light_pos"}, light_col{1, "light_col"};

  // Camera (Camera.h) and image.
  Uniform<Float3> eye{glm::vec3(0.0f), "eye"}, forward{glm::vec3(0.0f), "forward"},
      right{glm::vec3(0.0f), "right"}, up{glm::vec3(0.0f), "true_up"};
  Uniform<Float> tan_half{0.0f, "tan_half"}, aspect{1.0f, "aspect"};
  Uniform<Float2> size{glm::vec2(1.0f), "size"}, offset{glm::vec2(0.5f), "sample_offset"};
  // Grid.
  Uniform<Float3> grid_lo{glm::vec3(0.0f), "grid_lo"}, grid_hi{glm::vec3(0.0f), "grid_hi"},
      grid_cell{glm::vec3(1.0f), "grid_cell"};
  Uniform<Int3> grid_res{glm::ivec3(1), "grid_res"};
  Uniform<Int> max_steps{3, "max_voxel_steps"};
  // Shading.
  Uniform<Int> max_depth{5, "max_depth"}, max_iter{64, "max_iterations"}, nlights{0, "light_count"};
  Uniform<Float> ambient{0.1f, "ambient"}, eps{1e-4f, "ray_epsilon"};
  Uniform<Float3> background{glm::vec3(0.0f), "background"};

  Program trace_program, intersect_program, camera_program;
  std::map<std::string, Kernel> kernels;             // backend/accuracy -> compiled tracer
  std::set<std::pair<std::string, int64_t>> warmed;  // kernels launched at a size before
  std::unique_ptr<Multipass> multipass;

  void upload();
  void set_camera(const Camera& camera, int width, int height);
  Kernel& kernel(const std::string& backend, Accuracy a);
  Program capture_tracer() const;
  Program capture_camera() const;
  Program capture_intersector() const;
  RenderResult render_multipass(const RenderSettings& rs, int width, int height, int depth,
                                int spp);

  // ---- DSL building blocks (called inside program bodies) ----------------------------------

  // The camera ray through pixel pix (docs/camera.md).
  Float3 camera_ray(const Int2& pix) const;

  // The ray against the grid's box: inside, and the parameter range [t_enter, t_exit]
  // (t_exit at most tmax).
  void ray_box(const Float3& o, const Float3& d, const Float& tmax, Bool& inside, Float& t_enter,
               Float& t_exit) const;
  // The direction components the traversal treats as zero: zero, and denormals (which a
  // backend may flush, and whose reciprocal overflows): |d| < FLT_MIN.
  Bool3 flat_axes(const Float3& d) const;
  // 1 / d, with 1 on the flat axes; the step (+1, -1, or 0 on flat axes) along each axis.
  Float3 inverse_dir(const Float3& d) const;
  Int3 step_dir(const Float3& d) const;
  // The axis of the smallest of t (the first of equals), as a mask.
  Bool3 nearest_axis(const Float3& t) const;
  // A 3D-DDA's start in the grid of cells (lo, cell), indices 0..last: the cell at o + t d
  // (clamped) and the distances to its exit planes. The top level and the subgrids share it.
  void dda_start(const Float3& o, const Float3& d, const Float& t, const Float3& lo,
                 const Float3& cell, const Float3& last, Int3& vox, Float3& tmx) const;
  // 3D-DDA initialization (thesis 5.1.2): the voxel at t_enter and the distances to the
  // next voxel boundary on each axis (Traversal::Recompute: the origin relative to the
  // grid's corner, from which leave_voxel recomputes the boundaries from the cell index).
  void dda_init(const Float3& o, const Float3& d, const Float& t_enter, Int3& vox,
                Float3& tmx) const;
  // The voxel's entry: the index range (start, count) of its triangles, (distance to the
  // nearest non-empty voxel, 0) when it is empty, or (base, -m) for a subgrid (Grid.h).
  Int2 voxel_range(const Int3& vox) const;
  // The knob's triangle test (Moller-Trumbore or watertight) against the triangle of
  // element-list entry ref; keeps the closest hit (ties: the smaller id).
  void test_triangle(const Float3& o, const Float3& d, const Int& ref, Float& best_t, Int& best_id,
                     Float& best_u, Float& best_v) const;
  // The direction's per-ray traversal constants (RaySteps).
  RaySteps ray_steps(const Float3& d) const;
  // The distances along the ray to the voxel's exit planes (tmx itself when incremental).
  Float3 voxel_exits(const RaySteps& r, const Int3& vox, const Float3& tmx) const;
  // The triangles of a voxel with a subgrid (entry (base, -m), Grid.h): a 3D-DDA over its
  // sub-voxels, within the voxel.
  void walk_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit, const Bool& any_hit,
                    const Int2& entry, const Int3& vox, const Float3& tmx, Float& best_t,
                    Int& best_id, Float& best_u, Float& best_v) const;
  // After a voxel's triangles: done when the best hit lies within the voxel (or any hit,
  // for shadow rays), the ray ends inside it, it leaves the grid or the steps run out;
  // otherwise steps to the next voxel (the axis with the nearest boundary), or, from an
  // empty voxel far from any triangle, jumps over the empty voxels around it. entry is the
  // voxel's entry (voxel_range; (0, 0) where the caller has not loaded it: a plain step).
  void leave_voxel(const RaySteps& r, const Float& t_exit, const Float& best_t, const Int& best_id,
                   const Bool& any_hit, const Int2& entry, Int3& vox, Float3& tmx, Int& steps,
                   Bool& done) const;
  // The whole closest-hit (or any-hit) search, for the single kernel.
  void intersect(const Float3& o, const Float3& d, const Float& tmax, const Bool* any_hit,
                 Bool& hit, Float& best_t, Int& best_id, Float& best_u, Float& best_v) const;

  // A secondary ray's origin: p moved off the surface along n (the knob's fixed epsilon or
  // scale-aware offset).
  Float3 offset_origin(const Float3& p, const Float3& n) const;
  // The surface at a hit of ray (ro, rd) at distance ht on triangle hid, (hu, hv).
  void surface(const Float3& ro, const Float3& rd, const Float& ht, const Int& hid, const Float& hu,
               const Float& hv, Surface& s) const;
  // Phong from light l (without its shadow ray).
  Float3 phong(const Int& l, const Surface& s) const;
  // Local light when there are no shadow rays: all lights, or the headlight.
  Float3 unshadowed_light(const Surface& s) const;
  // The shadow ray towards light l; active is false when the light is behind the surface.
  void shadow_ray(const Int& l, const Surface& s, Float3& ro, Float3& rd, Float& tmax,
                  Bool& active) const;

  // Eq. 5.1 and the next ray: adds the surface's share of local light to color, then (if
  // reflection is on) makes the reflected and refracted rays. Writes the continuing ray into
  // (ro, rd, weight, depth) and sets go; `push` is called for a second branch (refraction
  // with reflection) with its origin, direction and weight, and may be null.
  struct Branch {
    Float3 o{0.0f}, d{0.0f};
    Float w = 0.0f;
  };
  void shade(const Surface& s, const Float3& local, Float3& color, Float& weight, Int& depth,
             Float3& ro, Float3& rd, Bool& go, Bool* has_second, Branch* second) const;
};

// Adds one kernel's compile stages to r.stages (RenderResult).
void add_stages(RenderResult& r, const rill::CompileInfo& k);

// Array contents must be at least one element: empty data gets a dummy element.
template <class V>
std::vector<typename V::host_type> padded(std::vector<typename V::host_type> v) {
  if (v.empty()) v.emplace_back();
  return v;
}

}  // namespace rt
