// rill-trace render in one process: the first frame (which compiles), then --bench-frames
// more of it or the other frames of --frames, the outputs, --stats-json and the stats line.
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "Commands.h"
#include "Doing.h"
#include "FramePlan.h"
#include "FrameReport.h"
#include "FrameSequence.h"
#include "Interrupt.h"
#include "Outputs.h"
#include "PartialName.h"
#include "Prepare.h"
#include "Progressive.h"
#include "distributed/Launch.h"
#include "rill/CompileProgressLine.h"
#include "rill/Stopwatch.h"
#include "rill/rt/scene/Pose.h"

namespace trace_cli {

using Clock = std::chrono::steady_clock;
using rill::ms_since;

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
  // "compiling 7 kernels for opencl (PoCL)... 3/7" on stderr while a compile that has run
  // for a second goes on: through the first render, which compiles (later frames' compiles
  // are reported by the frame line). Nothing when stderr is not a terminal.
  std::optional<rill::CompileProgressLine> compile_line;
  if (!o.quiet) compile_line.emplace(stderr);
  std::unique_ptr<Prepared> prepared = prepare(o);
  Prepared& p = *prepared;
  const rt::Scene& scene = p.scene;
  const rt::Grid& grid = p.grid;
  rt::Tracer& tracer = *p.tracer;
  const rt::RenderSettings& rs = p.rs;
  const double load_ms = p.load_ms;

  const FramePlan plan = plan_frames(o, p);
  const FrameSpan& span = plan.span;
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
  const bool progressive_path = progressive(o, p);
  if (progressive_path && (span.count() > 1 || o.bench_frames > 0 || animated) &&
      (o.time_limit > 0 || !o.save.empty() || !o.resume.empty()))
    throw rt::SceneError(
        "--time-limit, --save and --resume render one still frame (not with "
        "--frames, --bench-frames or an animated scene)");
  // SIGINT and SIGTERM from here on stop the render between passes, launches and frames
  // (Interrupt.h); before, while the scene loads and the kernels compile, they end the process
  // at once. Ended after the last frame: the video is ffmpeg's, which gets the terminal's
  // SIGINT itself.
  std::optional<InterruptGuard> interrupts(std::in_place);
  // Says that a signal stopped the render, what was done and what is on disk; the exit status.
  auto stopped = [](const std::string& what) {
    const int sig = interrupted();
    std::fprintf(stderr, "rill-trace: interrupted by %s %s\n", signal_name(sig), what.c_str());
    return interrupted_status(sig);
  };
  // Each frame's render stops after the pass in flight (render_progressive checks the same).
  rt::RenderSettings frame_rs = rs;
  frame_rs.after_pass = [](int) { return interrupted() == 0; };
  rt::RenderResult r = progressive_path ? render_progressive(o, p, first_camera)
                                        : tracer.render(frame_rs, first_camera);
  if (interrupted() != 0) {
    // An image of fewer samples than asked for never takes the whole one's name: a still is
    // written as its partial outputs (x.png -> x.partial.png), the mean of the samples done;
    // a sequence's frame cut short is dropped (the frames before it are the sequence's).
    const std::string frame = span.count() > 1 ? " of frame " + std::to_string(span.first) : "";
    std::string done = "after " + std::to_string(r.spp) + " of " +
                       std::to_string(std::max(p.scene.options.spp, 1)) + " samples per pixel" +
                       frame;
    if (span.count() == 1 && r.spp > 0) {
      g_doing = "writing the partial outputs";
      const std::vector<std::string> partial = write_outputs(o, p, r, partial_name);
      if (!partial.empty())
        done += "; wrote the image of " + std::to_string(r.spp) + " samples as " + partial.front() +
                (partial.size() > 1 ? " and the other partial outputs" : "");
    } else {
      done += "; no image written";
    }
    if (!progressive_path || o.save.empty())
      return stopped(done + (progressive_path ? " (--save keeps the sums, to resume from)" : ""));
    return stopped(done + "; saved the sums to " + o.save + " (--resume " + o.save +
                   " goes on from them)");
  }
  const double render_ms = ms_since(t_render);
  compile_line.reset();
  const double compile_ms = p.setup_ms + (render_ms - r.trace_ms);
  // Of that, the compile() calls (about 0 from a kernel cache), the first launches that trace
  // nothing (the drivers' first-use work: RenderResult::first_launch_ms); the rest is set-up:
  // uploading the scene and grid.
  const double kernels_ms = std::min(r.stages.compile_ms, compile_ms);
  const double first_launch_ms = std::min(r.first_launch_ms, compile_ms - kernels_ms);
  const double setup_ms = compile_ms - kernels_ms - first_launch_ms;

