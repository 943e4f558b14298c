// rill-bench-trace: the ray tracer's benchmarks (issue #6, docs/raytracer.md, Performance).
//
//   rill-bench-trace [--sections throughput,embree,grid,depth,spec,bounce,whitted,shared]
//                    [--size WxH]
//                    [--scenes builtin:thesis-a,...,FILE.obj] [--backends
//                    all|cpu,simd,opencl,glsl,glsl-compute]
//                    [--repeats R] [--subgrids N|off|auto] [--grid-density D|auto] [--grid-scene S]
//                    [--grids auto,16,32,...] [--loops auto|ray,segment]
//                    [--packets auto|on|off,...] [--embree-modes auto|4,8,16,1M]
//                    [--depth-scene S] [--depths 1-8] [--sweep-backends cpu]
//                    [--path-scenes default|S,...] [--bounce 2] [--spp 1] [--seed N]
//                    [--whitted-frames full,camera]
//                    [--md F] [--csv F]
//
// Sections (each a table; all timings are medians of R interleaved repeats, after an
// untimed warm-up run that also compiles):
//   throughput  per scene and backend: primary rays (the camera rays' closest hit, the
//               tracer's intersector kernel alone, launch only: rays and results stay where
//               the backend keeps them) and full shading (Tracer::render, its rays/s counted
//               as rill-trace counts them: camera, shadow and secondary rays over the trace
//               time, which includes what `rill-trace render` reads back by default: the
//               8-bit image for its PNG, into the memory of the last frame's, as
//               `rill-trace render --bench-frames` does). With --loops ray,segment each backend's
//               full frames run with both megakernel loops, interleaved, one row each.
//               With --packets off,auto the CPU backends run once per setting (Options.h,
//               Packets: whether lane groups walk the grid together), side by side.
//   embree      the same primary rays through Intel Embree 3 (rtcIntersect1, one ray at a
//               time, oneTBB over the same cores), interleaved with Rill's CPU backend:
//               Mrays/s of both, the ratio, and how many rays agree (same primitive, or the
//               same distance within 1e-5 relative: a ray through a shared edge may pick
//               either triangle). A second table: Embree's coherent modes on the same
//               rays in the same rounds (--embree-modes: packets of 4/8/16 over pixel tiles,
//               the stream rtcIntersect1M over 8x8 tiles; trace_embree_modes.h), each checked
//               for agreement and set against each CPU backend. Compiled out (with a note) when
//               CMake found no Embree.
//   grid        one scene at several grid resolutions (N^3 voxels, and the heuristic):
//               build time, bytes per triangle, primary and full-shading throughput.
//   depth       scenes with mirrors (default thesis-b, and glass with refraction) at maximum
//               depth 1..8: trace time and rays.
//   spec        the scene's specialized kernel (Features: only the code the scene calls
//               for) against one with every effect on (specular, reflection, refraction with
//               its ray stack, vertex normals and colours, the lights and shadows the scene
//               has), same scene, interleaved: trace times, ratio, and pixels that differ.
//   whitted     (not in the default list) full Whitted frames: per scene, Rill's frame as
//               `rill-trace render` makes it with its defaults (Tracer::render, the megakernel,
//               reading back the 8-bit image) on cpu and simd, and a plain Whitted renderer on
//               Embree 3 (embree_whitted.h: rtcIntersect1 and rtcOccluded1 ray by ray, oneTBB
//               over tiles, the shading formulas of WhittedFormulas.h), interleaved: ms per
//               frame, the rays of each (Embree's by kind: camera, shadow, secondary), Mrays/s,
//               Rill/Embree, and how many pixels of Embree's linear image agree with Rill's cpu
//               image (every channel within 1e-4; at least 99% must). --whitted-frames
//               full,camera adds each scene with shadows off and max depth 0: the camera rays'
//               hits and their shading alone. Needs Embree.
//   bounce      (not in the default list) the path tracer's incoherent rays: per path scene
//               (--path-scenes; default cornell-path, thesis C with an area light and, where
//               ../shared/meshes has it, the bunny under one), the rays leaving the second
//               surface hit of each camera path (--bounce 2: after two scatterings), read back
//               from the wavefront strategy's own records on cpu (render/BounceRays.h; paths
//               that ended before are absent, and the count is printed), and the camera rays,
//               each traced by Rill's intersector on cpu and simd and by Embree's
//               rtcIntersect1, interleaved: Mrays/s, Rill/Embree, agreement as in the Embree
//               section with the mismatches counted by kind, the rays' mean grid cells crossed
//               (a plain 3D-DDA's walk, to explain the times), and how the ratio changes from
//               camera rays to bounce rays. Needs Embree.
//
// Exit status 1 if a check fails: Embree and Rill agree on fewer than --min-agree of the
// rays (primary or bounce), a backend's hits differ from the CPU's (strict: they must be
// identical), or the every-effect kernel's image differs from the specialized one by more than
// the tracer's weight cut-off (1e-3) or one of its camera rays hits another primitive, or the
// plain Embree renderer's Whitted image agrees with Rill's on fewer than 99% of the pixels
// (simd's image must be cpu's under strict).
#include <rill/rill.h>
#include <tbb/info.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "CommaList.h"
#include "HitAgreement.h"
#include "Timing.h"
#include "embree_whitted.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/DeviceArrays.h"
#include "rill/rt/render/BounceRays.h"
#include "rill/rt/scene/Scene.h"
#include "trace_embree.h"
#include "trace_embree_modes.h"

