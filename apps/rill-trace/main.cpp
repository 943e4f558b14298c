// rill-trace: the Rill ray tracer's command line.
//
//   rill-trace render SCENE [--backend cpu|simd|opencl|glsl|glsl-compute] [--accuracy
//   strict|fast|double]
//                           [--size WxH] [--out FILE.png] [--pfm FILE.pfm] [--depth FILE.pfm]
//                           [--prim FILE.pfm] [--normal FILE.pfm] [--max-depth N] [--spp N]
//                           [--grid N|auto] [--grid-density D] [--subgrids N|off|auto]
//                           [--light-buffer N|off|auto]
//                           [--strategy megakernel|multipass] [--loop auto|ray|segment]
//                           [--stats-json FILE] [--source FILE] [--quiet]
//                           [--triangle moller|watertight] [--offset epsilon|scaled]
//                           [--traversal incremental|recompute]
//                           [--stats] [--wait-threshold F] [--masking on|off]   (multipass)
//                           [--device SPEC] [--tile N] [--tail-tile N] [--rank-timeout S]
//                           [--tile-timeout S] [--checkpoint S] [--progress] [--distribute]
//                           (under mpirun: docs/distributed.md)
//   rill-trace accuracy [--backends LIST] [--scenes LIST] [--size WxH] [--repeats N]
//                       [--one-at-a-time] [--out-dir DIR]
//   rill-trace demo [--scene SCENE] [--size WxH] [--out-dir DIR]
//   rill-trace info
//
// SCENE is a JSON scene file, an OBJ file (framed by a default camera, lit from the eye) or
// builtin:NAME. Exit status: 0 on success, 1 on an error (one line on stderr), 2 on bad
// options.
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <nlohmann/json.hpp>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <regex>
#include <sstream>

#include "AccuracyBench.h"
#include "FrameSequence.h"
#include "distributed/Launch.h"
#include "distributed/SceneHash.h"
#if RILL_HAVE_MPI
#include "distributed/Farm.h"
#include "distributed/MpiSession.h"
#endif
#include "rill/Stopwatch.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Pose.h"
#include "rill/rt/scene/Scene.h"

namespace {

using Clock = std::chrono::steady_clock;

// A number option's check. CLI::Range says "Value x not in range 0 to 64" for a word, as if x
// were a number: this says that it is not one, and else whether it is out of range.
CLI::Validator number_in(double lo, double hi, bool integer) {
  auto text = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        char* end = nullptr;
        errno = 0;
        const double v = integer ? static_cast<double>(std::strtoll(s.c_str(), &end, 10))
                                 : std::strtod(s.c_str(), &end);
        if (s.empty() || end == s.c_str() || *end != '\0' || errno == ERANGE || v != v)
          return "'" + rt::clipped(s) + "' is not " + (integer ? "an integer" : "a number");
        if (v < lo || v > hi) return s + " is out of range (" + text(lo) + " to " + text(hi) + ")";
        return {};
      },
      std::string(integer ? "INT" : "NUMBER") + " in [" + text(lo) + " - " + text(hi) + "]");
}

// A file option's check: an empty name would otherwise read as the option not given.
CLI::Validator file_name() {
  return CLI::Validator(
      [](std::string& s) -> std::string { return s.empty() ? "an empty file name" : ""; }, "FILE");
}

// A setting's check where an empty value would otherwise read as the option not given.
CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& s) -> std::string { return s.empty() ? "an empty value" : ""; }, "");
}

// Where a frame's interpolated camera comes from, for its errors: the scene file and the
// camera keys around the frame's time (keys that are each fine can still interpolate to a
// degenerate view, eye on look_at).
std::string frame_camera_where(const std::string& scene_path, const rt::Scene& s, int frame) {
  const double t = s.animation.time.time_of(frame);
  const auto& keys = s.animation.camera.keys;
  size_t i = 0;
  while (i + 1 < keys.size() && keys[i + 1].time <= t) ++i;
  std::string from = "camera.keys[" + std::to_string(i) + "]";
  if (i + 1 < keys.size() && keys[i].time < t)
    from = "between camera.keys[" + std::to_string(i) + "] and [" + std::to_string(i + 1) + "]";
  char time[32];
  std::snprintf(time, sizeof time, "%g", t);
  return scene_path + ": the camera at frame " + std::to_string(frame) + " (time " + time + ", " +
         from + ")";
}

using rill::ms_since;

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

void parse_size(const std::string& s, int& w, int& h) {
  char x = 0;
  long a = 0, b = 0;
  char tail[2];
  if (std::sscanf(s.c_str(), "%ld%c%ld%1s", &a, &x, &b, tail) != 3 || (x != 'x' && x != 'X'))
    throw rt::SceneError("--size expects WxH, e.g. 512x512 (got '" + s + "')");
  if (a < 1 || b < 1 || a > 16384 || b > 16384 || a * b > (1l << 25))
    throw rt::SceneError("--size " + s +
                         " is out of range (1..16384 per side, at most 33554432 pixels)");
  w = static_cast<int>(a);
  h = static_cast<int>(b);
}

int parse_grid(const std::string& s) {
  if (s.empty() || s == "auto") return 0;
  char* end = nullptr;
  long v = std::strtol(s.c_str(), &end, 10);
  if (end == s.c_str() || *end != '\0' || v < 1 || v > 512)
    throw rt::SceneError("--grid expects 'auto' or a number of voxels per axis in 1..512 (got '" +
                         s + "')");
  return static_cast<int>(v);
}

std::vector<float> to_float(const std::vector<int32_t>& v) {
  std::vector<float> f(v.size());
  for (size_t i = 0; i < v.size(); ++i) f[i] = static_cast<float>(v[i]);
  return f;
}

nlohmann::json split_json(const rt::FrameTimes& t) {
  return {{"setup", t.setup},           {"launch", t.launch}, {"kernel", t.kernel},
          {"accumulate", t.accumulate}, {"reduce", t.reduce}, {"read_back", t.read_back}};
}

// What rill-trace is doing, for the message when memory runs out ("out of memory while
// building the grid 512x512x512").
thread_local std::string g_doing = "starting";  // per thread: frames are written on their own

// Everything a render needs before its first frame: the scene with the command line's changes,
// its grid, the tracer and the settings. Each rank of a distributed render makes its own.
// Built in place and never moved (the tracer was made from the scene and grid beside it).
struct Prepared {
  rt::Scene scene;
  rt::Grid grid;
  rt::TracerOptions knobs;
  std::unique_ptr<rt::Tracer> tracer;
  rt::RenderSettings rs;
  rill::Accuracy acc = rill::Accuracy::Strict;
  std::string out;  // the PNG: --out, or a default name when no output is named
  double load_ms = 0, setup_ms = 0;
};