  // --bench-frames: the same frame again, each timed as the user's program would see it
  // (Tracer::render from call to return: launch, kernel, reductions, read-back, host work).
  // --overlap on: a repeat's read-back runs beside the next repeat's trace where the backend
  // allows (RenderSettings::read_back_later); a repeat's time is then its render and the wait
  // for the repeat before's read-back, and each repeat's read-back step includes its wait.
  std::vector<double> frame_ms, frame_trace_ms;
  std::vector<rt::FrameTimes> frame_times;
  rt::RenderSettings bench_rs = rs;
  bench_rs.read_back_later = o.overlap;
  rt::RenderResult frame;  // one result for every frame: its image memory is reused
  rt::RenderResult ahead;  // --overlap on: the repeat before, its read-back in flight
  auto wait_ahead = [&] {
    ahead.wait_outputs();
    frame_trace_ms.back() = ahead.trace_ms;
    frame_times.back().read_back = ahead.times.read_back;
  };
  for (int f = 0; f < o.bench_frames; ++f) {
    if (interrupted() != 0)
      return stopped("after " + std::to_string(f) + " of " + std::to_string(o.bench_frames) +
                     " --bench-frames repeats; nothing written");
    const auto t_frame = Clock::now();
    tracer.render(bench_rs, first_camera, frame);
    if (o.overlap && f > 0) wait_ahead();
    frame_ms.push_back(ms_since(t_frame));
    frame_trace_ms.push_back(frame.trace_ms);
    frame_times.push_back(frame.times);
    if (o.overlap) std::swap(frame, ahead);
  }
  if (o.overlap && o.bench_frames > 0) {
    const auto t_last = Clock::now();
    wait_ahead();
    frame_ms.back() += ms_since(t_last);
    // The last repeat is `ahead` after its swap: back into `frame`, whose rays are counted
    // below (after one repeat `frame` would otherwise be the empty result, and 0 Mrays/s).
    std::swap(frame, ahead);
  }
  const int64_t bench_rays = frame.rays;  // each repeat's (frame goes on to --frames' frames)
  std::vector<double> sorted = frame_ms;  // for the min and max
  std::sort(sorted.begin(), sorted.end());
  const double median_ms = median(frame_ms);
  // The median of each step over the frames (they need not add up to the median frame).
  auto median_of = [&](double rt::FrameTimes::*step) {
    std::vector<double> v;
    for (const rt::FrameTimes& t : frame_times) v.push_back(t.*step);
    return median(std::move(v));
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
  frame_stats[0].first_launch_ms = r.first_launch_ms;
  frame_stats[0].cold = r.cold;
  frame_stats[0].compiles = rill::kernel_cache_stats().misses - misses_before;
  frame_stats[0].rays = r.rays;
  frame_stats[0].launches = r.launches;
  // --frames: the other frames, back to back through the same tracer (compiled kernels, the
  // grid and the static arrays stay; Tracer::set_time moves the objects and their BVH).
  Progress progress(span.count(), o.quiet);
  progress.update(1, r.trace_ms);
  // --overlap on: frame k's outputs are written (encoded, compressed, saved) on a thread of
  // their own while frame k + 1 renders, at most one frame waiting behind the one being
  // written; the written results' memory comes back in `spare` for later frames. Declared
  // after what its writes use, so that it finishes them before those go.
  std::mutex spare_mutex;
  std::vector<rt::RenderResult> spare;
  FrameWriter writer;
  // --overlap on: frame k - 1's read-back also runs beside frame k's trace where the backend
  // allows (RenderSettings::read_back_later): it waits here in `previous` until frame k has
  // rendered, then goes to the writer; its wait is added to its trace time.
  rt::RenderSettings sequence_rs = frame_rs;
  sequence_rs.read_back_later = o.overlap;
  rt::RenderResult previous;
  int previous_k = -1;  // none waiting
  auto write_previous = [&] {
    if (previous_k < 0) return;
    previous.wait_outputs();
    frame_stats.back().trace_ms = previous.trace_ms;
    writer.wait_in_flight(1);
    writer.post([&, k = previous_k, image = std::move(previous)]() mutable {
      for (const std::string& w : write_outputs(o, p, image, frame_file(k))) written.push_back(w);
      std::lock_guard<std::mutex> lock(spare_mutex);
      spare.push_back(std::move(image));
    });
    previous = rt::RenderResult();
    previous_k = -1;
  };
  // A frame stopped by a signal is dropped; those before it are written and stay.
  auto stopped_in_frame = [&](int k, bool in_flight) {
    write_previous();
    writer.finish();
    progress.finish();
    return stopped((in_flight ? "in frame " : "before frame ") + std::to_string(k) + " of " +
                   std::to_string(span.first) + ".." + std::to_string(span.last) + "; frames " +
                   std::to_string(span.first) + ".." + std::to_string(k - 1) + " are written" +
                   (in_flight ? ", frame " + std::to_string(k) + " (in flight) is not" : ""));
  };
  for (int k = span.first + 1; k <= span.last; ++k) {
    if (interrupted() != 0) return stopped_in_frame(k, false);
    writer.check();  // a frame that could not be written ends the render now
    FrameStats fs;
    fs.frame = k;
    fs.time = animated ? scene.animation.time.time_of(k) : 0.0;
    g_doing = "rendering frame " + std::to_string(k);
    const int64_t misses = rill::kernel_cache_stats().misses;
    if (animated) fs.update = tracer.set_time(fs.time, bvh_update);
    const rt::Camera camera = rt::camera_at(scene, fs.time);
    rt::check_camera(camera, frame_camera_where(o.scene, scene, k));
    tracer.render(sequence_rs, camera, frame);
    if (interrupted() != 0) return stopped_in_frame(k, true);
    fs.trace_ms = frame.trace_ms;
    fs.compile_ms = frame.compile_ms;
    fs.first_launch_ms = frame.first_launch_ms;
    fs.cold = frame.cold;
    fs.compiles = rill::kernel_cache_stats().misses - misses;
    fs.rays = frame.rays;
    fs.launches = frame.launches;
    if (o.overlap) {
      write_previous();  // frame k - 1, now that frame k has rendered
      previous = std::move(frame);
      previous_k = k;
      std::lock_guard<std::mutex> lock(spare_mutex);
      frame = rt::RenderResult();
      if (!spare.empty()) {
        frame = std::move(spare.back());
        spare.pop_back();
      }
    } else {
      g_doing = "writing frame " + std::to_string(k);
      for (const std::string& w : write_outputs(o, p, frame, frame_file(k))) written.push_back(w);
    }
    frame_stats.push_back(fs);
    progress.update(k - span.first + 1, fs.trace_ms);
  }
  write_previous();  // the last frame
  writer.finish();   // the last frames' writes, and the first error of any
  progress.finish();
  if (interrupted() != 0)
    return stopped(
        "after the last frame was written; the video, --source and --stats-json are not");
  interrupts.reset();
  if (!o.video.empty()) {
    g_doing = "writing the video";
    write_video(p.out, span.first, scene.animation.time.fps, o.video);
    written.push_back(o.video);
  }
  write_source(o, p);

  // The rays, launches and trace time of every frame of --frames (the first alone without it;
  // --bench-frames' repeats are reported on their own).
  const FrameTotals all = totals(frame_stats);
  // Mrays/s from warm traces where there are any, else labelled cold (FrameReport.h).
  const Speed sp = speed(frame_stats, bench_rays, frame_trace_ms);
  const double rays_per_s = sp.rays_per_second;
  if (!o.stats_json.empty()) {
    nlohmann::json j = stats_json(o, p, r.width, r.height, all.rays);
    j["launches"] = all.launches;
    if (o.strategy == rt::Strategy::Multipass) {
      j["wait_threshold"] = rs.wait_threshold;
      j["masking"] = rs.masking;
    }
    if (o.strategy == rt::Strategy::Multipass || o.strategy == rt::Strategy::Wavefront) {
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
    j["rays_per_second_from"] = sp.from;
    j["rays_per_second_cold"] = sp.cold;
    j["trace_cold"] = r.cold;
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
                              {"compile", r.stages.compile_ms},
                              {"execution", r.stages.execution}};
    if (!frame_ms.empty())
      j["bench_frames"] = {{"frames", frame_ms.size()},
                           {"frame_ms", frame_ms},
                           {"trace_ms", frame_trace_ms},
                           {"rays", bench_rays},
                           {"median_ms", median_ms},
                           {"min_ms", sorted.front()},
                           {"max_ms", sorted.back()},
                           {"fps", median_ms > 0 ? 1000.0 / median_ms : 0.0},
                           {"device", rill::backend(o.backend).description()},
                           {"median_split_ms", split_json(median_split)}};
    j["time_ms"] = {{"load", load_ms},
                    {"grid_build", grid.build_ms},
                    {"compile", kernels_ms},
                    {"setup", setup_ms},
                    {"first_launch", first_launch_ms},
                    {"trace", all.trace_ms},
                    {"total", load_ms + grid.build_ms + compile_ms + all.trace_ms}};
    // The first frame's trace time, step by step (Tracer.h, FrameTimes).
    j["trace_split_ms"] = split_json(r.times);
    if (animated || span.count() > 1) j["frames"] = frames_json(frame_stats, tracer.features());
    write_json(o.stats_json, j);
  }
  // A mode that runs otherwise than the backend's name says (simd's double: scalar C).
  if (!o.quiet && !r.stages.execution.empty())
    std::printf("note: %s %s: %s\n", o.backend.c_str(), rill::accuracy_name(o.accuracy),
                r.stages.execution.c_str());
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
  if (const PathLaunches pl = path_launches(o, p); o.stats && pl.per_launch > 0)
    std::printf("path regeneration: %s, %d sample%s per launch (%s)\n",
                pl.per_launch > 1 ? "on" : "off", pl.per_launch, pl.per_launch > 1 ? "s" : "",
                pl.why.c_str());
  if (o.stats && o.strategy == rt::Strategy::Wavefront)
    std::printf("%-14s %8s %14s %14s %10s   (%lld pixels a launch)\n", "stage", "calls",
                "processed", "written", "ms", static_cast<long long>(r.width) * r.height);
  if (o.stats && o.strategy == rt::Strategy::Multipass)
    std::printf("%-14s %8s %14s %14s %10s   (masking %s, wait threshold %g)\n", "pass", "calls",
                "processed", "written", "ms", rs.masking ? "on" : "off", rs.wait_threshold);
  if (o.stats && (o.strategy == rt::Strategy::Multipass || o.strategy == rt::Strategy::Wavefront)) {
    for (const rt::PassStats& ps : r.passes)
      std::printf("%-14s %8lld %14lld %14lld %10.2f\n", ps.name.c_str(),
                  static_cast<long long>(ps.calls), static_cast<long long>(ps.processed),
                  static_cast<long long>(ps.written), ps.ms);
  }
  // "N frames of WxH" for a sequence, as a distributed render's line says.
  const std::string what =
      span.count() > 1 ? std::to_string(span.count()) + " frames of " : std::string();
  std::printf(
      "rill-trace: %s, %zu triangles, %s%dx%d, %s %s%s, grid %dx%dx%d: %.3f Mrays/s%s (%lld "
      "rays); load %.1f ms, grid build %.1f ms, compile %.1f ms%s, set-up %.1f ms, first launch "
      "%.1f ms, trace %.1f ms%s%s\n",
      scene.name.c_str(), scene.triangle_count(), what.c_str(), r.width, r.height,
      o.backend.c_str(), rill::accuracy_name(o.accuracy),
      o.strategy == rt::Strategy::Multipass ? " multipass" : "", grid.res.x, grid.res.y, grid.res.z,
      rays_per_s * 1e-6, sp.cold ? " cold" : "", static_cast<long long>(all.rays), load_ms,
      grid.build_ms, kernels_ms, r.from_cache ? " (cached)" : "", setup_ms, first_launch_ms,
      all.trace_ms,
      !r.cold            ? ""
      : span.count() > 1 ? " (the first frame cold)"
                         : " (cold)",
      o.strategy == rt::Strategy::Multipass
          ? (" (" + std::to_string(all.launches) + " launches)").c_str()
          : "");
  return 0;
}

}  // namespace trace_cli