namespace {

using rill::bench::Clock;
using rill::bench::join_list;
using rill::bench::median;
using rill::bench::ms_since;
using rill::bench::split_list;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// A result table: printed as Markdown, and written to --md / --csv.
struct Table {
  std::string title;
  std::vector<std::string> head;
  std::vector<std::vector<std::string>> rows;
  std::string markdown() const {
    std::string s = "### " + title + "\n\n|";
    for (const auto& h : head) s += " " + h + " |";
    s += "\n|";
    for (size_t i = 0; i < head.size(); ++i) s += i == 0 ? " --- |" : " ---: |";
    s += "\n";
    for (const auto& r : rows) {
      s += "|";
      for (const auto& c : r) s += " " + c + " |";
      s += "\n";
    }
    return s + "\n";
  }
  std::string csv() const {
    auto q = [](const std::string& c) { return "\"" + c + "\""; };
    std::string s = q("table");
    for (const auto& h : head) s += "," + q(h);
    s += "\n";
    for (const auto& r : rows) {
      s += q(title);
      for (const auto& c : r) s += "," + q(c);
      s += "\n";
    }
    return s;
  }
};

struct Options {
  std::string sections = "throughput,embree,grid,depth,spec";
  std::string size = "1024x1024";
  std::string scenes = "builtin:thesis-a,builtin:thesis-b,builtin:thesis-c";
  std::string backends = "all";
  int repeats = 3;
  std::string grid_scene = "builtin:thesis-c";
  std::string grids = "auto,16,20,32,48,64,96,128";
  std::string subgrids;             // empty: the scene's (default auto: per backend)
  std::string grid_density;         // empty: the scene's (default auto: per backend)
  std::string accuracy = "strict";  // of the throughput and Embree sections
  rill::Accuracy acc = rill::Accuracy::Strict;
  // The megakernel loops of the throughput section's full frames, side by side (Tracer.h).
  std::string loops = "auto";
  std::vector<rt::MegakernelLoop> loop_list{rt::MegakernelLoop::Auto};
  // The packet settings the CPU backends run with, side by side (the throughput and Embree
  // sections).
  std::string packets = "auto";
  std::vector<rt::Packets> packets_list{rt::Packets::Auto};
  // Embree's modes beside rtcIntersect1 in the Embree section (trace_embree_modes.h); empty:
  // auto, the CPU's native packets and the stream.
  std::string embree_modes = "auto";
  std::vector<bench::EmbreeMode> embree_mode_list;
  std::string depth_scene = "builtin:thesis-b,builtin:glass";
  std::string depths = "1-8";
  std::string sweep_backends = "cpu";
  // The bounce section: the path tracer's rays after `bounce` scatterings, `spp` samples per
  // pixel, the scenes' seed unless one is given.
  std::string path_scenes = "default";
  int bounce = 2;
  int spp = 1;
  int64_t seed = -1;  // -1: the scene's
  // The whitted section's frames: full (the scene's), camera (no shadows, max depth 0).
  std::string whitted_frames = "full";
  // The shared section's child: measure this backend alone and write the figures here.
  std::string shared_alone, shared_out;
  std::string md, csv;
  double min_agree = 0.999;
  int width = 0, height = 0;
};

// --depths FIRST-LAST, within 0..64.
void parse_depths(const std::string& s, int& first, int& last) {
  if (std::sscanf(s.c_str(), "%d-%d", &first, &last) != 2 || first < 0 || last < first || last > 64)
    throw rt::SceneError("--depths expects FIRST-LAST within 0..64 (got '" + s + "')");
}

void parse_size(const std::string& s, int& w, int& h) {
  char x = 0;
  long a = 0, b = 0;
  char tail[2];
  if (std::sscanf(s.c_str(), "%ld%c%ld%1s", &a, &x, &b, tail) != 3 || (x != 'x' && x != 'X') ||
      a < 1 || b < 1 || a > 16384 || b > 16384)
    throw rt::SceneError("--size expects WxH, e.g. 1024x1024 (got '" + s + "')");
  w = static_cast<int>(a);
  h = static_cast<int>(b);
}

// The backends to run: the list (or all of this build's) that can run here; the others are
// reported once.
std::vector<std::string> usable_backends(const std::string& list) {
  std::vector<std::string> want;
  if (list == "all")
    for (rill::Backend* b : rill::backends()) want.push_back(b->name());
  else
    want = split_list(list);
  std::vector<std::string> out;
  for (const auto& name : want) {
    rill::Backend& b = rill::backend(name);  // throws for an unknown name
    if (std::string why = b.unavailable_reason(); !why.empty()) {
      std::printf("note: backend %s is not available here: %s\n", name.c_str(), why.c_str());
      continue;
    }
    out.push_back(name);
  }
  return out;
}

rt::Scene load(const std::string& spec, const Options& o) {
  rt::Scene s = rt::load_scene(spec);
  s.width = o.width;
  s.height = o.height;
  s.options.spp = 1;
  if (!o.subgrids.empty()) s.options.subgrid_min = rt::parse_subgrid_min(o.subgrids);
  if (!o.grid_density.empty()) s.options.grid_density = rt::parse_grid_density(o.grid_density);
  s.validate();
  return s;
}

// The bounce section's default scenes: the built-in Cornell box with its area light, thesis C
// with a 4 x 4 area light (the path benchmark's scene, docs/benchmarks/2026-12-07-path.md) and
// the bunny under an area light where ../shared/meshes has it (the repository does not ship it;
// no test needs it).
std::vector<std::string> default_path_scenes() {
  const std::string root = RILL_BENCH_SOURCE_DIR;
  std::vector<std::string> out{"builtin:cornell-path",
                               root + "/docs/benchmarks/2026-12-07-path/thesis-c-area.json"};
  if (std::filesystem::exists(root + "/../shared/meshes/stanford-bunny.obj"))
    out.push_back(root + "/docs/benchmarks/2026-12-07-bounce-rays/bunny-area.json");
  return out;
}

int64_t grid_bytes(const rt::Grid& g) {
  return static_cast<int64_t>(g.voxels.size() * sizeof(glm::ivec2) +
                              g.elements.size() * sizeof(int32_t));
}

std::string res_str(const rt::Grid& g) {
  return std::to_string(g.res.x) + "x" + std::to_string(g.res.y) + "x" + std::to_string(g.res.z);
}

// The grid cells a ray's segment inside the grid crosses up to its hit (dist; +inf: up to
// where it leaves the grid), 1 + the cell boundaries crossed on each axis, averaged over the
// rays: the length of a plain 3D-DDA walk, before empty-space skipping shortens it and before
// subgrids lengthen it. Only to explain why some rays cost more than others.
double mean_cells_crossed(const rt::Grid& g, const std::vector<glm::vec3>& origins,
                          const std::vector<glm::vec3>& dirs, const std::vector<float>& dist) {
  double sum = 0;
  for (size_t i = 0; i < dirs.size(); ++i) {
    const glm::dvec3 o(origins[i]), d(dirs[i]);
    double t0 = 0, t1 = std::isfinite(dist[i]) ? static_cast<double>(dist[i]) : HUGE_VAL;
    for (int a = 0; a < 3; ++a) {  // the slabs of the grid's box
      if (d[a] == 0) {
        if (o[a] < g.lo[a] || o[a] > g.hi[a]) t1 = -1;
        continue;
      }
      const double ta = (g.lo[a] - o[a]) / d[a], tb = (g.hi[a] - o[a]) / d[a];
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    if (!(t1 > t0)) continue;  // misses the grid: no cell
    double cells = 1;
    for (int a = 0; a < 3; ++a) cells += std::fabs(d[a]) * (t1 - t0) / g.cell[a];
    sum += cells;
  }
  return dirs.empty() ? 0.0 : sum / static_cast<double>(dirs.size());
}

// The tracer's intersector on one backend, bound to rays (the camera rays, or the bounce
// section's); launches are timed.
struct RayRun {
  std::string backend;
  rill::Kernel kernel;
  rill::Stream<rill::Float3> origins, dirs;
  rill::Stream<rill::Int> prim;
  rill::Stream<rill::Float> dist;
  // The rays of a width x height image, as 2D streams (a backend may use the shape: simd
  // runs tiles of neighbouring pixels together); rays of no image shape as n x 1.
  RayRun(rt::Tracer& tracer, const std::string& be, const std::vector<glm::vec3>& o,
         const std::vector<glm::vec3>& d, int width, int height,
         rill::Accuracy accuracy = rill::Accuracy::Strict)
      : backend(be),
        kernel(tracer.intersect_kernel(be, accuracy)),
        origins(width, height),
        dirs(width, height),
        prim(width, height),
        dist(width, height) {
    origins.upload(o);
    dirs.upload(d);
    kernel.inputs(origins, dirs).outputs(prim, dist);
  }
  double run() {
    const auto t = Clock::now();
    kernel.execute();
    return ms_since(t);
  }
  std::vector<int32_t> hits(size_t n) {
    auto p = prim.download();
    p.resize(n);
    return p;
  }
  std::vector<float> dists(size_t n) {
    auto d = dist.download();
    d.resize(n);
    return d;
  }
};

// What `rill-trace render` reads back by default: the 8-bit image for its PNG.
rt::FrameOutputs png_only() {
  rt::FrameOutputs o;
  o.color = o.depth = o.prim = o.normal = false;
  o.rgb8 = true;
  return o;
}

// A render as rill-trace makes it: one sample, reading back what a PNG needs (timed
// sections); `outputs` for sections that compare images.
rt::RenderSettings settings(const std::string& be, const rt::Scene& s, int max_depth = -1,
                            rill::Accuracy a = rill::Accuracy::Strict,
                            rt::FrameOutputs outputs = png_only()) {
  rt::RenderSettings rs;
  rs.outputs = outputs;
  rs.backend = be;
  rs.accuracy = a;
  rs.width = s.width;
  rs.height = s.height;
  rs.spp = 1;
  rs.max_depth = max_depth;
  return rs;
}

class Bench {
 public:
  explicit Bench(const Options& o) : o_(o) {}
  std::vector<Table> tables;
  bool ok = true;

  void throughput_and_embree(bool throughput, bool embree) {
    // The CPU backend first: the others' hits are compared with it, and Embree runs beside it.
    // Embree is compared with both CPU backends: scalar `cpu` and lockstep `simd`.
    std::vector<std::string> bes =
        throughput ? usable_backends(o_.backends) : std::vector<std::string>{"cpu", "simd"};
    bes.erase(std::remove(bes.begin(), bes.end(), "cpu"), bes.end());
    if (embree && std::find(bes.begin(), bes.end(), "simd") == bes.end())
      bes.insert(bes.begin(), "simd");
    if (embree || throughput) bes.insert(bes.begin(), "cpu");
    // Each CPU backend once per packet setting (labelled when there are several); the GPU
    // backends with the first.
    std::vector<rt::Packets> pks;
    std::vector<std::string> labels;
    {
      std::vector<std::string> each;
      for (const auto& be : bes)
        for (size_t p = 0; p < o_.packets_list.size(); ++p) {
          if (p > 0 && be != "cpu" && be != "simd") continue;
          each.push_back(be);
          pks.push_back(o_.packets_list[p]);
          labels.push_back(o_.packets_list.size() > 1 && (be == "cpu" || be == "simd")
                               ? be + " (packets " + rt::packets_name(o_.packets_list[p]) + ")"
                               : be);
        }
      bes = each;
    }
    const std::string acc = rill::accuracy_name(o_.acc);
    Table tp{"Throughput, " + size_str() + ", " + acc + ", median of " +
                 std::to_string(o_.repeats) + " (Mrays/s)",
             {"scene", "triangles", "grid", "build ms", "grid B/tri", "backend", "primary ms",
              "primary Mrays/s", "full ms", "rays/pixel", "full Mrays/s", "hits vs cpu"},
             {}};
    Table em{"Rill's CPU backends against Embree " + embree_version() + ", primary rays, " +
                 size_str() + ", Rill " + acc + ", " +
                 std::to_string(tbb::info::default_concurrency()) + " threads, median of " +
                 std::to_string(o_.repeats),
             {"scene", "triangles", "backend", "Rill ms", "Rill Mrays/s", "Embree ms",
              "Embree Mrays/s", "Rill/Embree", "same prim", "agree", "grid build ms", "grid B/tri",
              "Embree build ms", "Embree B/tri"},
             {}};
    // Embree's modes (rtcIntersect1, packets, the stream) side by side on the same rays, each
    // against every CPU row of Rill.
    Table modes{"Embree " + embree_version() + "'s ray modes on the same primary rays, " +
                    size_str() + ", Rill " + acc + ", " +
                    std::to_string(tbb::info::default_concurrency()) + " threads, median of " +
                    std::to_string(o_.repeats),
                {"scene", "triangles", "Embree mode", "native", "Embree ms", "Embree Mrays/s",
                 "same prim as rtcIntersect1", "agree with Rill"},
                {}};
    for (size_t b = 0; b < bes.size(); ++b)
      if (bes[b] == "cpu" || bes[b] == "simd") modes.head.push_back(labels[b] + "/Embree");
    for (const auto& spec : split_list(o_.scenes)) {
      rt::Scene scene = load(spec, o_);
      // Each backend renders with the grid rill-trace would build for it (subgrid_min_for,
      // grid_density_for: the CPU and GPUs may want different ones); backends that want the
      // same share it.
      struct Setup {
        int32_t subgrid_min;
        double density;
        rt::Packets packets;
        rt::Grid grid;
        std::unique_ptr<rt::Tracer> tracer;
      };
      std::vector<std::unique_ptr<Setup>> setups;
      std::vector<Setup*> setup_of;
      for (size_t b = 0; b < bes.size(); ++b) {
        const std::string& be = bes[b];
        const int32_t want = rt::subgrid_min_for(scene.options.subgrid_min, be);
        const double density =
            rt::grid_density_for(scene.options.grid_density, be, scene.triangle_count());
        const rt::Packets pk = pks[b];
        auto it = std::find_if(setups.begin(), setups.end(), [&](const auto& u) {
          return u->subgrid_min == want && u->density == density && u->packets == pk;
        });
        if (it == setups.end()) {
          rt::Scene with = scene;
          with.options.subgrid_min = want;
          with.options.grid_density = density;
          auto u =
              std::make_unique<Setup>(Setup{want, density, pk, rt::build_grid_for(with), nullptr});
          rt::TracerOptions knobs;
          knobs.packets = pk;
          u->tracer = std::make_unique<rt::Tracer>(scene, u->grid, knobs);
          std::printf("%s: %zu triangles, grid %s (for %s), features: %s\n", scene.name.c_str(),
                      scene.triangle_count(), res_str(u->grid).c_str(), be.c_str(),
                      u->tracer->features().str().c_str());
          setups.push_back(std::move(u));
          it = setups.end() - 1;
        }
        setup_of.push_back(it->get());
      }
      std::fflush(stdout);
      const size_t n = static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height);
      const std::vector<glm::vec3> dirs =
          setup_of[0]->tracer->camera_rays("cpu", scene.camera, scene.width, scene.height);
      const std::vector<glm::vec3> origins(n, scene.camera.eye);

      std::vector<std::unique_ptr<RayRun>> runs;
      for (size_t b = 0; b < bes.size(); ++b) {
        runs.push_back(std::make_unique<RayRun>(*setup_of[b]->tracer, bes[b], origins, dirs,
                                                scene.width, scene.height, o_.acc));
        runs.back()->run();  // warm-up: uploads, driver compiles
      }
#ifdef RILL_BENCH_HAVE_EMBREE
      // Each Embree mode's hits and times; calls[0] is rtcIntersect1, the Embree table's.
      struct EmbreeCall {
        bench::EmbreeMode mode;
        std::vector<int32_t> prim;
        std::vector<float> dist;
        std::vector<double> ms;
      };
      std::unique_ptr<bench::EmbreeScene> ebr;
      std::vector<EmbreeCall> calls;
      if (embree) {
        ebr = std::make_unique<bench::EmbreeScene>(scene);
        std::vector<bench::EmbreeMode> ms{bench::EmbreeMode{}};
        for (const bench::EmbreeMode& m : o_.embree_mode_list.empty()
                                              ? bench::auto_embree_modes(ebr->device())
                                              : o_.embree_mode_list)
          ms.push_back(m);
        for (const bench::EmbreeMode& m : ms) {
          // -2 is no answer: a pixel that a mode's tiles never reach fails the agreement.
          calls.push_back({m,
                           std::vector<int32_t>(n, -2),
                           std::vector<float>(n, std::numeric_limits<float>::quiet_NaN()),
                           {}});
          bench::trace_image(*ebr, m, scene.camera.eye, dirs, scene.width, scene.height,
                             calls.back().prim.data(), calls.back().dist.data());  // warm-up
        }
      }
#endif
      const std::vector<rt::MegakernelLoop>& loops = o_.loop_list;
      auto full_settings = [&](size_t b, size_t l) {
        rt::RenderSettings rs = settings(bes[b], scene, -1, o_.acc);
        rs.loop = loops[l];
        return rs;
      };
      // [backend][loop]: the full frames' times and rays.
      std::vector<std::vector<double>> prim_ms(bes.size());
      std::vector<std::vector<std::vector<double>>> full_ms(
          bes.size(), std::vector<std::vector<double>>(loops.size()));
      std::vector<std::vector<int64_t>> full_rays(bes.size(), std::vector<int64_t>(loops.size()));
      // One result per backend and loop, rendered into frame after frame as rill-trace's
      // --bench-frames does: its images' memory is allocated once, by the warm-up.
      std::vector<std::vector<rt::RenderResult>> results(
          bes.size(), std::vector<rt::RenderResult>(loops.size()));
      if (throughput)
        for (size_t b = 0; b < bes.size(); ++b)  // warm-up and compile
          for (size_t l = 0; l < loops.size(); ++l)
            setup_of[b]->tracer->render(full_settings(b, l), scene.camera, results[b][l]);
      for (int r = 0; r < o_.repeats; ++r) {
        for (size_t b = 0; b < bes.size(); ++b) {
          prim_ms[b].push_back(runs[b]->run());
#ifdef RILL_BENCH_HAVE_EMBREE
          // Beside the first cpu run, every Embree mode, starting one later each round so
          // that none always follows the same one.
          for (size_t k = 0; ebr && b == 0 && k < calls.size(); ++k) {
            EmbreeCall& c = calls[(k + static_cast<size_t>(r)) % calls.size()];
            const auto t = Clock::now();
            bench::trace_image(*ebr, c.mode, scene.camera.eye, dirs, scene.width, scene.height,
                               c.prim.data(), c.dist.data());
            c.ms.push_back(ms_since(t));
          }
#endif
        }
        if (throughput)
          for (size_t b = 0; b < bes.size(); ++b)
            for (size_t l = 0; l < loops.size(); ++l) {
              rt::RenderResult& res = results[b][l];
              setup_of[b]->tracer->render(full_settings(b, l), scene.camera, res);
              full_ms[b][l].push_back(res.trace_ms);
              full_rays[b][l] = res.rays;
            }
      }
      const std::vector<int32_t> cpu_prim = runs[0]->hits(n);
      auto build_ms_of = [&](size_t b) { return setup_of[b]->grid.build_ms; };
      auto bpt_of = [&](size_t b) {
        return static_cast<double>(grid_bytes(setup_of[b]->grid)) /
               static_cast<double>(std::max<size_t>(scene.triangle_count(), 1));
      };
      for (size_t b = 0; b < bes.size(); ++b) {
        std::string vs = "-";
        if (b > 0) {  // every backend's hits must equal cpu's
          const std::vector<int32_t> p = runs[b]->hits(n);
          size_t differ = 0;
          for (size_t i = 0; i < n; ++i) differ += p[i] != cpu_prim[i];
          vs = differ == 0 ? "identical" : std::to_string(differ) + " differ";
          // Only strict promises the same bits everywhere; fast's differences are reported.
          ok = ok && (differ == 0 || o_.acc == rill::Accuracy::Fast);
          if (differ && o_.acc != rill::Accuracy::Fast)
            std::printf("error: %s: %zu primary hits differ from cpu's\n", labels[b].c_str(),
                        differ);
        }
        if (!throughput) continue;
        const double pm = median(prim_ms[b]);
        for (size_t l = 0; l < loops.size(); ++l) {
          const double fm = median(full_ms[b][l]);
          const double rays = static_cast<double>(full_rays[b][l]);
          // The loop is named when it was asked for: "cpu (segment)".
          const std::string label =
              loops[l] == rt::MegakernelLoop::Auto
                  ? labels[b]
                  : labels[b] + " (" + rt::megakernel_loop_name(loops[l]) + ")";
          tp.rows.push_back(
              {scene.name, std::to_string(scene.triangle_count()), res_str(setup_of[b]->grid),
               fmt("%.1f", build_ms_of(b)), fmt("%.1f", bpt_of(b)), label, fmt("%.2f", pm),
               fmt("%.3f", mrays(static_cast<double>(n), pm)), fmt("%.1f", fm),
               fmt("%.2f", rays / static_cast<double>(n)), fmt("%.3f", mrays(rays, fm)), vs});
        }
      }
#ifdef RILL_BENCH_HAVE_EMBREE
      if (ebr) {
        const std::vector<float> cpu_dist = runs[0]->dists(n);
        const bench::HitAgreement agreement =
            bench::compare_hits(cpu_prim, cpu_dist, calls[0].prim, calls[0].dist);
        const size_t same = agreement.same;
        const double frac = agreement.fraction();
        ok = ok && frac >= o_.min_agree;
        const double emm = median(calls[0].ms);
        for (size_t b = 0; b < bes.size(); ++b) {
          if (bes[b] != "cpu" && bes[b] != "simd") continue;
          // simd's hits equal cpu's (checked above when the throughput section runs).
          const double rm = median(prim_ms[b]);
          em.rows.push_back(
              {scene.name, std::to_string(scene.triangle_count()), labels[b], fmt("%.2f", rm),
               fmt("%.3f", mrays(static_cast<double>(n), rm)), fmt("%.2f", emm),
               fmt("%.3f", mrays(static_cast<double>(n), emm)), fmt("%.3f", emm / rm),
               fmt("%.4f%%", 100.0 * static_cast<double>(same) / static_cast<double>(n)),
               fmt("%.4f%%", 100.0 * frac), fmt("%.1f", build_ms_of(b)), fmt("%.1f", bpt_of(b)),
               fmt("%.1f", ebr->build_ms()),
               fmt("%.1f", static_cast<double>(ebr->bytes()) /
                               static_cast<double>(std::max<size_t>(scene.triangle_count(), 1)))});
        }
        for (const EmbreeCall& c : calls) {
          // Every pixel must have an answer, whatever --min-agree allows: a tile that was never
          // traced may be a single corner pixel.
          const auto untraced = static_cast<size_t>(std::count(c.prim.begin(), c.prim.end(), -2));
          if (untraced) {
            ok = false;
            std::printf("error: %s: %s left %zu of the %zu pixels untraced\n", scene.name.c_str(),
                        c.mode.function().c_str(), untraced, n);
          }
          const bench::HitAgreement a = bench::compare_hits(cpu_prim, cpu_dist, c.prim, c.dist);
          if (a.fraction() < o_.min_agree) {
            ok = false;
            std::printf("error: %s: %s agrees with Rill on %.4f%% of the rays (%s)\n",
                        scene.name.c_str(), c.mode.function().c_str(), 100.0 * a.fraction(),
                        a.mismatch_str("Rill", "Embree").c_str());
          }
          size_t same_as_one = 0;
          for (size_t i = 0; i < n; ++i) same_as_one += c.prim[i] == calls[0].prim[i];
          const double cm = median(c.ms);
          std::vector<std::string> row{
              scene.name,
              std::to_string(scene.triangle_count()),
              c.mode.label(),
              bench::embree_native(ebr->device(), c.mode),
              fmt("%.2f", cm),
              fmt("%.3f", mrays(static_cast<double>(n), cm)),
              fmt("%.4f%%", 100.0 * static_cast<double>(same_as_one) / static_cast<double>(n)),
              fmt("%.4f%%", 100.0 * a.fraction())};
          for (size_t b = 0; b < bes.size(); ++b)
            if (bes[b] == "cpu" || bes[b] == "simd")
              row.push_back(fmt("%.3f", cm / median(prim_ms[b])));
          modes.rows.push_back(row);
        }
      }
#endif
    }
    if (throughput) add(tp);
    if (embree) {
#ifdef RILL_BENCH_HAVE_EMBREE
      add(em);
      add(modes);
#else
      std::printf("note: built without Embree 3 (libembree-dev): no Embree comparison\n");
#endif
    }
  }

  // The path tracer's bounce rays against its camera rays: the rays the path integrator
  // traces after o_.bounce scatterings, read back from the wavefront strategy's own path
  // records (render/BounceRays.h), and the camera rays of the Embree section, each traced by
  // Rill's intersector on cpu and simd and by Embree's rtcIntersect1 one ray at a time,
  // interleaved in one run. Both ray sets go to Rill and to Embree with an origin per ray, so
  // the two rows of a scene differ only in which rays they trace.
  void bounce_rays() {
#ifndef RILL_BENCH_HAVE_EMBREE
    std::printf("note: built without Embree 3 (libembree-dev): no bounce-ray comparison\n");
#else
    const std::vector<std::string> bes = usable_backends("cpu,simd");
    const std::string bounce_name = "bounce " + std::to_string(o_.bounce);
    Table t{"Rill's CPU backends against Embree " + embree_version() + ", the path tracer's " +
                bounce_name + " rays and the camera rays, " + size_str() + ", " +
                std::to_string(o_.spp) + " spp, Rill " + rill::accuracy_name(o_.acc) + ", " +
                std::to_string(tbb::info::default_concurrency()) + " threads, median of " +
                std::to_string(o_.repeats),
            {"scene", "triangles", "rays", "count", "hit", "cells/ray", "backend", "Rill ms",
             "Rill Mrays/s", "Embree ms", "Embree Mrays/s", "Rill/Embree", "same prim", "agree",
             "mismatches (vs Embree)"},
            {}};
    std::vector<std::string> ratios;  // per scene and backend: the bounce ratio over the primary
    const std::vector<std::string> specs =
        o_.path_scenes == "default" ? default_path_scenes() : split_list(o_.path_scenes);
    for (const auto& spec : specs) {
      rt::Scene scene = load(spec, o_);
      if (scene.options.integrator != rt::Integrator::Path)
        throw rt::SceneError(spec + ": the bounce section traces the path integrator's rays: " +
                             "the scene needs options.integrator \"path\"");
      scene.options.spp = o_.spp;
      if (o_.seed >= 0) scene.options.seed = static_cast<uint32_t>(o_.seed);
      scene.validate();
      // cpu and simd want the same subgrids (subgrid_min_for: both run on the CPU); this
      // section traces both on the cpu backend's grid (simd may get a denser one by default,
      // grid_density_for; images do not depend on it).
      const rt::Grid grid = rt::build_grid_for(scene, "cpu");
      rt::Tracer tracer(scene, grid);
      std::printf("%s: %zu triangles, grid %s, max_depth %d, seed %u\n", scene.name.c_str(),
                  scene.triangle_count(), res_str(grid).c_str(), scene.options.max_depth,
                  static_cast<unsigned>(scene.options.seed));
      std::fflush(stdout);

      struct RaySet {
        std::string name;
        std::vector<glm::vec3> origins, dirs;
        int width = 0, height = 0;  // the streams' shape
        std::vector<std::unique_ptr<RayRun>> runs;
        std::vector<std::vector<double>> rill_ms;
        std::vector<double> embree_ms;
        std::vector<int32_t> e_prim;
        std::vector<float> e_dist;
      };
      std::vector<RaySet> sets(2);
      RaySet& primary = sets[0];
      primary.name = "primary";
      primary.dirs = tracer.camera_rays("cpu", scene.camera, scene.width, scene.height);
      primary.origins.assign(primary.dirs.size(), scene.camera.eye);
      primary.width = scene.width;
      primary.height = scene.height;
      RaySet& bounce = sets[1];
      bounce.name = bounce_name;
      {
        // The path tracer's own frame, on cpu: its rays after o_.bounce scatterings, in pixel
        // order sample after sample (a 1D list: simd groups neighbouring pixels' rays).
        rt::BounceRays captured;
        captured.bounce = o_.bounce;
        rt::RenderSettings rs = settings("cpu", scene, -1, o_.acc);
        rs.strategy = rt::Strategy::Wavefront;
        rs.spp = o_.spp;
        rs.bounce_rays = &captured;
        tracer.render(rs, scene.camera);
        if (captured.size() > static_cast<size_t>(std::numeric_limits<int>::max()))
          throw rt::SceneError("--size and --spp: more bounce rays than one stream holds");
        bounce.origins = std::move(captured.origins);
        bounce.dirs = std::move(captured.directions);
        bounce.width = static_cast<int>(bounce.dirs.size());
        bounce.height = 1;
      }
      const size_t paths = static_cast<size_t>(scene.width) * scene.height * o_.spp;
      std::printf("  %s rays: %zu of %zu camera paths (%.1f%%)\n", bounce_name.c_str(),
                  bounce.dirs.size(), paths,
                  100.0 * static_cast<double>(bounce.dirs.size()) / static_cast<double>(paths));
      std::fflush(stdout);
      if (bounce.dirs.empty()) {
        std::printf("  no path reaches %s: no row\n", bounce_name.c_str());
        sets.pop_back();
      }

      bench::EmbreeScene ebr(scene);
      for (RaySet& rays : sets) {
        for (const auto& be : bes) {
          rays.runs.push_back(std::make_unique<RayRun>(tracer, be, rays.origins, rays.dirs,
                                                       rays.width, rays.height, o_.acc));
          rays.runs.back()->run();  // warm-up: uploads, compiles
        }
        rays.rill_ms.resize(bes.size());
        rays.e_prim.resize(rays.dirs.size());
        rays.e_dist.resize(rays.dirs.size());
        ebr.trace(rays.origins, rays.dirs, rays.e_prim.data(), rays.e_dist.data());  // warm-up
      }
      for (int r = 0; r < o_.repeats; ++r)
        for (RaySet& rays : sets) {
          for (size_t b = 0; b < bes.size(); ++b) rays.rill_ms[b].push_back(rays.runs[b]->run());
          const auto t0 = Clock::now();
          ebr.trace(rays.origins, rays.dirs, rays.e_prim.data(), rays.e_dist.data());
          rays.embree_ms.push_back(ms_since(t0));
        }

      std::vector<double> primary_ratio(bes.size(), 0.0);
      for (size_t k = 0; k < sets.size(); ++k) {
        RaySet& rays = sets[k];
        const size_t n = rays.dirs.size();
        const double emm = median(rays.embree_ms);
        const std::vector<int32_t> cpu_prim = rays.runs[0]->hits(n);
        size_t hit = 0;
        for (int32_t p : cpu_prim) hit += p >= 0;
        const double cells =
            mean_cells_crossed(grid, rays.origins, rays.dirs, rays.runs[0]->dists(n));
        for (size_t b = 0; b < bes.size(); ++b) {
          const std::vector<int32_t> prim = rays.runs[b]->hits(n);
          if (b > 0) {  // under strict simd's hits are cpu's, bit for bit
            size_t differ = 0;
            for (size_t i = 0; i < n; ++i) differ += prim[i] != cpu_prim[i];
            if (differ) {
              std::printf("%s: %s: %s's hits differ from cpu's on %zu rays\n",
                          o_.acc == rill::Accuracy::Fast ? "note" : "error", scene.name.c_str(),
                          bes[b].c_str(), differ);
              ok = ok && o_.acc == rill::Accuracy::Fast;
            }
          }
          const bench::HitAgreement a =
              bench::compare_hits(prim, rays.runs[b]->dists(n), rays.e_prim, rays.e_dist);
          ok = ok && a.fraction() >= o_.min_agree;
          const double rm = median(rays.rill_ms[b]);
          const double ratio = emm / rm;  // Rill's rays/s over Embree's
          if (k == 0)
            primary_ratio[b] = ratio;
          else
            ratios.push_back(scene.name + " " + bes[b] + ": " + fmt("%.3f", ratio) + " / " +
                             fmt("%.3f", primary_ratio[b]) + " = " +
                             fmt("%.2f", ratio / primary_ratio[b]));
          const double nd = static_cast<double>(n);
          t.rows.push_back({scene.name, std::to_string(scene.triangle_count()), rays.name,
                            std::to_string(n), fmt("%.1f%%", 100.0 * static_cast<double>(hit) / nd),
                            fmt("%.1f", cells), bes[b], fmt("%.2f", rm), fmt("%.3f", mrays(nd, rm)),
                            fmt("%.2f", emm), fmt("%.3f", mrays(nd, emm)), fmt("%.3f", ratio),
                            fmt("%.4f%%", 100.0 * static_cast<double>(a.same) / nd),
                            fmt("%.4f%%", 100.0 * a.fraction()), a.mismatch_str("Rill", "Embree")});
        }
      }
    }
    add(t);
    std::printf("Rill/Embree on %s rays over Rill/Embree on primary rays (the ratio's change):\n",
                bounce_name.c_str());
    for (const auto& r : ratios) std::printf("  %s\n", r.c_str());
#endif
  }

  // Full Whitted frames against the plain Embree renderer (embree_whitted.h): Rill's frame as
  // `rill-trace render` makes it on cpu and simd, and Embree's, interleaved round by round
  // (each round starting one later), each on the cores oneTBB gives it.
  void whitted_frames() {
#ifndef RILL_BENCH_HAVE_EMBREE
    std::printf("note: built without Embree 3 (libembree-dev): no Whitted comparison\n");
#else
    const std::vector<std::string> bes = usable_backends("cpu,simd");
    if (bes.empty() || bes[0] != "cpu") {  // cpu's image is the one compared
      ok = false;
      std::printf("error: the whitted section needs the cpu backend\n");
      return;
    }
    Table t{"Whitted frames: rill-trace render against a plain Embree " + embree_version() +
                " renderer, " + size_str() + ", Rill " + rill::accuracy_name(o_.acc) + ", " +
                std::to_string(tbb::info::default_concurrency()) + " threads, median of " +
                std::to_string(o_.repeats),
            {"scene", "triangles", "frame", "max depth", "backend", "Rill ms", "Rill rays",
             "Rill Mrays/s", "Embree ms", "Embree rays (camera + shadow + secondary)",
             "Embree Mrays/s", "Rill/Embree", "pixels agree", "same bytes"},
            {}};
    for (const auto& spec : split_list(o_.scenes))
      for (const auto& kind : split_list(o_.whitted_frames)) {
        rt::Scene scene = load(spec, o_);
        if (kind == "camera") {  // hit finding and shading alone: no shadow or secondary rays
          scene.options.shadows = false;
          scene.options.max_depth = 0;
        }
        whitted_frame(scene, kind, bes, t);
      }
    add(t);
#endif
  }

#ifdef RILL_BENCH_HAVE_EMBREE
  // One scene's rows of the whitted section: frame `kind` (full or camera).
  void whitted_frame(const rt::Scene& scene, const std::string& kind,
                     const std::vector<std::string>& bes, Table& t) {
    // Each backend with the grid rill-trace builds for it (build_grid_for: cpu and simd may
    // get different densities; images do not depend on it).
    std::vector<std::unique_ptr<rt::Grid>> grids;
    std::vector<std::unique_ptr<rt::Tracer>> tracers;
    for (const auto& be : bes) {
      grids.push_back(std::make_unique<rt::Grid>(rt::build_grid_for(scene, be)));
      tracers.push_back(std::make_unique<rt::Tracer>(scene, *grids.back()));
    }
    const int depth = scene.options.max_depth;
    const bench::EmbreeScene ebr(scene);
    const bench::EmbreeWhitted plain(scene, ebr, tracers[0]->features(), rt::TracerOptions{},
                                     depth);
    std::printf("%s: %zu triangles, max depth %d, features: %s\n", scene.name.c_str(),
                scene.triangle_count(), depth, tracers[0]->features().str().c_str());
    std::fflush(stdout);
    // The images compared: cpu's linear colour (an untimed render) and Embree's.
    const rt::FrameOutputs colour{.color = true, .depth = false, .prim = false, .normal = false};
    const rt::RenderResult reference =
        tracers[0]->render(settings("cpu", scene, -1, o_.acc, colour), scene.camera);
    // Timed: each backend's frames into one result, as rill-trace's --bench-frames renders;
    // each warmed up (compiled) first.
    std::vector<rt::RenderResult> results(bes.size());
    std::vector<std::vector<double>> rill_ms(bes.size());
    std::vector<double> embree_ms;
    bench::WhittedImage image;
    for (size_t b = 0; b < bes.size(); ++b)
      tracers[b]->render(settings(bes[b], scene, -1, o_.acc), scene.camera, results[b]);
    plain.render(scene.width, scene.height, image);
    const size_t sides = bes.size() + 1;  // the backends, then Embree
    for (int r = 0; r < o_.repeats; ++r)
      for (size_t k = 0; k < sides; ++k) {
        const size_t x = (k + static_cast<size_t>(r)) % sides;
        if (x == bes.size()) {
          const auto t0 = Clock::now();
          plain.render(scene.width, scene.height, image);
          embree_ms.push_back(ms_since(t0));
        } else {
          tracers[x]->render(settings(bes[x], scene, -1, o_.acc), scene.camera, results[x]);
          rill_ms[x].push_back(results[x].trace_ms);
        }
      }
    // Agreement: a pixel agrees when every channel is within kWhittedSame (why: see
    // kWhittedSame in embree_whitted.h).
    const size_t n = image.color.size();
    size_t agree = 0, same_bytes = 0;
    for (size_t p = 0; p < n; ++p) {
      const glm::vec3 d = glm::abs(reference.color[p] - image.color[p]);
      agree += std::max({d.x, d.y, d.z}) <= bench::kWhittedSame;
    }
    for (size_t p = 0; p < n; ++p)
      same_bytes += std::memcmp(&results[0].rgb8[3 * p], &image.rgb8[3 * p], 3) == 0;
    const double frac = static_cast<double>(agree) / static_cast<double>(std::max<size_t>(n, 1));
    if (frac < bench::kWhittedMinAgree) {
      ok = false;
      std::printf(
          "error: %s: Embree's Whitted image agrees with Rill's on %.4f%% of the "
          "pixels (at least %.0f%% must)\n",
          scene.name.c_str(), 100.0 * frac, 100.0 * bench::kWhittedMinAgree);
    }
    const double emm = median(embree_ms);
    const bench::WhittedRays& er = image.rays;
    for (size_t b = 0; b < bes.size(); ++b) {
      // Under strict every backend's bytes are cpu's.
      if (b > 0 && results[b].rgb8 != results[0].rgb8 && o_.acc == rill::Accuracy::Strict) {
        ok = false;
        std::printf("error: %s: %s's image differs from cpu's\n", scene.name.c_str(),
                    bes[b].c_str());
      }
      const double rm = median(rill_ms[b]);
      const double rays = static_cast<double>(results[b].rays);
      t.rows.push_back({scene.name, std::to_string(scene.triangle_count()), kind,
                        std::to_string(depth), bes[b], fmt("%.1f", rm),
                        std::to_string(results[b].rays), fmt("%.3f", mrays(rays, rm)),
                        fmt("%.1f", emm),
                        std::to_string(er.total()) + " (" + std::to_string(er.camera) + " + " +
                            std::to_string(er.shadow) + " + " + std::to_string(er.secondary) + ")",
                        fmt("%.3f", mrays(static_cast<double>(er.total()), emm)),
                        fmt("%.3f", emm / rm), fmt("%.4f%%", 100.0 * frac),
                        fmt("%.4f%%", 100.0 * static_cast<double>(same_bytes) /
                                          static_cast<double>(std::max<size_t>(n, 1)))});
    }
  }
#endif

  // Time against grid resolution. Every grid's tracer is set up first, so that the timed
  // repeats can interleave the resolutions (the machine's load drifts).
  void grid_sweep() {
    const auto bes = usable_backends(o_.sweep_backends);
    rt::Scene scene = load(o_.grid_scene, o_);
    const size_t n = static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height);
    const double tris = static_cast<double>(std::max<size_t>(scene.triangle_count(), 1));
    Table t{"Grid resolution sweep: " + scene.name + " (" + std::to_string(scene.triangle_count()) +
                " triangles), " + size_str() + ", median of " + std::to_string(o_.repeats),
            {"grid", "voxels", "refs/tri", "build ms", "grid B/tri", "backend", "primary Mrays/s",
             "full ms", "full Mrays/s"},
            {}};
    struct Point {
      int res = 0;
      rt::Grid grid;
      std::vector<double> build;
      std::unique_ptr<rt::Tracer> tracer;
      std::vector<std::unique_ptr<RayRun>> runs;  // per backend
      std::vector<std::vector<double>> prim_ms, full_ms;
      std::vector<int64_t> rays;
    };
    std::vector<Point> points;
    const std::vector<glm::vec3> origins(n, scene.camera.eye);
    for (const auto& g : split_list(o_.grids)) {
      Point p;
      p.res = rt::parse_grid_resolution(g, "--grids");
      for (int r = 0; r < o_.repeats; ++r) {  // the build time is a median too
        p.grid = rt::build_grid(
            scene, p.res, rt::subgrid_min_for(scene.options.subgrid_min, "cpu"),
            rt::grid_density_for(scene.options.grid_density, "cpu", scene.triangle_count()));
        p.build.push_back(p.grid.build_ms);
      }
      p.tracer = std::make_unique<rt::Tracer>(scene, p.grid);
      const auto dirs = p.tracer->camera_rays("cpu", scene.camera, scene.width, scene.height);
      for (const auto& be : bes) {
        p.runs.push_back(
            std::make_unique<RayRun>(*p.tracer, be, origins, dirs, scene.width, scene.height));
        p.runs.back()->run();                                 // warm-up
        p.tracer->render(settings(be, scene), scene.camera);  // compile, warm-up
      }
      p.prim_ms.resize(bes.size());
      p.full_ms.resize(bes.size());
      p.rays.resize(bes.size());
      points.push_back(std::move(p));
    }
    for (int r = 0; r < o_.repeats; ++r)
      for (auto& p : points)
        for (size_t b = 0; b < bes.size(); ++b) {
          p.prim_ms[b].push_back(p.runs[b]->run());
          rt::RenderResult res = p.tracer->render(settings(bes[b], scene), scene.camera);
          p.full_ms[b].push_back(res.trace_ms);
          p.rays[b] = res.rays;
        }
    for (auto& p : points)
      for (size_t b = 0; b < bes.size(); ++b) {
        const double fm = median(p.full_ms[b]);
        t.rows.push_back({(p.res == 0 ? "auto " : "") + res_str(p.grid),
                          std::to_string(p.grid.voxel_count()),
                          fmt("%.2f", static_cast<double>(p.grid.elements.size()) / tris),
                          fmt("%.1f", median(p.build)),
                          fmt("%.1f", static_cast<double>(grid_bytes(p.grid)) / tris), bes[b],
                          fmt("%.3f", mrays(static_cast<double>(n), median(p.prim_ms[b]))),
                          fmt("%.1f", fm), fmt("%.3f", mrays(static_cast<double>(p.rays[b]), fm))});
      }
    add(t);
  }