// Warnings go to stderr when `say` (rank 0 of a distributed render; every single process).
std::unique_ptr<Prepared> prepare(const RenderOptions& o, bool say = true) {
  auto p = std::make_unique<Prepared>();
  g_doing = "loading " + rt::clipped(o.scene);
  if (o.strategy != "megakernel" && o.strategy != "multipass")
    throw rt::SceneError("--strategy expects megakernel or multipass (got '" + o.strategy + "')");
  const rt::MegakernelLoop loop = rt::parse_megakernel_loop(o.loop);  // before the slow steps
  p->acc = rill::parse_accuracy(o.accuracy);
  const auto t_load = Clock::now();
  rt::InputOptions input;
  input.strict = o.strict_input;
  input.allow_empty = o.allow_empty;
  p->scene = rt::load_scene(o.scene, input);
  rt::Scene& scene = p->scene;
  if (!o.size.empty()) parse_size(o.size, scene.width, scene.height);
  if (o.max_depth >= 0) scene.options.max_depth = o.max_depth;
  if (o.spp > 0) scene.options.spp = o.spp;
  if (!o.grid.empty()) scene.options.grid = parse_grid(o.grid);
  if (!o.subgrids.empty()) scene.options.subgrid_min = rt::parse_subgrid_min(o.subgrids);
  if (!o.light_buffer.empty()) scene.options.light_buffer = rt::parse_light_buffer(o.light_buffer);
  if (!o.grid_density.empty()) scene.options.grid_density = rt::parse_grid_density(o.grid_density);
  if (o.max_depth > 64) throw rt::SceneError("--max-depth must be in 0..64");
  if (o.spp > 4096) throw rt::SceneError("--spp must be in 1..4096");
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
  p->knobs.triangle = rt::parse_triangle_test(o.triangle);
  p->knobs.offset = rt::parse_self_intersection(o.offset);
  p->knobs.traversal = rt::parse_traversal(o.traversal);
  g_doing = "uploading the scene and grid (" + std::to_string(p->grid.voxel_count()) +
            " voxels) and building the light buffer";
  p->tracer = std::make_unique<rt::Tracer>(scene, p->grid, p->knobs);
  p->setup_ms = ms_since(t_setup);
  if (const std::string& why = p->tracer->light_buffer().skipped; !why.empty()) {
    const std::string w = "no light buffer (" + why + "): shadow rays walk the grid";
    if (say) std::fprintf(stderr, "rill-trace: warning: %s\n", w.c_str());
    scene.warnings.push_back(w);
  }

  rt::RenderSettings& rs = p->rs;
  rs.backend = o.backend;
  rs.accuracy = p->acc;
  rs.strategy = o.strategy == "multipass" ? rt::Strategy::Multipass : rt::Strategy::Megakernel;
  rs.loop = loop;
  rs.width = scene.width;
  rs.height = scene.height;
  if (o.masking != "on" && o.masking != "off")
    throw rt::SceneError("--masking expects on or off (got '" + o.masking + "')");
  rs.wait_threshold = o.wait_threshold;
  rs.masking = o.masking == "on";
  // Only what is written comes back from the device (the PNG: 8-bit, encoded there).
  p->out = o.out;
  if (p->out.empty() && o.pfm.empty() && o.depth.empty() && o.prim.empty() && o.normal.empty())
    p->out = (scene.name.empty() ? std::string("render") : scene.name) + ".png";
  rs.outputs.rgb8 = !p->out.empty();
  rs.outputs.color = !o.pfm.empty();
  rs.outputs.depth = !o.depth.empty();
  rs.outputs.prim = !o.prim.empty();
  rs.outputs.normal = !o.normal.empty();
  return p;
}

// An output's name for one frame, or for a partial render ("x.png" -> "x.partial.png").
using NameOf = std::function<std::string(const std::string&)>;

// Writes the outputs asked for from a render, each under name(its path) (a partial render
// writes beside the names asked for); returns what it wrote.
std::vector<std::string> write_outputs(
    const RenderOptions& o, const Prepared& p, const rt::RenderResult& r,
    const NameOf& name = [](const std::string& s) { return s; }) {
  g_doing = "writing the outputs";
  std::vector<std::string> written;
  auto pfm = [&](const std::string& path, const auto& data) {
    if (path.empty()) return;
    rt::write_pfm(name(path), r.width, r.height, data);
    written.push_back(name(path));
  };
  if (!p.out.empty()) {
    rt::write_png_rgb8(name(p.out), r.width, r.height, r.rgb8);
    written.push_back(name(p.out));
  }
  pfm(o.pfm, r.color);
  pfm(o.depth, r.depth);
  if (!o.prim.empty()) pfm(o.prim, to_float(r.prim));
  pfm(o.normal, r.normal);
  return written;
}

// The --stats-json fields a distributed render shares with a single-process one.
// width x height images, rays traced over all of them.
nlohmann::json stats_json(const RenderOptions& o, const Prepared& p, int width, int height,
                          int64_t rays) {
  const rt::Scene& scene = p.scene;
  const rt::Grid& grid = p.grid;
  nlohmann::json j;
  j["scene"] = o.scene;
  j["triangles"] = scene.triangle_count();
  j["width"] = width;
  j["height"] = height;
  j["backend"] = o.backend;
  j["accuracy"] = o.accuracy;
  j["strategy"] = o.strategy;
  if (o.strategy == "megakernel")
    j["megakernel_loop"] = rt::megakernel_loop_name(rt::megakernel_loop_for(p.rs.loop, o.backend));
  j["knobs"] = p.knobs.str();
  j["spp"] = scene.options.spp;
  j["max_depth"] = scene.options.max_depth;
  j["features"] = p.tracer->features().str();
  j["grid"] = {{"resolution", {grid.res.x, grid.res.y, grid.res.z}},
               {"density", scene.options.grid_density},
               {"subgrids", grid.subgrids},
               {"references", grid.elements.size()},
               {"triangles", grid.usable},
               {"degenerate", grid.degenerate},
               {"non_finite", grid.non_finite}};
  const rt::LightBufferStats& lb = p.tracer->light_buffer();
  j["light_buffer"] = {{"resolution", lb.res},
                       {"entries", lb.entries},
                       {"fallback_cells", lb.fallback_cells},
                       {"build_ms", lb.build_ms},
                       {"skipped", lb.skipped}};
  j["warnings"] = scene.warnings;
  j["rays"] = rays;
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
  if (!f) throw rt::SceneError("cannot write " + path);
}

// The notes after the outputs (unless --quiet): what was written, and scene trouble.
void print_notes(const RenderOptions& o, const Prepared& p,
                 const std::vector<std::string>& written) {
  if (o.quiet) return;
  for (const auto& w : written) std::printf("wrote %s\n", w.c_str());
  glm::vec3 lo, hi;
  if (rt::scene_bounds(p.scene, lo, hi)) {
    // In double: the float length of a 1e20-unit box overflows.
    const double size = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
    if (size < 1e-10f || size > 1e10f)
      std::printf(
          "note: the scene is %g units across; the intersection test's cubic terms underflow "
          "(GLSL flushes them) or overflow outside about 1e-10..1e10\n",
          static_cast<double>(size));
  }
  if (p.grid.degenerate + p.grid.non_finite > 0)
    std::printf("note: %zu degenerate and %zu non-finite triangles are never hit\n",
                p.grid.degenerate, p.grid.non_finite);
}

// One frame of a sequence (--frames): where it is in time, what moving its objects cost
// (Tracer::set_time) and its trace time.
struct FrameStats {
  int frame = 0;
  double time = 0;
  rt::FrameUpdate update;
  double trace_ms = 0, compile_ms = 0;
  int64_t compiles = 0;  // kernels compiled for it (misses of Rill's in-process kernel cache)
};

