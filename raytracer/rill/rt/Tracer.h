// The ray tracer's facade (rill::raytracer): build a Tracer from a scene and its grid, then
// render through a camera on any backend, with either strategy.
//
//   rt::Scene scene = rt::load_scene("scenes/cornell.json");   // scene/Scene.h
//   rt::Grid grid = rt::build_grid_for(scene);                 // accel/Grid.h
//   rt::Tracer tracer(scene, grid);
//   rt::RenderSettings rs;  rs.backend = "opencl";  rs.width = 640;  rs.height = 480;
//   rt::RenderResult image = tracer.render(rs, scene.camera);
//
// Materials name surface shaders (kernel/Shader.h); register your own with
// rt::register_shader before building the tracer. Inside, the tracer uploads the scene once
// (kernel/DeviceScene.h) and builds its programs from the DSL building blocks there: the
// megakernel (megakernel/), one kernel per pixel with a loop, and the thesis's multipass
// sequence of small kernels (multipass/). Only what the scene calls for is generated
// (kernel/Features.h): its shaders, its textures, reflection, refraction and shadow code.
//
// The accuracy knobs (TracerOptions: triangle test, self-intersection offset, traversal)
// are fixed per tracer and select the code of the shared building blocks.
#pragma once

#include <rill/rill.h>

#include <memory>
#include <string>
#include <vector>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

enum class Strategy {
  Megakernel,  // one kernel per pixel with a RILL_DO loop (Sh; megakernel/)
  Multipass,   // the thesis's kernel sequence with ray states, no refraction (multipass/)
};

// The shape of the megakernel's loop (megakernel/Megakernel.h). Images do not depend on it,
// only speed does (docs/benchmarks/2026-11-25-gpu-frame.md, "Session 23").
enum class MegakernelLoop {
  Auto,     // Segment on cpu and simd; Ray on every other backend, whatever its device
  Ray,      // one traced ray per iteration, camera, secondary or shadow: the walk has one call
            // site, so a GPU's lanes walk together whichever kind of ray each one holds
  Segment,  // one path segment per iteration, its shadow rays traced in a light loop inside
            // it: no loop iteration per light, and a walk specialized for each kind of ray
};
// "auto", "ray" or "segment"; throws std::invalid_argument naming the bad value.
MegakernelLoop parse_megakernel_loop(const std::string& s);
const char* megakernel_loop_name(MegakernelLoop loop);
// The shape `loop` stands for on `backend`: Auto resolved, the others as they are.
MegakernelLoop megakernel_loop_for(MegakernelLoop loop, const std::string& backend);

// What a render reads back to the host (RenderResult): everything else stays on the device.
// A PNG needs only `rgb8`; a PFM needs `color`; the AOVs only when asked for.
struct FrameOutputs {
  bool color = true;   // RenderResult::color: the linear mean colour, 3 floats per pixel
  bool rgb8 = false;   // RenderResult::rgb8: the 8-bit sRGB encoding, encoded on the device
  bool depth = true;   // RenderResult::depth
  bool prim = true;    // RenderResult::prim
  bool normal = true;  // RenderResult::normal
};

// How a dynamic scene's BVH follows its moving triangles from one frame to the next
// (accel/Bvh.h): a new tree, or the same tree with its boxes recomputed (faster; the tree
// suits the new poses less as they drift from the ones it was built for). Either way the image
// is the same.
enum class BvhUpdate { Rebuild, Refit };
// "rebuild" or "refit"; throws std::invalid_argument naming the bad value.
BvhUpdate parse_bvh_update(const std::string& s);

// What Tracer::set_time did, in milliseconds.
struct FrameUpdate {
  double pose_ms = 0;    // the animated objects moved (host)
  double bvh_ms = 0;     // the BVH built or refitted (host, oneTBB)
  double upload_ms = 0;  // the moved triangles and the BVH uploaded
  // Triangles uploaded: the span from the first moving triangle to the last (static ones
  // inside it included); the rest of the scene's arrays stay on the device as they are.
  size_t uploaded = 0;
  bool rebuilt = false;  // a new tree (a refit falls back to it when triangles come or go)
  size_t moving = 0;     // moving triangles in the BVH
  int bvh_nodes = 0, bvh_depth = 0;
};

struct RenderSettings {
  std::string backend = "cpu";
  Strategy strategy = Strategy::Megakernel;
  MegakernelLoop loop = MegakernelLoop::Auto;  // the megakernel strategy's loop
  rill::Accuracy accuracy = rill::Accuracy::Strict;
  int width = 0, height = 0;  // 0: the scene's
  int max_depth = -1;         // -1: the scene's
  int spp = 0;                // 0: the scene's
  // Multipass strategy (Multipass.cpp): rerun the intersector while at least this fraction
  // of the traced rays waits for it (thesis 5.6: 20%); launch each pass masked to its state.
  double wait_threshold = 0.2;
  bool masking = true;
  FrameOutputs outputs;  // what comes back to the host
  // A window of the image, in its pixels (row 0 at the top): only these are rendered, through
  // the whole image's camera, bitwise the same as those pixels of the whole render, and the
  // RenderResult is the window's size. Empty (width or height 0): the whole image. The
  // distributed renderer's tiles (apps/rill-trace/distributed/).
  struct Window {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
  } window;
};