  // Time against maximum reflection depth.
  void depth_sweep() {
    for (const auto& spec : split_list(o_.depth_scene)) depth_sweep(spec);
  }
  void depth_sweep(const std::string& spec) {
    const auto bes = usable_backends(o_.sweep_backends);
    rt::Scene scene = load(spec, o_);
    int d0 = 1, d1 = 8;
    parse_depths(o_.depths, d0, d1);
    rt::Grid grid = rt::build_grid_for(scene);
    rt::Tracer tracer(scene, grid);
    const double n = static_cast<double>(scene.width) * scene.height;
    Table t{"Reflection depth sweep: " + scene.name + " (" +
                std::to_string(scene.triangle_count()) +
                " triangles, features: " + tracer.features().str() + "), " + size_str() +
                ", median of " + std::to_string(o_.repeats),
            {"max depth", "backend", "rays/pixel", "trace ms", "Mrays/s",
             "ms vs depth " + std::to_string(d0)},
            {}};
    for (const auto& be : bes) {
      tracer.render(settings(be, scene, d0), scene.camera);  // compile, warm-up
      std::map<int, std::vector<double>> ms;
      std::map<int, int64_t> rays;
      for (int r = 0; r < o_.repeats; ++r)
        for (int d = d0; d <= d1; ++d) {
          rt::RenderResult res = tracer.render(settings(be, scene, d), scene.camera);
          ms[d].push_back(res.trace_ms);
          rays[d] = res.rays;
        }
      const double base = median(ms[d0]);
      for (int d = d0; d <= d1; ++d) {
        const double m = median(ms[d]);
        t.rows.push_back({std::to_string(d), be, fmt("%.2f", static_cast<double>(rays[d]) / n),
                          fmt("%.1f", m), fmt("%.3f", mrays(static_cast<double>(rays[d]), m)),
                          fmt("%.2fx", m / base)});
      }
    }
    add(t);
  }