nlohmann::json frames_json(const std::vector<FrameStats>& frames, const rt::Features& f) {
  nlohmann::json a = nlohmann::json::array();
  for (const FrameStats& s : frames) {
    nlohmann::json j = {{"frame", s.frame},
                        {"time", s.time},
                        {"trace_ms", s.trace_ms},
                        {"compile_ms", s.compile_ms},
                        {"kernels_compiled", s.compiles}};
    if (f.dynamic)
      j["update"] = {
          {"pose_ms", s.update.pose_ms},         {"bvh_ms", s.update.bvh_ms},
          {"upload_ms", s.update.upload_ms},     {"rebuilt", s.update.rebuilt},
          {"moving_triangles", s.update.moving}, {"bvh_nodes", s.update.bvh_nodes},
          {"bvh_depth", s.update.bvh_depth},     {"uploaded_triangles", s.update.uploaded}};
    a.push_back(j);
  }
  return a;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// "48 frames (0..47): trace median 12.3 ms; BVH rebuilt, median 0.4 ms (600 moving
// triangles); upload 0.2 ms; compiled once".
void print_frames_summary(const std::vector<FrameStats>& frames) {
  std::vector<double> trace, bvh, upload;
  bool recompiled = false, rebuilt = false;
  for (size_t i = 0; i < frames.size(); ++i) {
    trace.push_back(frames[i].trace_ms);
    bvh.push_back(frames[i].update.bvh_ms);
    upload.push_back(frames[i].update.upload_ms);
    rebuilt = rebuilt || frames[i].update.rebuilt;
    recompiled = recompiled || (i > 0 && frames[i].compiles > 0);
  }
  std::printf(
      "%zu frame%s (%d..%d): trace median %.2f ms; BVH %s median %.3f ms (%zu moving "
      "triangles), upload median %.3f ms; %s\n",
      frames.size(), frames.size() == 1 ? "" : "s", frames.front().frame, frames.back().frame,
      median(trace), rebuilt ? "rebuilt," : "refitted,", median(bvh), frames.back().update.moving,
      median(upload),
      recompiled ? "kernels recompiled after the first frame" : "kernels compiled once");
}

rt::BvhUpdate parse_bvh_update_option(const std::string& s) {
  try {
    return rt::parse_bvh_update(s);
  } catch (const std::invalid_argument& e) {
    throw rt::SceneError(std::string("--bvh: ") + e.what());
  }
}

// What --frames asks of a render (FrameSequence.h): which frames, how the BVH follows the
// moving objects, and each frame's output names. Checks that every output has a frame number
// when there are several frames, and --video (and, with check_tools, that ffmpeg is there);
// sets a numbered default --out for a sequence.
struct FramePlan {
  trace_cli::FrameSpan span;  // frame 0 alone without --frames
  bool animated = false;
  bool sequence = false;  // --frames given: the names carry frame numbers
  rt::BvhUpdate bvh_update = rt::BvhUpdate::Rebuild;
  // The output name of path for a frame.
  NameOf file(int frame) const {
    return [sequence = sequence, frame](const std::string& path) {
      return sequence ? trace_cli::frame_path(path, frame) : path;
    };
  }
};

FramePlan plan_frames(const RenderOptions& o, Prepared& p, bool check_tools = true) {
  const rt::Scene& scene = p.scene;
  FramePlan plan;
  plan.animated = scene.animation.animated();
  plan.sequence = !o.frames.empty();
  plan.span = plan.sequence ? trace_cli::parse_frames(o.frames, scene.animation.time, plan.animated)
                            : trace_cli::FrameSpan{};
  plan.bvh_update = parse_bvh_update_option(o.bvh);
  const trace_cli::FrameSpan& span = plan.span;
  if (o.out.empty() && o.pfm.empty() && o.depth.empty() && o.prim.empty() && o.normal.empty() &&
      span.count() > 1)
    p.out = (scene.name.empty() ? std::string("render") : scene.name) + "-%04d.png";
  const std::pair<std::string, const std::string*> outputs[] = {{"--out", &p.out},
                                                                {"--pfm", &o.pfm},
                                                                {"--depth", &o.depth},
                                                                {"--prim", &o.prim},
                                                                {"--normal", &o.normal}};
  for (const auto& [option, path] : outputs) {
    if (path->empty()) continue;
    const bool numbered = plan.sequence && trace_cli::has_frame_number(*path, option);
    if (span.count() > 1 && !numbered)
      throw rt::SceneError("--frames " + o.frames + " writes " + std::to_string(span.count()) +
                           " frames: " + option + " needs a frame number, such as frame-%04d" +
                           std::filesystem::path(*path).extension().string());
  }
  // Two options naming one file: the later write would silently replace the earlier one.
  {
    const std::pair<std::string, const std::string*> files[] = {
        {"--out", &p.out},      {"--pfm", &o.pfm},       {"--depth", &o.depth},
        {"--prim", &o.prim},    {"--normal", &o.normal}, {"--stats-json", &o.stats_json},
        {"--source", &o.source}};
    std::map<std::string, std::string> seen;  // normalized path -> option
    for (const auto& [option, path] : files) {
      if (path->empty() || *path == "/dev/null") continue;
      const std::string key = std::filesystem::path(*path).lexically_normal().string();
      auto [it, fresh] = seen.emplace(key, option);
      if (!fresh)
        throw rt::SceneError(it->second + " and " + option + " both name " + *path +
                             ": one would overwrite the other");
    }
  }
  if (!o.video.empty()) {
    if (p.out.empty() || !plan.sequence)
      throw rt::SceneError("--video makes a video of the frames' PNGs: give --frames and --out");
    if (std::string why = check_tools ? trace_cli::video_tool_missing() : std::string();
        !why.empty())
      throw rt::SceneError(why);
  }
  return plan;
}

#if RILL_HAVE_MPI
int render_distributed(const RenderOptions& o);
#endif

int render(RenderOptions o) {
  // --threads: the CPU backends' worker threads (oneTBB), for the whole render.
  std::optional<tbb::global_control> threads;
  if (o.threads > 0)
    threads.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(o.threads));
  o.backend = rt::distributed::rank_backend(o.backend, o.backend_given);
  // Started by mpirun as one of several processes: one image over all of them.
  const int launched = rt::distributed::launcher_world_size();
  if (launched > 1) {
#if RILL_HAVE_MPI
    return render_distributed(o);
#else
    throw rt::SceneError("started by an MPI launcher as one of " + std::to_string(launched) +
                         " processes, but this rill-trace was built without MPI (RILL_MPI=OFF "
                         "or no libopenmpi-dev at build time): each would render the whole "
                         "image; rebuild with MPI, or run it without mpirun");
#endif
  }
  if (o.distribute)
    throw rt::SceneError(
        "--distribute: not started by an MPI launcher as one of several processes; run "
        "'mpirun -np N rill-trace render ...' with N >= 2 (docs/distributed.md)");
  rt::distributed::use_device(o.backend, rt::distributed::rank_device(o.device, 0));
  std::unique_ptr<Prepared> prepared = prepare(o);
  Prepared& p = *prepared;
  const rt::Scene& scene = p.scene;
  const rt::Grid& grid = p.grid;
  rt::Tracer& tracer = *p.tracer;
  const rt::RenderSettings& rs = p.rs;
  const double load_ms = p.load_ms;

  const FramePlan plan = plan_frames(o, p);
  const trace_cli::FrameSpan& span = plan.span;
  const bool animated = plan.animated;
  const rt::BvhUpdate bvh_update = plan.bvh_update;
  auto frame_file = [&plan](int frame) { return plan.file(frame); };

  const auto t_render = Clock::now();
  g_doing = "rendering " + std::to_string(rs.width) + "x" + std::to_string(rs.height) + " on " +
            o.backend;
  // A dynamic scene's first frame: its objects and camera where they are then.
  const double first_time = animated ? scene.animation.time.time_of(span.first) : 0.0;
  const int64_t misses_before = rill::kernel_cache_stats().misses;
  std::vector<FrameStats> frame_stats(1);
  if (animated) frame_stats[0].update = tracer.set_time(first_time, bvh_update);
  const rt::Camera first_camera = rt::camera_at(scene, first_time);
  // Keys that are each fine can still interpolate to a degenerate view (eye on look_at).
  if (animated) rt::check_camera(first_camera, frame_camera_where(o.scene, scene, span.first));
  rt::RenderResult r = tracer.render(rs, first_camera);
  const double render_ms = ms_since(t_render);
  const double compile_ms = p.setup_ms + (render_ms - r.trace_ms);
  // Of that, the compile() calls (about 0 from a kernel cache); the rest is set-up: uploading
  // the scene and grid, and the warm-up launch (Megakernel::render).
  const double kernels_ms = std::min(r.stages.compile_ms, compile_ms);

  // --bench-frames: the same frame again, each timed as the user's program would see it
  // (Tracer::render from call to return: launch, kernel, reductions, read-back, host work).
  std::vector<double> frame_ms;
  std::vector<rt::FrameTimes> frame_times;
  rt::RenderResult frame;  // one result for every frame: its image memory is reused
  for (int f = 0; f < o.bench_frames; ++f) {
    const auto t_frame = Clock::now();
    tracer.render(rs, first_camera, frame);
    frame_ms.push_back(ms_since(t_frame));
    frame_times.push_back(frame.times);
  }
  std::vector<double> sorted = frame_ms;
  std::sort(sorted.begin(), sorted.end());
  const double median_ms = sorted.empty() ? 0.0 : sorted[sorted.size() / 2];
  // The median of each step over the frames (they need not add up to the median frame).
  auto median_of = [&](double rt::FrameTimes::*step) {
    std::vector<double> v;
    for (const rt::FrameTimes& t : frame_times) v.push_back(t.*step);
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  rt::FrameTimes median_split;
  for (auto step :
       {&rt::FrameTimes::setup, &rt::FrameTimes::launch, &rt::FrameTimes::kernel,
        &rt::FrameTimes::accumulate, &rt::FrameTimes::reduce, &rt::FrameTimes::read_back})
    median_split.*step = median_of(step);

  std::vector<std::string> written = write_outputs(o, p, r, frame_file(span.first));
  frame_stats[0].frame = span.first;
  frame_stats[0].time = first_time;
  frame_stats[0].trace_ms = r.trace_ms;
  frame_stats[0].compile_ms = r.compile_ms;
  frame_stats[0].compiles = rill::kernel_cache_stats().misses - misses_before;
  // --frames: the other frames, back to back through the same tracer (compiled kernels, the
  // grid and the static arrays stay; Tracer::set_time moves the objects and their BVH).
  trace_cli::Progress progress(span.count(), o.quiet);
  progress.update(1, r.trace_ms);
  for (int k = span.first + 1; k <= span.last; ++k) {
    FrameStats fs;
    fs.frame = k;
    fs.time = animated ? scene.animation.time.time_of(k) : 0.0;
    g_doing = "rendering frame " + std::to_string(k);
    const int64_t misses = rill::kernel_cache_stats().misses;
    if (animated) fs.update = tracer.set_time(fs.time, bvh_update);
    const rt::Camera camera = rt::camera_at(scene, fs.time);
    rt::check_camera(camera, frame_camera_where(o.scene, scene, k));
    tracer.render(rs, camera, frame);
    fs.trace_ms = frame.trace_ms;
    fs.compile_ms = frame.compile_ms;
    fs.compiles = rill::kernel_cache_stats().misses - misses;
    g_doing = "writing frame " + std::to_string(k);
    for (const std::string& w : write_outputs(o, p, frame, frame_file(k)))
      if (written.size() < 8) written.push_back(w);
    frame_stats.push_back(fs);
    progress.update(k - span.first + 1, fs.trace_ms);
  }
  progress.finish();
  if (!o.video.empty()) {
    g_doing = "writing the video";
    trace_cli::write_video(p.out, span.first, scene.animation.time.fps, o.video);
    written.push_back(o.video);
  }
  if (!o.source.empty()) {
    std::ofstream f(o.source);
    f << tracer.source(o.backend, p.acc, p.rs.loop, p.rs.outputs, scene.options.spp);
    if (!f) throw rt::SceneError("cannot write " + o.source);
  }

  const double rays_per_s =
      r.trace_ms > 0 ? static_cast<double>(r.rays) / (r.trace_ms * 1e-3) : 0.0;
  if (!o.stats_json.empty()) {
    nlohmann::json j = stats_json(o, p, r.width, r.height, r.rays);
    j["launches"] = r.launches;
    if (o.strategy == "multipass") {
      j["wait_threshold"] = rs.wait_threshold;
      j["masking"] = rs.masking;
      nlohmann::json passes = nlohmann::json::array();
      for (const rt::PassStats& ps : r.passes)
        passes.push_back({{"name", ps.name},
                          {"calls", ps.calls},
                          {"processed", ps.processed},
                          {"written", ps.written},
                          {"ms", ps.ms}});
      j["passes"] = passes;
    }
    j["rays_per_second"] = rays_per_s;
    j["compiled_from_cache"] = r.from_cache;
    // Each kernel's Kernel::info(), summed over the render's kernels (multipass compiles its
    // nine at once, so the sum exceeds time_ms.compile).
    j["compile_stages_ms"] = {{"kernels", r.kernels},
                              {"origin", rill::origin_name(r.stages.origin)},
                              {"capture", r.stages.capture_ms},
                              {"optimize", r.stages.optimize_ms},
                              {"codegen", r.stages.codegen_ms},
                              {"backend_compile", r.stages.backend_compile_ms},
                              {"driver_finish", r.stages.driver_finish_ms},
                              {"compile", r.stages.compile_ms}};
    if (!frame_ms.empty())
      j["bench_frames"] = {{"frames", frame_ms.size()},
                           {"frame_ms", frame_ms},
                           {"median_ms", median_ms},
                           {"min_ms", sorted.front()},
                           {"max_ms", sorted.back()},
                           {"fps", median_ms > 0 ? 1000.0 / median_ms : 0.0},
                           {"device", rill::backend(o.backend).description()},
                           {"median_split_ms", split_json(median_split)}};
    j["time_ms"] = {
        {"load", load_ms},       {"grid_build", grid.build_ms},
        {"compile", kernels_ms}, {"setup", compile_ms - kernels_ms},
        {"trace", r.trace_ms},   {"total", load_ms + grid.build_ms + compile_ms + r.trace_ms}};
    // The first frame's trace time, step by step (Tracer.h, FrameTimes).
    j["trace_split_ms"] = split_json(r.times);
    if (animated || span.count() > 1) j["frames"] = frames_json(frame_stats, tracer.features());
    write_json(o.stats_json, j);
  }
  print_notes(o, p, written);
  if (frame_stats.size() > 1 || animated) print_frames_summary(frame_stats);
  if (!frame_ms.empty())
    std::printf(
        "%zu frames of %dx%d after the first: median %.2f ms (%.1f fps), min %.2f ms, max "
        "%.2f ms; %s\n",
        frame_ms.size(), r.width, r.height, median_ms, median_ms > 0 ? 1000.0 / median_ms : 0.0,
        sorted.front(), sorted.back(), rill::backend(o.backend).description().c_str());
  if (!frame_ms.empty()) {
    // The kernel's own time within the launch, where the backend can time it.
    char kernel[64] = "";
    if (median_split.kernel >= 0)
      std::snprintf(kernel, sizeof kernel, " (kernel %.3f ms)", median_split.kernel);
    std::printf(
        "  median per step: set-up %.3f ms, launch %.3f ms%s, accumulate %.3f ms, reduce %.3f "
        "ms, read-back %.3f ms\n",
        median_split.setup, median_split.launch, kernel, median_split.accumulate,
        median_split.reduce, median_split.read_back);
  }
  if (o.stats)
    std::printf(
        "compile stages, summed over %d kernel(s) (%s): capture %.1f ms, optimize %.1f ms, "
        "codegen %.1f ms, backend compile %.1f ms, driver finish %.1f ms; compile() calls %.1f "
        "ms\n",
        r.kernels, rill::origin_name(r.stages.origin), r.stages.capture_ms, r.stages.optimize_ms,
        r.stages.codegen_ms, r.stages.backend_compile_ms, r.stages.driver_finish_ms,
        r.stages.compile_ms);
  if (o.stats && o.strategy == "multipass") {
    std::printf("%-14s %8s %14s %14s %10s   (masking %s, wait threshold %g)\n", "pass", "calls",
                "processed", "written", "ms", rs.masking ? "on" : "off", rs.wait_threshold);
    for (const rt::PassStats& ps : r.passes)
      std::printf("%-14s %8lld %14lld %14lld %10.2f\n", ps.name.c_str(),
                  static_cast<long long>(ps.calls), static_cast<long long>(ps.processed),
                  static_cast<long long>(ps.written), ps.ms);
  }
  std::printf(
      "rill-trace: %s, %zu triangles, %dx%d, %s %s%s, grid %dx%dx%d: %.3f Mrays/s (%lld rays); "
      "load %.1f ms, grid build %.1f ms, compile %.1f ms%s, set-up %.1f ms, trace %.1f ms%s\n",
      scene.name.c_str(), scene.triangle_count(), r.width, r.height, o.backend.c_str(),
      o.accuracy.c_str(), o.strategy == "multipass" ? " multipass" : "", grid.res.x, grid.res.y,
      grid.res.z, rays_per_s * 1e-6, static_cast<long long>(r.rays), load_ms, grid.build_ms,
      kernels_ms, r.from_cache ? " (cached)" : "", compile_ms - kernels_ms, r.trace_ms,
      o.strategy == "multipass" ? (" (" + std::to_string(r.launches) + " launches)").c_str() : "");
  return 0;
}

#if RILL_HAVE_MPI
// What besides the scene decides the pixels, for the scene hash (SceneHash.h): size, samples
// and depth are in the scene by now.
std::string pixel_settings(const RenderOptions& o, const Prepared& p) {
  return "accuracy " + o.accuracy + "; knobs " + p.knobs.str();
}

// The outputs asked for, in the order write_outputs writes them.
std::vector<std::string> output_paths(const RenderOptions& o, const Prepared& p) {
  std::vector<std::string> paths;
  for (const std::string* path : {&p.out, &o.pfm, &o.depth, &o.prim, &o.normal})
    if (!path->empty()) paths.push_back(*path);
  return paths;
}

// The note beside a frame's partial outputs: NAME.partial.txt after its first output.
std::string partial_note_path(const RenderOptions& o, const Prepared& p, const NameOf& file) {
  const std::string first = rt::distributed::partial_name(file(output_paths(o, p).front()));
  const size_t dot = first.find_last_of('.');
  return (dot == std::string::npos ? first : first.substr(0, dot)) + ".txt";
}

// Writes a frame's tiles so far as partial outputs (NAME.partial.EXT, each NAME the frame's
// output name by `file`), and the note: what is in it and what is not, and why. Returns what
// it wrote.
std::vector<std::string> write_partial(const RenderOptions& o, const Prepared& p,
                                       const rt::distributed::FarmResult& R,
                                       const rt::distributed::FramePart& part, const NameOf& file,
                                       const std::string& why) {
  std::vector<std::string> written = write_outputs(o, p, part.image, [&](const std::string& path) {
    return rt::distributed::partial_name(file(path));
  });
  const std::string note = partial_note_path(o, p, file);
  std::ostringstream f;
  f << "rill-trace: a partial render of " << o.scene;
  if (R.frames > 1 || !o.frames.empty()) f << ", frame " << part.frame;
  f << ", " << part.image.width << "x" << part.image.height << " in " << part.tiles << " tiles of "
    << o.tile << " pixels\n"
    << "why: " << why << "\n"
    << "tiles in the image: " << part.tiles_done << " of " << part.tiles
    << "; the others are black, depth +inf, prim -1\n";
  for (const rt::distributed::RankReport& r : R.ranks)
    f << "rank " << r.rank << " on " << r.host << " (" << r.backend << "): " << r.tiles << " tiles"
      << (R.frames > 1 ? " of the sequence" : "") << (r.lost.empty() ? "" : ", lost: " + r.lost)
      << "\n";
  f << "missing tiles (x y width height):\n";
  for (const rt::distributed::Tile& t : part.missing)
    f << t.x << " " << t.y << " " << t.width << " " << t.height << "\n";
  rt::write_output_file(note, [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << f.str();
    if (!out) throw rt::SceneError("cannot write " + note);
  });
  written.push_back(note);
  return written;
}

// Rank 0's record of a distributed render, frame by frame as they complete.
struct DistributedFrames {
  std::vector<std::string> written;
  struct Done {
    int frame = 0;
    double time = 0, done_ms = 0;  // its time in the animation; complete this long after start
    int64_t rays = 0;
  };
  std::vector<Done> done;
  int64_t rays = 0;
  int width = 0, height = 0;
};

int finish_distributed(const RenderOptions& o, Prepared& p, const FramePlan& plan,
                       const rt::distributed::FarmResult& R, const DistributedFrames& frames,
                       rt::distributed::MpiSession& mpi, Clock::time_point t_start);

// --tail-tile: as given, or half of --tile (tiles under 16 pixels are not cut).
int tail_tile_of(const RenderOptions& o) {
  return o.tail_tile >= 0 ? o.tail_tile : (o.tile >= 16 ? o.tile / 2 : 0);
}

// One image, or the frames of --frames, over every rank of the MPI job (distributed/Farm.h,
// docs/distributed.md).
int render_distributed(const RenderOptions& o) {
  namespace dist = rt::distributed;
  if (o.bench_frames > 0)
    throw rt::SceneError("--bench-frames times one process; it does not run under mpirun");
  dist::MpiSession mpi;
  const bool root = mpi.rank() == 0;
  const std::string who = "rank " + std::to_string(mpi.rank()) + " on " + mpi.host();
  const auto t_start = Clock::now();
  std::unique_ptr<Prepared> prepared;
  FramePlan plan;
  DistributedFrames frames;
  std::optional<dist::FarmResult> result;
  // What the farm's render thread uses, here rather than in the try block: after a signal
  // that thread may still be in a tile while rank 0 writes the partial outputs.
  rt::RenderSettings rs;
  int posed = -1;  // the frame the scene is posed at
  rt::Camera camera;
  std::function<rt::RenderResult(const dist::Tile&)> render_tile;
  try {
    dist::use_device(o.backend, dist::rank_device(o.device, mpi.local_rank()));
    dist::FarmOptions fo;
    fo.tile = o.tile;
    fo.tail_tile = tail_tile_of(o);
    fo.rank_timeout = o.rank_timeout;
    fo.tile_timeout = o.tile_timeout;
    fo.progress = root && o.progress;
    fo.checkpoint = o.checkpoint;
    dist::Farm farm(mpi, fo);
    farm.start(
        [&] {
          prepared = prepare(o, root);
          plan = plan_frames(o, *prepared, root);  // ffmpeg for --video: rank 0's
          // Every camera of the sequence, before any tile: a bad one stops the start.
          const rt::Scene& scene = prepared->scene;
          for (int k = plan.span.first; plan.animated && k <= plan.span.last; ++k)
            rt::check_camera(rt::camera_at(scene, scene.animation.time.time_of(k)),
                             frame_camera_where(o.scene, scene, k));
          return dist::scene_hash(scene, pixel_settings(o, *prepared));
        },
        o.backend);
    // A worker that failed to load has no settings: it renders nothing, and waits for rank 0
    // to end the job.
    if (prepared) {
      rs = prepared->rs;
      camera = prepared->scene.camera;
    }
    // A tile of another frame than the one posed moves the scene there first (on the farm's
    // render thread, the only one that calls this).
    render_tile = [&](const dist::Tile& t) {
      const rt::Scene& scene = prepared->scene;
      if (plan.animated && t.frame != posed) {
        const double time = scene.animation.time.time_of(t.frame);
        prepared->tracer->set_time(time, plan.bvh_update);
        camera = rt::camera_at(scene, time);
        posed = t.frame;
      }
      rt::RenderSettings s = rs;
      s.window = {t.x, t.y, t.width, t.height};
      return prepared->tracer->render(s, camera);
    };
    // Rank 0: each frame written as it completes; the frames begun kept on disk as partial
    // outputs while they render, as mpirun may kill rank 0 without warning.
    trace_cli::Progress progress(plan.span.count(), o.quiet || o.progress || !plan.sequence);
    trace_cli::FrameWriter writer;
    auto on_frame = [&](int frame, rt::RenderResult&& image) {
      writer.check();  // a frame that could not be written ends the render now
      const rt::Scene& scene = prepared->scene;
      frames.done.push_back({frame, plan.animated ? scene.animation.time.time_of(frame) : 0.0,
                             ms_since(t_start), image.rays});
      frames.rays += image.rays;
      frames.width = image.width;
      frames.height = image.height;
      for (const std::string& path : output_paths(o, *prepared))
        if (frames.written.size() < 8) frames.written.push_back(plan.file(frame)(path));
      progress.update(static_cast<int>(frames.done.size()), 0);
      // Written beside the farm's loop, which goes on handing out tiles meanwhile.
      writer.post([&, frame, image = std::move(image)] {
        write_outputs(o, *prepared, image, plan.file(frame));
        std::error_code ignored;  // its checkpoints are out of date now
        for (const std::string& path : output_paths(o, *prepared))
          std::filesystem::remove(dist::partial_name(plan.file(frame)(path)), ignored);
        std::filesystem::remove(partial_note_path(o, *prepared, plan.file(frame)), ignored);
      });
    };
    auto checkpoint = [&](const dist::FarmResult& so_far) {
      for (const dist::FramePart& part : so_far.unfinished)
        write_partial(o, *prepared, so_far, part, plan.file(part.frame),
                      "a checkpoint: the render was still running when this was written (it is "
                      "removed when the frame completes)");
    };
    dist::FarmJob job;
    job.width = rs.width;
    job.height = rs.height;
    job.first_frame = plan.span.first;
    job.frames = plan.span.count();
    job.outputs = rs.outputs;
    result = farm.render(job, render_tile, on_frame, checkpoint);
    // mpirun may send SIGTERM again while the frames in hand are written: they and the partial
    // outputs go through it (finish_distributed).
    if (result && result->interrupted) {
      std::signal(SIGTERM, SIG_IGN);
      std::signal(SIGINT, SIG_IGN);
    }
    try {
      writer.finish();
    } catch (const std::exception& e) {
      if (!result || result->complete()) throw;
      // Incomplete anyway: the partial outputs are still worth writing.
      std::fprintf(stderr, "rill-trace: %s\n", e.what());
    }
    progress.finish();
  } catch (const std::exception& e) {
    // Rank 0: a rank failed to load or has another scene (the message names it), or rank 0
    // itself failed. A worker: rank 0 is lost. Either way the job ends here, all of it: the
    // other ranks may be waiting in MPI, or be hung.
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "rill-trace: %s%s\n", root ? "" : (who + ": ").c_str(), msg.c_str());
    std::fflush(stderr);
    if (root) mpi.abort(1);
    std::_Exit(1);
  }
  if (!root) return 0;

  const dist::FarmResult& R = *result;
  try {
    return finish_distributed(o, *prepared, plan, R, frames, mpi, t_start);
  } catch (const std::exception& e) {
    if (!R.must_abort) throw;  // main reports it; MPI_Finalize finds every rank
    std::fprintf(stderr, "rill-trace: %s\n", e.what());
    std::fflush(stderr);
    mpi.abort(1);
  }
}