// A render's time, step by step, in milliseconds (wall clock on the host; they add up to
// RenderResult::trace_ms, less a little bookkeeping).
struct FrameTimes {
  double setup = 0;   // output buffers made or resized (0 when a frame reuses them)
  double launch = 0;  // the tracing kernels' launches, each until its kernel has run
  // Of `launch`: how long the tracing kernels ran, as the device timed them
  // (rill::LaunchStats::device_ms, summed); the rest of `launch` is the cost of launching.
  // -1 where the backend cannot tell.
  double kernel = 0;
  double accumulate = 0;  // samples added up on the device (spp > 1) and their mean
  double reduce = 0;      // the ray count, reduced on the device
  double read_back = 0;   // the outputs asked for, encoded (8-bit) and read back

  // Adds one launch's device time to `kernel` (which stays -1 once a launch could not tell).
  void add_kernel(double device_ms) {
    kernel = kernel < 0 || device_ms < 0 ? -1 : kernel + device_ms;
  }
};

// One multipass pass (kernel) over a render: launches, elements run and written, time.
struct PassStats {
  std::string name;
  int64_t calls = 0, processed = 0, written = 0;
  double ms = 0;
};

// The image and AOVs of a render: those RenderSettings::outputs asked for (the others are
// left empty).
struct RenderResult {
  int width = 0, height = 0;
  std::vector<glm::vec3> color;     // linear, row 0 at the top; the mean over the samples
  std::vector<unsigned char> rgb8;  // the same as 8-bit sRGB (to_srgb8), 3 bytes per pixel
  std::vector<float> depth;         // first-sample AOVs: hit distance (+inf: miss)
  std::vector<int32_t> prim;        // primitive id (-1: miss)
  std::vector<glm::vec3> normal;    // shading normal as stored (0 on a miss)
  int64_t rays = 0;                 // rays traced (camera, shadow, secondary), all samples
  double compile_ms = 0;            // 0 when the compiled kernel came from a cache
  bool from_cache = false;
  // The render's kernels' compile stages (Kernel::info()), summed over them: the multipass
  // strategy compiles its nine at once (compile_all), so the sum exceeds compile_ms. origin
  // is the first kernel's.
  rill::CompileInfo stages;
  int kernels = 0;                // how many kernels `stages` sums
  double trace_ms = 0;            // the frame: launches, accumulation, reduction, read-back
  FrameTimes times;               // trace_ms, step by step
  int64_t launches = 0;           // kernel launches while tracing
  std::vector<PassStats> passes;  // multipass only: per pass (Multipass.cpp)
  std::string backend;
  std::string loop;  // the megakernel's loop as run ("ray" or "segment"); empty for multipass
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

  // The megakernel's program with the given loop (Auto: Ray, the program GPUs run; the
  // CPU backends run Segment's, megakernel_loop_for). The Segment loop's is captured with the
  // tracer, the Ray loop's at its first use.
  const rill::Program& program(MegakernelLoop loop = MegakernelLoop::Ray) const;
  const Features& features() const;
  const TracerOptions& options() const;
  // The shadow rays' light buffer (accel/LightBuffer.h): res 0 where there is none.
  const LightBufferStats& light_buffer() const;
  // The shaders generated into the kernels: those of the materials the scene's triangles use.
  std::vector<std::string> shaders() const;
  // Dynamic scenes (Scene::animation, docs/dynamic-scenes.md): moves the animated objects
  // to `time` (seconds) and brings their BVH up to date; the static triangles' grid, the
  // compiled kernels and the other arrays stay as they are. The camera is the caller's:
  // camera_at(scene, time) (scene/Pose.h). A new tracer starts at the time range's start.
  // Nothing to do for a static scene.
  FrameUpdate set_time(double time, BvhUpdate how = BvhUpdate::Rebuild);
  // Compiles (cached per backend and accuracy) and renders through the camera.
  RenderResult render(const RenderSettings& settings, const Camera& camera);
  // The same into `result`, whose image memory is reused: frame after frame into one
  // RenderResult allocates nothing on the host.
  void render(const RenderSettings& settings, const Camera& camera, RenderResult& result);
  // The megakernel's generated source on a backend (compiles if needed): the variant a
  // render with these outputs and samples per pixel runs (without AOV outputs when none is
  // asked for; encoding the 8-bit image itself for one sample without the linear colour).
  std::string source(const std::string& backend, rill::Accuracy a = rill::Accuracy::Strict,
                     MegakernelLoop loop = MegakernelLoop::Auto,
                     const FrameOutputs& outputs = FrameOutputs{}, int spp = 1);

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
  std::unique_ptr<Impl> d_;
};

// The sample offsets used for spp samples (sample 0 is the pixel centre).
glm::vec2 sample_offset(int k);
// Adds one kernel's compile stages to r.stages.
void add_stages(RenderResult& r, const rill::CompileInfo& k);

}  // namespace rt