  // The specialized kernel against one with every effect on.
  void specialization() {
    const auto bes = usable_backends(o_.backends);
    Table t{"Specialized kernel against every effect on, " + size_str() + ", median of " +
                std::to_string(o_.repeats),
            {"scene", "scene's features", "backend", "specialized ms", "all-on ms", "time saved",
             "pixels differing"},
            {}};
    rt::TracerOptions all;
    rt::Features& every = all.extra_features;
    every.specular = every.reflection = every.refraction = true;
    every.vertex_normals = every.vertex_colors = true;
    every.stack = rt::kRayStack;
    for (const auto& spec : split_list(o_.scenes)) {
      rt::Scene scene = load(spec, o_);
      rt::Grid grid = rt::build_grid_for(scene);
      rt::Tracer special(scene, grid), generic(scene, grid, all);
      for (const auto& be : bes) {
        // Colour and AOVs, compared below.
        const rt::FrameOutputs images{.color = true, .depth = true, .prim = true, .normal = true};
        const auto strict = rill::Accuracy::Strict;
        rt::RenderResult a = special.render(settings(be, scene, -1, strict, images), scene.camera);
        rt::RenderResult b = generic.render(settings(be, scene, -1, strict, images), scene.camera);
        size_t differ = 0;
        float maxdiff = 0;
        for (size_t p = 0; p < a.color.size(); ++p) {
          differ += std::memcmp(&a.color[p], &b.color[p], sizeof(glm::vec3)) != 0;
          const glm::vec3 d = glm::abs(a.color[p] - b.color[p]);
          maxdiff = std::max({maxdiff, d.x, d.y, d.z});
        }
        // Every effect on at zero strength changes only rounding (interpolated normals and
        // white vertex colours are not exactly the face normal and 1), and rounding can flip
        // whether a secondary ray whose weight is at the tracer's cut-off (1e-3, kMinWeight in
        // kernel/Shading.h) is traced: so colours may differ by up to that weight (measured: 3.7e-4
        // on thesis-b at 1920x1080), while every camera ray must hit the same primitive.
        const bool same = maxdiff <= 1e-3f && a.prim == b.prim && generic.features().refraction &&
                          generic.features().vertex_colors && generic.features().vertex_normals;
        ok = ok && same;
        std::vector<double> sm, gm;
        for (int r = 0; r < o_.repeats; ++r) {
          sm.push_back(special.render(settings(be, scene), scene.camera).trace_ms);
          gm.push_back(generic.render(settings(be, scene), scene.camera).trace_ms);
        }
        const double s = median(sm), g = median(gm);
        t.rows.push_back({scene.name, special.features().str(), be, fmt("%.1f", s), fmt("%.1f", g),
                          fmt("%.1f%%", 100.0 * (g - s) / g),
                          differ == 0 ? std::string("0")
                                      : std::to_string(differ) + " (max " +
                                            fmt("%.2g", static_cast<double>(maxdiff)) + ")"});
        std::printf("  %s %s done\n", scene.name.c_str(), be.c_str());
        std::fflush(stdout);
      }
    }
    add(t);
  }