// Rank 0, every frame back (or the farm ended without some): writes what there is of the
// frames not complete, the video and the stats, and reports.
int finish_distributed(const RenderOptions& o, Prepared& p, const FramePlan& plan,
                       const rt::distributed::FarmResult& R, const DistributedFrames& frames,
                       rt::distributed::MpiSession& mpi, Clock::time_point t_start) {
  namespace dist = rt::distributed;
  if (!R.complete()) {
    // mpirun may send SIGTERM more than once while it ends the job: the partial outputs are
    // written through them (only SIGKILL stops that; the last checkpoint is on disk already).
    if (R.interrupted) {
      std::signal(SIGTERM, SIG_IGN);
      std::signal(SIGINT, SIG_IGN);
    }
    // First the message: when mpirun ends the job, SIGKILL follows SIGTERM within a second,
    // at times within milliseconds.
    const std::string why =
        R.interrupted ? "stopped by a signal: mpirun ends the job when a rank dies, and names the "
                        "rank and its host (mpirun --enable-recovery goes on without it)"
                      : "every rank was lost";
    std::string frames_note;
    if (R.frames > 1)
      frames_note = "; " + std::to_string(R.frames_done) + " of " + std::to_string(R.frames) +
                    " frames are complete and written, " + std::to_string(R.unfinished.size()) +
                    " begun";
    std::fprintf(stderr,
                 "rill-trace: the render is incomplete (%s); writing the %d of %d tiles done as "
                 "partial outputs (NAME.partial.EXT) with a note%s\n",
                 why.c_str(), R.tiles_done, R.tiles, frames_note.c_str());
    std::fflush(stderr);
    std::vector<std::string> written = frames.written;
    for (const dist::FramePart& part : R.unfinished)
      for (const std::string& w : write_partial(o, p, R, part, plan.file(part.frame), why))
        written.push_back(w);
    print_notes(o, p, written);
    std::fflush(stdout);
    if (R.interrupted) std::_Exit(1);  // mpirun is ending the job
    mpi.abort(1);
  }
  std::vector<std::string> written = frames.written;
  if (!o.video.empty()) {
    g_doing = "writing the video";
    trace_cli::write_video(p.out, plan.span.first, p.scene.animation.time.fps, o.video);
    written.push_back(o.video);
  }
  if (!o.source.empty()) {
    std::ofstream f(o.source);
    f << p.tracer->source(o.backend, p.acc, p.rs.loop);
    if (!f) throw rt::SceneError("cannot write " + o.source);
  }
  const double wall_ms = R.wall_ms;
  if (!o.stats_json.empty()) {
    nlohmann::json j = stats_json(o, p, frames.width, frames.height, frames.rays);
    nlohmann::json ranks = nlohmann::json::array();
    for (const dist::RankReport& r : R.ranks)
      ranks.push_back({{"rank", r.rank},
                       {"host", r.host},
                       {"backend", r.backend},
                       {"tiles", r.tiles},
                       {"busy_ms", r.busy_ms},
                       {"lost", r.lost}});
    // [id, rank, ms, x, y, width, height, frame] in the order they came back
    nlohmann::json tile_ms = nlohmann::json::array();
    for (const dist::FarmResult::TileTime& t : R.tile_times)
      tile_ms.push_back(nlohmann::json::array({t.tile.id, t.rank, t.ms, t.tile.x, t.tile.y,
                                               t.tile.width, t.tile.height, t.tile.frame}));
    j["distributed"] = {
        {"ranks", R.ranks.size()},
        {"tile", o.tile},
        {"tiles", R.tiles},
        {"tiles_done", R.tiles_done},
        {"complete", R.complete()},
        {"imbalance", R.imbalance},
        {"per_rank", ranks},
        {"per_tile", tile_ms},
        {"warnings", R.warnings},
        {"tail_tile", tail_tile_of(o)},
        {"gather", {{"tiles", R.gathered}, {"bytes", R.gathered_bytes}, {"ms", R.gather_ms}}}};
    j["time_ms"] = {{"load", p.load_ms},
                    {"grid_build", p.grid.build_ms},
                    {"render", wall_ms},
                    {"total", ms_since(t_start)}};
    if (plan.animated || plan.span.count() > 1) {
      // Frames in the order they completed; tile ids run frame after frame.
      nlohmann::json list = nlohmann::json::array();
      for (const DistributedFrames::Done& d : frames.done)
        list.push_back(
            {{"frame", d.frame}, {"time", d.time}, {"done_ms", d.done_ms}, {"rays", d.rays}});
      j["frames"] = list;
    }
    write_json(o.stats_json, j);
  }
  print_notes(o, p, written);
  if (!o.quiet)
    for (const dist::RankReport& r : R.ranks)
      std::printf("  rank %d on %s (%s): %d tiles, busy %.1f ms%s\n", r.rank, r.host.c_str(),
                  r.backend.c_str(), r.tiles, r.busy_ms, r.lost.empty() ? "" : ", lost");
  const std::string what =
      plan.span.count() > 1 ? std::to_string(plan.span.count()) + " frames of " : std::string();
  std::printf(
      "rill-trace: %s, %zu triangles, %s%dx%d, %s %s, %zu ranks, %d tiles of %d: %lld rays; load "
      "%.1f ms, grid build %.1f ms, render %.1f ms, imbalance %.1f%%\n",
      p.scene.name.c_str(), p.scene.triangle_count(), what.c_str(), frames.width, frames.height,
      o.backend.c_str(), o.accuracy.c_str(), R.ranks.size(), R.tiles, o.tile,
      static_cast<long long>(frames.rays), p.load_ms, p.grid.build_ms, wall_ms,
      R.imbalance * 100.0);
  std::fflush(stdout);
  if (R.must_abort) {
    std::fprintf(stderr,
                 "rill-trace: the image is complete without the lost rank(s); ending the job "
                 "with MPI_Abort, as MPI_Finalize would wait for them\n");
    std::fflush(stderr);
    mpi.abort(3);
  }
  return 0;
}
#endif

