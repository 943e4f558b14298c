// `rill-trace render`'s options (docs/cli.md), as parsed from the command line, and the
// subcommand that parses them.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace trace_cli {

struct RenderOptions {
  std::string scene;
  std::string backend = "cpu";
  std::string accuracy = "strict";
  std::string size;
  std::string out, pfm, depth, prim, normal, stats_json, source;
  int max_depth = -1;
  int spp = 0;
  std::string grid = "";
  std::string subgrids = "";
  std::string light_buffer = "";
  std::string grid_density = "";
  std::string strategy = "megakernel";
  std::string loop = "auto";
  bool quiet = false;
  // Input files (Scene.h, InputOptions): malformed lines as errors; mesh files without faces.
  bool strict_input = false, allow_empty = false;
  int threads = 0;  // CPU backends' worker threads; 0: all cores
  // Accuracy knobs (Tracer.h, TracerOptions).
  std::string triangle = "moller", offset = "scaled", traversal = "incremental";
  // Multipass: per-pass statistics, the intersector's rerun threshold, masked launches.
  bool stats = false;
  double wait_threshold = 0.2;
  std::string masking = "on";
  // Frame-rate mode: after the first render (which compiles), render this many more frames
  // of the same scene back to back and report their times.
  int bench_frames = 0;
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
  std::string bvh = "rebuild";
  std::string video;
};

// Adds the "render" subcommand to app, parsing into o (which must outlive the parse).
CLI::App* add_render_command(CLI::App& app, RenderOptions& o);

}  // namespace trace_cli