 private:
  const Options& o_;

  static double mrays(double rays, double ms) {
    return ms > 0 ? rays / (ms * 1e3) : 0.0;
  }
  // The shared-process section (issue 52 item 1): each GPU backend measured in a process of
  // its own (this program again, started before this one opens any GPU backend), then all of
  // them in this one process, one backend after the other and then launch by launch
  // interleaved, then alone again in a child while this process holds every backend open.
  // Wall time of the primary-ray launch and of a full frame, with the device's own timing of
  // the kernels beside them (a slower kernel on the device, or the same kernel and a slower
  // launch, point at different causes), and each against the backend's figure alone.
  struct SharedFigures {
    double prim_ms = -1, prim_kernel_ms = -1, full_ms = -1, full_kernel_ms = -1;
  };
  // Measures `bes` on `spec` in this process; `interleaved`: launch by launch, else each
  // backend's repeats together.
  std::vector<SharedFigures> shared_measure(const std::string& spec,
                                            const std::vector<std::string>& bes, bool interleaved) {
    rt::Scene scene = load(spec, o_);
    std::vector<std::unique_ptr<rt::Grid>> grids;
    std::vector<std::unique_ptr<rt::Tracer>> tracers;
    std::vector<std::unique_ptr<RayRun>> runs;
    std::vector<rt::RenderResult> results(bes.size());
    const size_t n = static_cast<size_t>(scene.width) * static_cast<size_t>(scene.height);
    for (const auto& be : bes) {
      rt::Scene with = scene;
      with.options.subgrid_min = rt::subgrid_min_for(scene.options.subgrid_min, be);
      grids.push_back(std::make_unique<rt::Grid>(rt::build_grid_for(with)));
      tracers.push_back(std::make_unique<rt::Tracer>(scene, *grids.back()));
      const std::vector<glm::vec3> dirs =
          tracers.back()->camera_rays("cpu", scene.camera, scene.width, scene.height);
      runs.push_back(std::make_unique<RayRun>(*tracers.back(), be,
                                              std::vector<glm::vec3>(n, scene.camera.eye), dirs,
                                              scene.width, scene.height, o_.acc));
      runs.back()->run();  // warm-up: uploads, driver compiles
      tracers.back()->render(settings(be, scene, -1, o_.acc), scene.camera, results.back());
    }
    std::vector<std::vector<double>> pw(bes.size()), pk(bes.size()), fw(bes.size()), fk(bes.size());
    auto one = [&](size_t b) {
      pw[b].push_back(runs[b]->run());
      pk[b].push_back(runs[b]->kernel.last_launch().device_ms);
      tracers[b]->render(settings(bes[b], scene, -1, o_.acc), scene.camera, results[b]);
      fw[b].push_back(results[b].trace_ms);
      fk[b].push_back(results[b].times.kernel);
    };
    if (interleaved) {
      for (int r = 0; r < o_.repeats; ++r)
        for (size_t b = 0; b < bes.size(); ++b) one(b);
    } else {
      for (size_t b = 0; b < bes.size(); ++b)
        for (int r = 0; r < o_.repeats; ++r) one(b);
    }
    std::vector<SharedFigures> out(bes.size());
    for (size_t b = 0; b < bes.size(); ++b)
      out[b] = {median(pw[b]), median(pk[b]), median(fw[b]), median(fk[b])};
    return out;
  }
  // This program again, measuring `be` alone on every scene; false (reported) if it failed.
  bool shared_child(const std::string& be, std::map<std::string, SharedFigures>& out) {
    char tmpl[] = "/tmp/rill-bench-shared-XXXXXX";
    const int fd = mkstemp(tmpl);
    if (fd < 0) return false;
    close(fd);
    // An argument vector, not a shell line: scene paths may hold spaces or quotes.
    // The child measures what this process does: the same scenes, grid and kernel settings.
    std::vector<std::string> args = {std::filesystem::read_symlink("/proc/self/exe").string()};
    args.insert(args.end(), {"--sections", "shared", "--shared-alone", be, "--shared-out", tmpl});
    args.insert(args.end(), {"--backends", be, "--scenes", o_.scenes, "--size", o_.size});
    args.insert(args.end(), {"--repeats", std::to_string(o_.repeats), "--accuracy", o_.accuracy});
    args.insert(args.end(), {"--packets", o_.packets, "--loops", o_.loops});
    if (!o_.subgrids.empty()) args.insert(args.end(), {"--subgrids", o_.subgrids});
    if (!o_.grid_density.empty()) args.insert(args.end(), {"--grid-density", o_.grid_density});
    std::vector<char*> argv;
    std::string cmd;  // for the message
    for (const std::string& a : args) {
      argv.push_back(const_cast<char*>(a.c_str()));
      cmd += (cmd.empty() ? "'" : " '") + a + "'";  // quoted: the message names each argument
    }
    argv.push_back(nullptr);
    posix_spawn_file_actions_t quiet;  // the child's own report would interleave with ours
    posix_spawn_file_actions_init(&quiet);
    posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
    pid_t pid = 0;
    int status = 0;
    const bool ran = posix_spawn(&pid, argv[0], &quiet, nullptr, argv.data(), environ) == 0 &&
                     waitpid(pid, &status, 0) == pid && WIFEXITED(status) &&
                     WEXITSTATUS(status) == 0;
    posix_spawn_file_actions_destroy(&quiet);
    std::ifstream f(tmpl);
    std::string spec;
    SharedFigures fig;
    while (ran && f >> fig.prim_ms >> fig.prim_kernel_ms >> fig.full_ms >> fig.full_kernel_ms &&
           f.get() == ' ' && std::getline(f, spec))
      out[spec] = fig;
    std::filesystem::remove(tmpl);
    ok = ok && ran;
    if (!ran)
      std::fprintf(stderr, "rill-bench-trace: the child measuring %s failed: %s\n", be.c_str(),
                   cmd.c_str());
    return ran;
  }

