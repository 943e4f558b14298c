// `rill-trace render`'s options (docs/cli.md), as parsed from the command line, and the
// subcommand that parses them.
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "CameraOptions.h"
#include "rill/rt/Tracer.h"

namespace trace_cli {

// Each value is typed as the command line is parsed: a bad one is an error of the command
// line (exit status 2) naming the option, before any scene is loaded.
struct RenderOptions {
  std::string scene;
  std::string backend = "cpu";  // a backend's name; checked when it is looked up
  rill::Accuracy accuracy = rill::Accuracy::Strict;
  int width = 0, height = 0;  // --size; 0: the scene's
  std::string out, pfm, depth, prim, normal, stats_json, source;
  std::string exr;        // --exr: the linear colour and every AOV in one OpenEXR file
  std::string albedo;     // --albedo: the path integrator's first-hit albedo AOV (PFM)
  bool variance = false;  // --variance: the pixels' variance as channels of --exr
  int max_depth = -1;
  CameraOptions camera;  // --eye, --look-at, --up, --fov, --camera, --up-axis
  int spp = 0;
  // The scene's accelerator options where the command line gives them (Scene.h,
  // SceneOptions: grid 0 is auto, the others' special values as parse_* give them).
  std::optional<int> grid, subgrid_min, light_buffer;
  std::optional<double> grid_density;
  rt::Strategy strategy = rt::Strategy::Megakernel;
  rt::MegakernelLoop loop = rt::MegakernelLoop::Auto;
  bool quiet = false;
  // Input files (Scene.h, InputOptions): malformed lines as errors; mesh files without faces.
  bool strict_input = false, allow_empty = false;
  int threads = 0;  // CPU backends' worker threads; 0: all cores
  // Accuracy knobs (--triangle, --offset, --traversal; kernel/Options.h).
  rt::TracerOptions knobs;
  // Multipass: per-pass statistics, the intersector's rerun threshold, masked launches.
  bool stats = false;
  // --debug, --debug-nonfinite: the kernels' debug mode (docs/debugging.md), as RILL_DEBUG.
  bool debug = false, debug_nonfinite = false;
  double wait_threshold = 0.2;
  bool masking = true;
  // Frame-rate mode: after the first render (which compiles), render this many more frames
  // of the same scene back to back and report their times.
  int bench_frames = 0;
  // --frames: write frame n's outputs on a thread of their own while frame n + 1 renders;
  // --frames and --bench-frames: read frame n back while frame n + 1 traces (read_back_later).
  bool overlap = true;
  // Distributed rendering (docs/distributed.md): tile size and the size of the last tiles
  // (-1: half the tile size; 0: not cut), how long a silent rank or a slow tile is waited
  // for, the device, whether distribution is required.
  int tile = 128, tail_tile = -1;
  double rank_timeout = 20, tile_timeout = 0, checkpoint = 2;
  std::string device;
  bool distribute = false;
  bool progress = false;
  bool backend_given = false;  // --backend on the command line (else $RILL_TRACE_BACKEND)
  // Dynamic scenes (docs/dynamic-scenes.md): the frames to render ("N" or "A:B"), how the
  // BVH follows the moving objects, and a preview video of the frames.
  std::string frames;
  rt::BvhUpdate bvh = rt::BvhUpdate::Rebuild;
  std::string video;
  // The path integrator (docs/path-tracing.md): overrides of the scene's options, and
  // progressive rendering: stop after the pass that crosses a time limit (seconds; 0: none),
  // save the running sums (every N passes, and at the end) and resume from them.
  std::optional<rt::Integrator> integrator;
  std::optional<int> seed;
  double time_limit = 0;
  std::string save, resume;
  int save_every = 0;
};

// Whether the command line names an image output (--out, --pfm, the AOVs, --exr); without one
// a render writes a PNG of a default name.
bool any_image_output(const RenderOptions& o);

// Adds the "render" subcommand to app, parsing into o (which must outlive the parse).
CLI::App* add_render_command(CLI::App& app, RenderOptions& o);

}  // namespace trace_cli
