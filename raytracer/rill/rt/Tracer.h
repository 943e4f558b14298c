// The ray tracer: one Rill program, written once, run on every backend (and, as a second
// strategy, the thesis's multipass kernels built from the same DSL functions).
//
// The kernel (Sh style, after Moreno-Fortuny and McCool) runs one instance per pixel: it
// makes the camera ray (Camera.h), then a RILL_DO ... RILL_UNTIL loop traces one ray per
// iteration through the uniform grid (3D-DDA, Amanatides & Woo) and reacts to what it hit:
// a camera or secondary ray gets Phong shading and then one shadow ray per light; when the
// lights are done, the local colour is weighted as in the thesis's eq. 5.1 and the path
// continues with a reflected or refracted ray (a second branch goes on a small ray stack),
// until the path ends, the stack is empty and the loop finishes.
//
// The accuracy knobs (TracerOptions: triangle test, self-intersection offset, traversal)
// are fixed per tracer and select the code of the shared building blocks (TracerImpl.h).
//
// Only what the scene calls for is generated (host C++ at capture time, see Features):
// a scene without reflective materials has no reflection code, one without lights no
// shadow rays, one without glass no refraction code and no ray stack.
#pragma once

#include <rill/rill.h>

#include <memory>
#include <string>
#include <vector>

#include "rill/rt/scene/Camera.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

struct Multipass;

// What the kernel is generated with, decided on the host from the scene.
struct Features {
  bool geometry = false;        // any traceable triangle (else every ray misses)
  bool lights = false;          // point lights (else a headlight at the eye, no shadows)
  bool shadows = false;         // shadow rays (lights and options.shadows)
  bool specular = false;        // any Ks > 0: Phong highlights
  bool reflection = false;      // any reflect > 0
  bool refraction = false;      // any transmit > 0 (Fresnel, total internal reflection)
  bool vertex_normals = false;  // interpolated normals (mesh normals and smooth_normals)
  bool vertex_colors = false;   // per-vertex colours multiply Kd
  int stack = 0;                // ray stack entries (refraction: reflected branch)
  std::string str() const;      // "geometry lights shadows ..." for logs and stats
};
Features scene_features(const Scene& s);

constexpr int kRayStack = 3;

enum class Strategy {
  Megakernel,  // one kernel per pixel with a RILL_DO loop (Sh)
  Multipass,   // the thesis's kernel sequence with ray states (no refraction)
};

// Accuracy knobs fixed when the tracer is built: each selects different DSL code in the
// generated kernels (and so a different kernel; see docs/accuracy.md, "The ray tracer's
// accuracy knobs"). The defaults are the recommended settings.
enum class TriangleTest {
  MollerTrumbore,  // Moller & Trumbore 1997: edges from v0, the determinant, u, v, t
  Watertight,      // Woop, Benthin & Wald 2013: shear to ray space, three 2D edge functions
};
enum class SelfIntersection {
  Epsilon,  // new rays start at P + eps * n, eps fixed per scene (its size)
  Scaled,   // Wachter & Binder 2019: P from the barycentrics, then a few ulps along n
};
enum class Traversal {
  Incremental,  // 3D-DDA: tMax += tDelta at each step (Amanatides & Woo)
  Recompute,    // tMax recomputed from the cell index at each step (no accumulated error)
};
// Defaults as measured (docs/accuracy.md): the scaled offset is far more accurate at no
// measurable cost; the watertight test costs 5-20% on the CPU for the rare hole; the
// recomputed traversal costs 5-30% and gains nothing measurable.
struct TracerOptions {
  TriangleTest triangle = TriangleTest::MollerTrumbore;
  SelfIntersection offset = SelfIntersection::Scaled;
  Traversal traversal = Traversal::Incremental;
  Features extra_features;  // kernel features forced on (see the Tracer constructor)
  std::string str() const;  // "moller epsilon incremental"
};
// Parse the command-line names (moller|watertight, epsilon|scaled, incremental|recompute);
// throw std::invalid_argument naming the bad value.
TriangleTest parse_triangle_test(const std::string& s);
SelfIntersection parse_self_intersection(const std::string& s);
Traversal parse_traversal(const std::string& s);