int demo(const std::string& scene_spec, const std::string& size, const std::string& out_dir) {
  rt::Scene scene = rt::load_scene(scene_spec);
  if (!size.empty()) parse_size(size, scene.width, scene.height);
  scene.validate();
  rt::Grid grid = rt::build_grid_for(scene);
  rt::Tracer tracer(scene, grid);
  std::printf("rill-trace demo: %s, %zu triangles, %dx%d, grid %dx%dx%d, kernel features: %s\n",
              scene.name.c_str(), scene.triangle_count(), scene.width, scene.height, grid.res.x,
              grid.res.y, grid.res.z, tracer.features().str().c_str());
  std::filesystem::create_directories(out_dir.empty() ? "." : out_dir);
  std::vector<std::pair<std::string, rt::RenderResult>> results;
  for (rill::Backend* b : rill::backends()) {
    if (std::string why = b->unavailable_reason(); !why.empty()) {
      std::printf("  %-7s unavailable: %s\n", b->name().c_str(), why.c_str());
      continue;
    }
    rt::RenderSettings rs;
    rs.backend = b->name();
    rs.width = scene.width;
    rs.height = scene.height;
    const auto t = Clock::now();
    rt::RenderResult r = tracer.render(rs, scene.camera);
    const double total = ms_since(t);
    std::string png = (std::filesystem::path(out_dir.empty() ? "." : out_dir) /
                       ("demo-" + scene.name + "-" + b->name() + ".png"))
                          .string();
    rt::write_png(png, r.width, r.height, r.color);
    std::printf("  %-7s compile %8.1f ms%s  trace %8.1f ms  %7.3f Mrays/s  -> %s\n",
                b->name().c_str(), total - r.trace_ms, r.from_cache ? " (cached)" : "         ",
                r.trace_ms, r.trace_ms > 0 ? static_cast<double>(r.rays) / (r.trace_ms * 1e3) : 0.0,
                png.c_str());
    results.emplace_back(b->name(), std::move(r));
  }
  if (results.empty()) throw rt::SceneError("no backend can run here");
  bool all_same = true;
  for (size_t i = 1; i < results.size(); ++i) {
    const auto& a = results[0].second;
    const auto& b = results[i].second;
    size_t diff = 0;
    for (size_t p = 0; p < a.color.size(); ++p)
      if (std::memcmp(&a.color[p], &b.color[p], sizeof(glm::vec3)) != 0 || a.prim[p] != b.prim[p])
        ++diff;
    std::printf(
        "  %s vs %s: %s\n", results[0].first.c_str(), results[i].first.c_str(),
        diff == 0 ? "bitwise identical" : (std::to_string(diff) + " pixels differ").c_str());
    all_same = all_same && diff == 0;
  }
  if (results.size() > 1)
    std::printf("rill-trace demo: the images are %s\n",
                all_same ? "identical on every backend" : "NOT identical");
  if (!all_same)
    throw rt::SceneError(
        "demo: the backends' images differ (strict mode should make them identical)");
  return 0;
}