 public:
  void shared_process() {
    if (!o_.shared_alone.empty()) {  // the child
      std::ofstream f(o_.shared_out);
      for (const auto& spec : split_list(o_.scenes)) {
        const SharedFigures g = shared_measure(spec, {o_.shared_alone}, false)[0];
        // The figures first, the scene last: the rest of the line, whatever blanks it holds.
        f << g.prim_ms << ' ' << g.prim_kernel_ms << ' ' << g.full_ms << ' ' << g.full_kernel_ms
          << ' ' << spec << '\n';
      }
      if (!f) throw rt::SceneError("cannot write " + o_.shared_out);
      return;
    }
    // The GPU backends asked for, by name only: opening one here before the children ran
    // would make their "alone" figures those of a machine where another process holds it.
    std::vector<std::string> want;
    if (o_.backends == "all")
      for (rill::Backend* b : rill::backends()) want.push_back(b->name());
    else
      want = split_list(o_.backends);
    want.erase(std::remove_if(want.begin(), want.end(),
                              [](const std::string& b) { return b == "cpu" || b == "simd"; }),
               want.end());
    std::map<std::string, std::map<std::string, SharedFigures>> alone, alone_held;
    for (const auto& be : want) shared_child(be, alone[be]);
    std::vector<std::string> bes;
    for (const auto& be : want)
      if (!alone[be].empty()) bes.push_back(be);
    bes = usable_backends(join_list(bes));
    if (bes.size() < 2) {
      std::printf("note: the shared section needs two GPU backends that run here (%zu did)\n",
                  bes.size());
      return;
    }
    std::map<std::string, std::vector<SharedFigures>> seq, inter;
    for (const auto& spec : split_list(o_.scenes)) {
      seq[spec] = shared_measure(spec, bes, false);
      inter[spec] = shared_measure(spec, bes, true);
    }
    for (const auto& be : bes) shared_child(be, alone_held[be]);
    const std::string acc = rill::accuracy_name(o_.acc);
    Table t{"GPU backends sharing a process, " + size_str() + ", " + acc + ", median of " +
                std::to_string(o_.repeats) +
                " (ms: wall / the device's kernel time; x: against alone)",
            {"scene", "backend", "primary alone", "primary shared", "x", "primary interleaved", "x",
             "primary alone, others held open elsewhere", "frame alone", "frame shared", "x",
             "frame interleaved", "x"},
            {}};
    auto wk = [](double w, double k) {
      return k < 0 ? fmt("%.2f", w) : fmt("%.2f", w) + " / " + fmt("%.2f", k);
    };
    for (const auto& spec : split_list(o_.scenes))
      for (size_t b = 0; b < bes.size(); ++b) {
        const SharedFigures a = alone[bes[b]][spec], h = alone_held[bes[b]][spec];
        const SharedFigures s = seq[spec][b], i = inter[spec][b];
        t.rows.push_back({spec, bes[b], wk(a.prim_ms, a.prim_kernel_ms),
                          wk(s.prim_ms, s.prim_kernel_ms), fmt("%.2f", s.prim_ms / a.prim_ms),
                          wk(i.prim_ms, i.prim_kernel_ms), fmt("%.2f", i.prim_ms / a.prim_ms),
                          wk(h.prim_ms, h.prim_kernel_ms), wk(a.full_ms, a.full_kernel_ms),
                          wk(s.full_ms, s.full_kernel_ms), fmt("%.2f", s.full_ms / a.full_ms),
                          wk(i.full_ms, i.full_kernel_ms), fmt("%.2f", i.full_ms / a.full_ms)});
      }
    add(t);
  }