struct RenderSettings {
  std::string backend = "cpu";
  Strategy strategy = Strategy::Megakernel;
  rill::Accuracy accuracy = rill::Accuracy::Strict;
  int width = 0, height = 0;  // 0: the scene's
  int max_depth = -1;         // -1: the scene's
  int spp = 0;                // 0: the scene's
  // Multipass strategy (Multipass.cpp): rerun the intersector while at least this fraction
  // of the traced rays waits for it (thesis 5.6: 20%); launch each pass masked to its state.
  double wait_threshold = 0.2;
  bool masking = true;
};

// One multipass pass (kernel) over a render: launches, elements run and written, time.
struct PassStats {
  std::string name;
  int64_t calls = 0, processed = 0, written = 0;
  double ms = 0;
};

struct RenderResult {
  int width = 0, height = 0;
  std::vector<glm::vec3> color;   // linear, row 0 at the top; the mean over the samples
  std::vector<float> depth;       // first-sample AOVs: hit distance (+inf: miss)
  std::vector<int32_t> prim;      // primitive id (-1: miss)
  std::vector<glm::vec3> normal;  // shading normal as stored (0 on a miss)
  int64_t rays = 0;               // rays traced (camera, shadow, secondary), all samples
  double compile_ms = 0;          // 0 when the compiled kernel came from a cache
  bool from_cache = false;
  // The render's kernels' compile stages (Kernel::info()), summed over them: the multipass
  // strategy compiles its nine at once (compile_all), so the sum exceeds compile_ms. origin
  // is the first kernel's.
  rill::CompileInfo stages;
  int kernels = 0;  // how many kernels `stages` sums
  double trace_ms = 0;
  int64_t launches = 0;           // kernel launches while tracing
  std::vector<PassStats> passes;  // multipass only: per pass (Multipass.cpp)
  std::string backend;
};

class Tracer {
 public:
  // Uploads the scene and grid into Rill arrays and captures the program. The scene's
  // options (shadows, smooth normals, ambient) are fixed here; camera, size, depth and
  // samples can change per render.
  // options.extra_features turns kernel features on in addition to the scene's (specular
  // when the scene has lights, reflection, refraction, vertex normals and colours; the rest
  // follow the scene; nothing for a scene without geometry), for benchmarks that compare the
  // specialized kernel with one that has every effect on. Missing vertex normals or colours
  // are then the geometric normal and white.
  Tracer(const Scene& scene, const Grid& grid, const TracerOptions& options = {});
  ~Tracer();
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  const rill::Program& program() const;
  const Features& features() const;
  const TracerOptions& options() const;
  // Compiles (cached per backend and accuracy) and renders through the camera.
  RenderResult render(const RenderSettings& settings, const Camera& camera);
  // The generated source on a backend (compiles if needed).
  std::string source(const std::string& backend, rill::Accuracy a = rill::Accuracy::Strict);

  // The camera rays the tracer casts (the kernel's own ray generation), for tests.
  std::vector<glm::vec3> camera_rays(const std::string& backend, const Camera& camera, int width,
                                     int height, glm::vec2 offset = glm::vec2(0.5f));
  // Traces explicit rays (origin, direction) with the closest-hit intersector only, for
  // tests: returns per ray the primitive id (-1: miss) and distance (+inf: miss).
  void intersect(const std::string& backend, const std::vector<glm::vec3>& origins,
                 const std::vector<glm::vec3>& dirs, std::vector<int32_t>& prim,
                 std::vector<float>& dist, rill::Accuracy accuracy = rill::Accuracy::Strict);
  // The same intersector compiled for a backend (inputs origin, direction; outputs prim,
  // dist), for benchmarks that time launches alone.
  rill::Kernel intersect_kernel(const std::string& backend,
                                rill::Accuracy accuracy = rill::Accuracy::Strict);

 private:
  struct Impl;
  friend struct Multipass;
  std::unique_ptr<Impl> d_;
};

// The sample offsets used for spp samples (sample 0 is the pixel centre).
glm::vec2 sample_offset(int k);

}  // namespace rt
