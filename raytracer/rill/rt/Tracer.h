// The ray tracer's facade (rill::raytracer): build a Tracer from a scene and its grid, then
// render through a camera on any backend, with any registered strategy.
//
//   rt::Scene scene = rt::load_scene("scenes/cornell.json");   // load/SceneFile.h
//   rt::Grid grid = rt::build_grid_for(scene);                 // accel/Grid.h
//   rt::Tracer tracer(scene, grid);
//   rt::RenderSettings rs;  rs.backend = "opencl";  rs.width = 640;  rs.height = 480;
//   rt::RenderResult image = tracer.render(rs, scene.camera);
//
// Materials name surface shaders (kernel/Shader.h); register your own with
// rt::register_shader (shaders/Registry.h) before building the tracer: a tracer generates
// its kernels from the shaders registered when it is built. Inside, the tracer uploads the scene
// once (kernel/DeviceScene.h) and builds its programs from the DSL building blocks there: the
// megakernel (megakernel/), one kernel per pixel with a loop, and the thesis's multipass
// sequence of small kernels (multipass/). Only what the scene calls for is generated
// (kernel/Features.h): its shaders, its textures, reflection, refraction and shadow code.
//
// The accuracy knobs (TracerOptions: triangle test, self-intersection offset, traversal)
// are fixed per tracer and select the code of the shared building blocks.
#pragma once

#include <rill/rill.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/render/RenderResult.h"
#include "rill/rt/render/RenderSettings.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/shaders/Registry.h"

namespace rt {

class RenderStrategy;
struct DeviceScene;

// The render strategies, by name: megakernel and multipass are built in, and a program adds
// its own (a class implementing strategy/RenderStrategy.h, made for a tracer's DeviceScene)
// before rendering with it: RenderSettings::strategy = {"name"}. A tracer makes a strategy at
// its first frame that asks for it. register_strategy throws std::invalid_argument for an
// empty or taken name.
using StrategyFactory = std::function<std::unique_ptr<RenderStrategy>(DeviceScene& scene)>;
void register_strategy(const std::string& name, StrategyFactory make);
std::vector<std::string> strategy_names();  // in the order they were registered
// The strategy of that name (as rill-trace's --strategy takes it); throws
// std::invalid_argument naming the bad value and the strategies there are.
Strategy parse_strategy(const std::string& s);

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
  // Compiles (cached per backend and accuracy) and renders through the camera, which must be
  // of the scene camera's kind (pinhole, orthographic or thin lens: camera_kind, Camera.h), as
  // the kernels generate that kind of ray; another kind throws std::runtime_error.
  RenderResult render(const RenderSettings& settings, const Camera& camera);
  // The same into `result`, whose image memory is reused: frame after frame into one
  // RenderResult allocates nothing on the host. With settings.read_back_later the images may
  // still be in flight when it returns (result.wait_outputs() waits; a render into a result
  // whose images are in flight waits for them first).
  void render(const RenderSettings& settings, const Camera& camera, RenderResult& result);
  // The megakernel's generated source on a backend (compiles if needed). Outputs and samples
  // per pixel select no variant: every render on that backend, accuracy and loop runs this
  // one kernel (megakernel/Megakernel.h); the two arguments are kept for existing callers.
  std::string source(const std::string& backend, rill::Accuracy a = rill::Accuracy::Strict,
                     MegakernelLoop loop = MegakernelLoop::Auto,
                     const FrameOutputs& outputs = FrameOutputs{}, int spp = 1);

  // The camera rays the tracer casts (the kernel's own ray generation), for tests.
  // origins (if given) gets each ray's origin; sample is the thin lens's sample index.
  std::vector<glm::vec3> camera_rays(const std::string& backend, const Camera& camera, int width,
                                     int height, glm::vec2 offset = glm::vec2(0.5f),
                                     std::vector<glm::vec3>* origins = nullptr, int sample = 0);
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

}  // namespace rt
