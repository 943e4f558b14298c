#include "Prepare.h"

#include <chrono>
#include <cstdio>

#include "Doing.h"
#include "rill/Stopwatch.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/Pose.h"

namespace trace_cli {

using Clock = std::chrono::steady_clock;
using rill::ms_since;

std::unique_ptr<Prepared> prepare(const RenderOptions& o, bool say) {
  auto p = std::make_unique<Prepared>();
  g_doing = "loading " + rt::clipped(o.scene);
  const auto t_load = Clock::now();
  rt::InputOptions input;
  input.strict = o.strict_input;
  input.allow_empty = o.allow_empty;
  {
    rt::InputFileLog read;  // every file loading reads, which no output may overwrite
    p->scene = rt::load_scene(o.scene, input);
    p->inputs = read.paths();
  }
  rt::Scene& scene = p->scene;
  if (o.width > 0) scene.width = o.width, scene.height = o.height;
  if (o.max_depth >= 0) scene.options.max_depth = o.max_depth;
  if (o.spp > 0) scene.options.spp = o.spp;
  if (o.grid) scene.options.grid = *o.grid;
  if (o.subgrid_min) scene.options.subgrid_min = *o.subgrid_min;
  if (o.light_buffer) scene.options.light_buffer = *o.light_buffer;
  if (o.grid_density) scene.options.grid_density = *o.grid_density;
  if (o.max_depth > 64) throw rt::SceneError("--max-depth must be in 0..64");
  if (o.integrator) scene.options.integrator = *o.integrator;
  if (o.seed) scene.options.seed = static_cast<uint32_t>(*o.seed);
  const bool path = scene.options.integrator == rt::Integrator::Path;
  for (const auto& [given, name] : {std::pair{o.time_limit > 0, "--time-limit"},
                                    {!o.save.empty(), "--save"},
                                    {!o.resume.empty(), "--resume"}})
    if (given && !path)
      throw rt::SceneError(std::string(name) +
                           " is for the path integrator (options.integrator \"path\" or "
                           "--integrator path); a Whitted render is not progressive");
  if (o.save_every > 0 && o.save.empty()) throw rt::SceneError("--save-every needs --save FILE");
  if (o.variance && o.exr.empty()) throw rt::SceneError("--variance needs --exr FILE");
  if (!o.albedo.empty() && !path)
    throw rt::SceneError("--albedo is the path integrator's AOV (--integrator path)");
  apply_camera_options(scene, o.camera);
  scene.validate();
  // An animated scene's camera as it is at the start (Pose.h): frame 0, for every path that
  // renders one frame; --frames moves it per frame.
  if (scene.animation.animated()) scene.camera = rt::camera_at(scene, scene.animation.time.start);
  p->load_ms = ms_since(t_load);
  for (const std::string& w : scene.warnings)
    if (say) std::fprintf(stderr, "rill-trace: warning: %s\n", w.c_str());

  g_doing = "building the grid of " + std::to_string(scene.triangle_count()) + " triangles";
  p->grid = rt::build_grid_for(scene, o.backend);  // settings left open: for the backend
  for (const std::string& w : p->grid.warnings) {
    if (say) std::fprintf(stderr, "rill-trace: warning: %s\n", w.c_str());
    scene.warnings.push_back(w);  // for --stats-json
  }

  const auto t_setup = Clock::now();
  g_doing = "uploading the scene and grid (" + std::to_string(p->grid.voxel_count()) +
            " voxels) and building the light buffer";
  p->tracer = std::make_unique<rt::Tracer>(scene, p->grid, o.knobs);
  p->setup_ms = ms_since(t_setup);
  if (const std::string& why = p->tracer->light_buffer().skipped; !why.empty()) {
    const std::string w = "no light buffer (" + why + "): shadow rays walk the grid";
    if (say) std::fprintf(stderr, "rill-trace: warning: %s\n", w.c_str());
    scene.warnings.push_back(w);
  }

  rt::RenderSettings& rs = p->rs;
  rs.backend = o.backend;
  rs.accuracy = o.accuracy;
  rs.strategy = o.strategy;
  rs.loop = o.loop;
  rs.width = scene.width;
  rs.height = scene.height;
  rs.wait_threshold = o.wait_threshold;
  rs.masking = o.masking;
  // Only what is written comes back from the device (the PNG: 8-bit, encoded there).
  p->out = o.out;
  if (!any_image_output(o))
    p->out = (scene.name.empty() ? std::string("render") : scene.name) + ".png";
  rs.outputs.rgb8 = !p->out.empty();
  // --exr holds the linear colour and every AOV.
  const bool exr = !o.exr.empty();
  rs.outputs.color = !o.pfm.empty() || exr;
  rs.outputs.depth = !o.depth.empty() || exr;
  rs.outputs.prim = !o.prim.empty() || exr;
  rs.outputs.normal = !o.normal.empty() || exr;
  // The albedo is the path integrator's, read back for --albedo (--exr then adds its channels
  // too, in one process and under mpirun alike: the tiles carry it, and the variance).
  rs.outputs.albedo = scene.options.integrator == rt::Integrator::Path && !o.albedo.empty();
  rs.outputs.variance = o.variance;
  return p;
}

}  // namespace trace_cli