 private:
  std::string size_str() const {
    return std::to_string(o_.width) + "x" + std::to_string(o_.height);
  }
  static std::string embree_version() {
#ifdef RILL_BENCH_HAVE_EMBREE
    return RTC_VERSION_STRING;
#else
    return "3";
#endif
  }
  void add(Table t) {
    std::printf("\n%s", t.markdown().c_str());
    std::fflush(stdout);
    tables.push_back(std::move(t));
  }
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{
      "rill-bench-trace: the ray tracer's benchmarks (primary and full-shading "
      "throughput, Embree, grid and depth sweeps, kernel specialization, the path tracer's "
      "bounce rays against Embree)"};
  app.add_option("--sections", o.sections,
                 "comma list of throughput,embree,grid,depth,spec,bounce,whitted,shared (whitted: "
                 "full Whitted frames against a plain Embree renderer; shared: the GPU backends in "
                 "one process against each alone)")
      ->default_str(o.sections);
  app.add_option("--size", o.size, "image size WxH")->default_str(o.size);
  app.add_option("--scenes", o.scenes, "comma list: builtin:NAME, OBJ or JSON files")
      ->default_str(o.scenes);
  app.add_option("--backends", o.backends,
                 "all, or a comma list of cpu,simd,opencl,glsl,glsl-compute")
      ->default_str(o.backends);
  app.add_option("--repeats", o.repeats, "timed repeats (medians)")
      ->check(CLI::Range(1, 1000))
      ->default_str("3");
  app.add_option("--grid-scene", o.grid_scene, "scene of the grid sweep")
      ->default_str(o.grid_scene);
  app.add_option(
      "--subgrids", o.subgrids,
      "voxels listing more triangles than this get a subgrid, off, or auto (default: the "
      "renderer's choice per backend, 12 on the CPU and off on a GPU; the grid, depth and spec "
      "sections build one grid, the CPU's)");
  app.add_option("--grid-density", o.grid_density,
                 "voxels per triangle of the auto grid, 0.125..256, or auto (default: the "
                 "scene's, auto: the renderer's choice per backend and scene)");
  app.add_option("--accuracy", o.accuracy,
                 "accuracy of the throughput and Embree sections: strict or fast (fast: hits "
                 "may differ between backends, and are reported, not checked)")
      ->default_str(o.accuracy);
  app.add_option("--packets", o.packets,
                 "comma list of auto,on,off: the CPU backends once per setting, side by side")
      ->default_str(o.packets);
  app.add_option("--embree-modes", o.embree_modes,
                 "Embree's modes beside rtcIntersect1 in the embree section: auto (the packet "
                 "widths of 8 and 16 this CPU runs natively, and the stream), or a comma list of "
                 "4, 8, 16 (rtcIntersect4/8/16) and 1M (rtcIntersect1M)")
      ->default_str(o.embree_modes);
  app.add_option("--loops", o.loops,
                 "the megakernel loops of the throughput section's full frames, side by side: "
                 "comma list of auto, ray, segment (Tracer.h: MegakernelLoop)")
      ->default_str(o.loops);
  app.add_option("--grids", o.grids, "grid resolutions of the sweep: auto or N (N^3 voxels)")
      ->default_str(o.grids);
  app.add_option("--depth-scene", o.depth_scene, "scenes of the depth sweep (comma list)")
      ->default_str(o.depth_scene);
  app.add_option("--depths", o.depths, "depth range of the sweep, FIRST-LAST")
      ->default_str(o.depths);
  app.add_option("--sweep-backends", o.sweep_backends, "backends of the two sweeps")
      ->default_str(o.sweep_backends);
  app.add_option("--path-scenes", o.path_scenes,
                 "scenes of the bounce section (path integrator): default, or a comma list")
      ->default_str(o.path_scenes);
  app.add_option("--bounce", o.bounce,
                 "the bounce section's rays: after this many scatterings (0: camera rays)")
      ->check(CLI::Range(0, 64))
      ->default_str("2");
  app.add_option("--spp", o.spp, "samples per pixel of the bounce section's rays")
      ->check(CLI::Range(1, 64))
      ->default_str("1");
  app.add_option("--seed", o.seed, "the bounce section's path seed (default: the scene's)")
      ->check(CLI::Range(int64_t{0}, int64_t{0xffffffff}));
  app.add_option("--whitted-frames", o.whitted_frames,
                 "the whitted section's frames, a comma list: full (the scene as it is), camera "
                 "(shadows off and max depth 0: the camera rays' hits and their shading alone)")
      ->default_str(o.whitted_frames);
  app.add_option("--min-agree", o.min_agree, "fraction of rays Embree and Rill must agree on")
      ->check(CLI::Range(0.0, 1.0))
      ->default_str("0.999");
  app.add_option("--shared-alone", o.shared_alone)->group("");  // the shared section's child
  app.add_option("--shared-out", o.shared_out)->group("");
  app.add_option("--md", o.md, "also write the tables as Markdown to this file");
  app.add_option("--csv", o.csv, "also write the tables as CSV to this file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // an unknown option, a value out of range: status 2
    std::fprintf(stderr, "rill-bench-trace: %s (see --help)\n", e.what());
    return 2;
  }
  // Command-line errors (a value the option does not take): exit status 2, as rill-trace's,
  // before any scene loads.
  std::vector<std::string> sections;
  try {
    o.embree_mode_list = bench::parse_embree_modes(split_list(o.embree_modes));
    parse_size(o.size, o.width, o.height);
    if (o.accuracy != "strict" && o.accuracy != "fast")
      throw rt::SceneError("--accuracy: strict or fast (got '" + o.accuracy +
                           "'; double is the accuracy reference)");
    o.acc = rill::parse_accuracy(o.accuracy);
    o.loop_list.clear();
    for (const std::string& l : split_list(o.loops)) {
      try {
        o.loop_list.push_back(rt::parse_megakernel_loop(l));
      } catch (const std::invalid_argument&) {
        throw rt::SceneError("--loops: unknown loop '" + l + "' (auto, ray, segment)");
      }
    }
    for (const std::string& g : split_list(o.grids)) rt::parse_grid_resolution(g, "--grids");
    int first = 0, last = 0;
    parse_depths(o.depths, first, last);
    if (!o.subgrids.empty()) rt::parse_subgrid_min(o.subgrids);
    if (!o.grid_density.empty()) rt::parse_grid_density(o.grid_density);
    if (o.loop_list.empty()) throw rt::SceneError("--loops: name at least one loop");
    o.packets_list.clear();
    for (const std::string& p : split_list(o.packets))
      o.packets_list.push_back(rt::parse_packets(p));
    if (o.packets_list.empty()) throw rt::SceneError("--packets: name at least one setting");
    const std::vector<std::string> frames = split_list(o.whitted_frames);
    if (frames.empty()) throw rt::SceneError("--whitted-frames: name at least one frame");
    for (const std::string& f : frames)
      if (f != "full" && f != "camera")
        throw rt::SceneError("--whitted-frames: unknown frame '" + f + "' (full, camera)");
    sections = split_list(o.sections);
    for (const auto& s : sections)
      if (s != "throughput" && s != "embree" && s != "grid" && s != "depth" && s != "spec" &&
          s != "bounce" && s != "whitted" && s != "shared")
        throw rt::SceneError("--sections: unknown section '" + s +
                             "' (throughput, embree, grid, depth, spec, bounce, whitted, shared)");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-bench-trace: %s\n", e.what());
    return 2;
  }
  auto has = [&](const char* s) {
    return std::find(sections.begin(), sections.end(), s) != sections.end();
  };
  int rc = 0;
  try {
    std::printf("rill-bench-trace: %dx%d, %d repeats, %d threads\n", o.width, o.height, o.repeats,
                tbb::info::default_concurrency());
    Bench b(o);
    if (has("throughput") || has("embree"))
      b.throughput_and_embree(has("throughput"), has("embree"));
    if (has("grid")) b.grid_sweep();
    if (has("depth")) b.depth_sweep();
    if (has("spec")) b.specialization();
    if (has("bounce")) b.bounce_rays();
    if (has("whitted")) b.whitted_frames();
    if (has("shared")) b.shared_process();
    if (!o.md.empty()) {
      std::ofstream f(o.md);
      for (const auto& t : b.tables) f << t.markdown();
      if (!f) throw rt::SceneError("cannot write " + o.md);
    }
    if (!o.csv.empty()) {
      std::ofstream f(o.csv);
      for (const auto& t : b.tables) f << t.csv();
      if (!f) throw rt::SceneError("cannot write " + o.csv);
    }
    if (!b.ok) {
      std::fprintf(stderr, "rill-bench-trace: a check failed (see the tables)\n");
      rc = 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-bench-trace: %s\n", e.what());
    rc = 1;
  }
  rill::clear_kernel_cache();
  return rc;
}