int info() {
  std::printf("backends:\n");
  for (rill::Backend* b : rill::backends()) {
    std::string why = b->unavailable_reason();
    std::printf("  %-7s %s  %s\n", b->name().c_str(), why.empty() ? "ok         " : "unavailable",
                why.empty() ? b->description().c_str() : why.c_str());
    if (why.empty())
      std::printf("          accuracy: strict fast%s\n",
                  b->supports(rill::Accuracy::Double) ? " double" : "");
  }
  std::printf("built-in scenes (builtin:NAME):");
  for (const auto& n : rt::builtin_scene_names()) std::printf(" %s", n.c_str());
  std::printf("\n");
  // Defaults as a scene file writes them (docs/scene-format.md): 0.5, or [r, g, b].
  auto value = [](const rt::ShaderParam& p) {
    const rt::ParamValue& v = p.default_value;
    if (p.required) return std::string("(required)");
    char buf[96];
    if (v.kind == rt::ParamValue::Kind::Number)
      std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v.number));
    else
      std::snprintf(buf, sizeof buf, "[%g, %g, %g]", static_cast<double>(v.color.r),
                    static_cast<double>(v.color.g), static_cast<double>(v.color.b));
    return std::string(buf);
  };
  std::printf("surface shaders (a material's \"shader\"; parameter, type, default):\n");
  for (const std::string& name : rt::shader_names()) {
    const rt::SurfaceShader& sh = *rt::find_shader(name);
    std::printf("  %-9s %s\n", name.c_str(), sh.doc.c_str());
    for (const rt::ShaderParam& p : sh.params)
      std::printf("            %-10s %-7s %-16s %s\n", p.name.c_str(), rt::param_type_name(p.type),
                  value(p).c_str(), p.doc.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // Ctrl-C or a kill while an image is written leaves no partial file (OutputFile.h).
  rt::remove_partial_output_on_interrupt();
  CLI::App app{"rill-trace: the Rill ray tracer (one DSL kernel, every backend)"};
  app.require_subcommand(1);
  RenderOptions ro;
  CLI::App* r = app.add_subcommand("render", "render a scene");
  r->add_option("scene", ro.scene, "JSON scene, OBJ file or builtin:NAME")->required();
  r->add_option("--backend", ro.backend, "cpu, simd, opencl, glsl or glsl-compute")
      ->default_str("cpu");
  r->add_option("--accuracy", ro.accuracy, "strict, fast or double")->default_str("strict");
  r->add_option("--size", ro.size, "image size WxH (default: the scene's)")->check(non_empty());
  r->add_option("--out", ro.out, "PNG output (sRGB)")->check(file_name());
  r->add_option("--pfm", ro.pfm, "linear colour as PFM")->check(file_name());
  r->add_option("--depth", ro.depth, "hit distance AOV as PFM (+inf: miss)")->check(file_name());
  r->add_option("--prim", ro.prim, "primitive id AOV as PFM (-1: miss)")->check(file_name());
  r->add_option("--normal", ro.normal, "shading normal AOV as PFM")->check(file_name());
  r->add_option("--max-depth", ro.max_depth, "reflection/refraction bounces")
      ->check(number_in(0, 64, true));
  r->add_option("--spp", ro.spp, "samples per pixel")->check(number_in(1, 4096, true));
  r->add_option("--grid", ro.grid, "voxels per axis, or auto")->check(non_empty());
  r->add_option("--grid-density", ro.grid_density,
                "voxels per triangle of the auto grid, 0.125..256 (default 4; 16 is faster on "
                "the CPU backends for large meshes, at 3.5x the memory)")
      ->check(non_empty());
  r->add_option("--subgrids", ro.subgrids,
                "voxels listing more triangles than this get a subgrid (1..1048576), off, or auto "
                "(default: 12 when the backend runs on the CPU, off on a GPU)")
      ->check(non_empty());
  r->add_option("--light-buffer", ro.light_buffer,
                "shadow rays: cells per edge of each light's direction cube (1..1024), off (walk "
                "the grid), or auto (default: 64 where the scene has shadows)")
      ->check(non_empty());
  r->add_option("--strategy", ro.strategy,
                "megakernel (one kernel, Sh style) or multipass (the thesis's kernel sequence)")
      ->default_str("megakernel");
  r->add_option("--loop", ro.loop,
                "megakernel: one traced ray per loop iteration (ray), or one path segment with "
                "its shadow rays (segment), or auto (default: segment on cpu and simd, ray on "
                "opencl, glsl and glsl-compute). Images do not depend on it")
      ->default_str("auto");
  r->add_option("--stats-json", ro.stats_json, "write timings and counts as JSON")
      ->check(file_name());
  r->add_option("--source", ro.source, "write the generated kernel source")->check(file_name());
  r->add_flag("--quiet", ro.quiet, "print only the stats line");
  r->add_option("--threads", ro.threads,
                "worker threads of the CPU backends (cpu, simd); default: one per core. Images "
                "do not depend on it")
      ->check(number_in(1, 4096, true));
  r->add_flag("--strict-input", ro.strict_input,
              "malformed lines in OBJ and MTL files are errors (default: warnings naming the "
              "first few lines, then a count)");
  r->add_flag("--allow-empty", ro.allow_empty,
              "a mesh file without faces loads as no triangles instead of an error");
  r->add_option("--bench-frames", ro.bench_frames,
                "frame-rate mode: render N more frames back to back after the first and report "
                "their times and frames per second")
      ->check(number_in(0, 100000, true));
  r->add_option("--tile", ro.tile,
                "distributed (mpirun): tile size in pixels, handed out one at a time; images "
                "do not depend on it")
      ->default_str("128")
      ->check(number_in(1, 16384, true));
  r->add_option("--tail-tile", ro.tail_tile,
                "distributed: the last tiles handed out (twice as many as there are ranks) are "
                "cut into tiles of N pixels, so that the ranks finish together (0: not cut)")
      ->default_str("half of --tile")
      ->check(number_in(0, 16384, true));
  r->add_option("--rank-timeout", ro.rank_timeout,
                "distributed: seconds a rank may be silent before it is lost")
      ->default_str("20")
      ->check(number_in(1, 86400, false));
  r->add_option("--tile-timeout", ro.tile_timeout,
                "distributed: seconds a rank may take for a tile before it is lost (0: no limit)")
      ->default_str("0")
      ->check(number_in(0, 86400, false));
  r->add_option("--checkpoint", ro.checkpoint,
                "distributed: rank 0 writes the image so far as NAME.partial.EXT this often, in "
                "seconds, while it renders (0: never); removed when the render completes")
      ->default_str("2")
      ->check(number_in(0, 86400, false));
  r->add_option("--device", ro.device,
                "the device of opencl, glsl or glsl-compute (RILL_OPENCL_DEVICE or "
                "RILL_EGL_DEVICE); {local_rank} is the rank's index on its host");
  r->add_flag("--progress", ro.progress,
              "distributed: rank 0 draws a progress bar on stderr, the tiles done per rank "
              "(mpirun passes stderr through a pipe, so rill-trace cannot tell a terminal)");
  r->add_flag("--distribute", ro.distribute,
              "require a distributed render: an error unless started by mpirun with 2 or more "
              "processes");
  r->add_option("--frames", ro.frames,
                "dynamic scenes: frame N, or frames A:B (both included); outputs need a frame "
                "number, e.g. --out frame-%04d.png");
  r->add_option("--bvh", ro.bvh,
                "dynamic scenes: the moving objects' BVH each frame: rebuild or refit")
      ->default_str("rebuild");
  r->add_option("--video", ro.video,
                "with --frames: a preview video of the PNGs (ffmpeg), .mp4 or .gif")
      ->check(file_name());
  r->add_option("--triangle", ro.triangle, "triangle test: moller or watertight")
      ->default_str("moller");
  r->add_option("--offset", ro.offset, "self-intersection: scaled (Wachter-Binder) or epsilon")
      ->default_str("scaled");
  r->add_option("--traversal", ro.traversal, "grid traversal: incremental or recompute")
      ->default_str("incremental");

  rt::AccuracyBenchOptions ao;
  std::string acc_size, acc_backends, acc_scenes;
  CLI::App* acc = app.add_subcommand(
      "accuracy", "time against error for every accuracy knob on every backend (a benchmark)");
  acc->add_option("--backends", acc_backends, "comma-separated (default: every available)");
  acc->add_option("--scenes", acc_scenes,
                  "comma-separated subset of closed,inside,floor-far,floor-tiny,cornell,glass");
  acc->add_option("--size", acc_size, "image size WxH (default 64x48)");
  acc->add_option("--repeats", ao.repeats, "timing repeats (median)")
      ->check(number_in(1, 100, true));
  acc->add_flag(
      "--one-at-a-time", [&](int64_t) { ao.factorial = false; },
      "vary one knob at a time instead of every combination");
  acc->add_option("--out-dir", ao.out_dir, "where accuracy.{md,csv,gp,svg} go");
  r->add_flag("--stats", ro.stats,
              "print the compile stages; multipass: per-pass calls, elements and time");
  r->add_option("--wait-threshold", ro.wait_threshold,
                "multipass: rerun the intersector while this fraction of rays waits (0..1]")
      ->default_str("0.2")
      ->check(number_in(1e-6, 1.0, false));
  r->add_option("--masking", ro.masking, "multipass: launch each pass masked to its state (on|off)")
      ->default_str("on");

  std::string demo_scene = "builtin:glass", demo_size, demo_out = ".";
  CLI::App* d =
      app.add_subcommand("demo", "render the flagship scene on every backend and compare");
  d->add_option("--scene", demo_scene, "scene to render")->default_str("builtin:glass");
  d->add_option("--size", demo_size, "image size WxH");
  d->add_option("--out-dir", demo_out, "where the PNGs go");
  CLI::App* in =
      app.add_subcommand("info", "list backends, devices, built-in scenes and surface shaders");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown first word: CLI11 only says that a subcommand is required.
    std::string what = e.what();
    // An option given twice: CLI11 says "--size: At Most 1 required but received 2".
    static const std::regex twice("^(-[-\\w]+): At Most 1 required but received (\\d+)$");
    if (std::smatch m; std::regex_match(what, m, twice))
      what = m[1].str() + " is given " + m[2].str() + " times: give it once";
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty())
      what = std::string("unknown command '") + argv[1] + "' (render, accuracy, demo, info)";
    std::fprintf(stderr, "rill-trace: %s (see --help)\n", what.c_str());
    return 2;
  }
  int rc = 0;
  try {
    ro.backend_given = r->count("--backend") > 0;
    if (*r) rc = render(ro);
    if (*d) rc = demo(demo_scene, demo_size, demo_out);
    if (*in) rc = info();
    if (*acc) {
      auto split = [](const std::string& s) {
        std::vector<std::string> v;
        std::stringstream ss(s);
        for (std::string item; std::getline(ss, item, ',');)
          if (!item.empty()) v.push_back(item);
        return v;
      };
      ao.backends = split(acc_backends);
      ao.scenes = split(acc_scenes);
      if (!acc_size.empty()) parse_size(acc_size, ao.width, ao.height);
      rc = rt::accuracy_bench(ao);
    }
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rill-trace: out of memory while %s\n", g_doing.c_str());
    rc = 1;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "rill-trace: %s\n", msg.c_str());
    rc = 1;
  }
  // Workaround for a library bug (reported): a GLSL kernel left in the in-process kernel
  // cache until exit crashes in OSMesaMakeCurrent when OpenCL (PoCL) was used too.
  rill::clear_kernel_cache();
  return rc;
}
