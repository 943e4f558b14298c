// rill-trace render under mpirun: one image, or the frames of --frames, over every rank of the
// job (distributed/Farm.h, docs/distributed.md). Rank 0 hands out tiles and writes each frame
// as it completes; a render cut short leaves partial outputs with a note. A progressive render
// (--time-limit, --save, --resume) goes in rounds, each a farm job over every tile that goes on
// from the image's sums so far, which rank 0 keeps.
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <utility>

#include "Commands.h"
#include "Doing.h"
#include "FramePlan.h"
#include "Interrupt.h"
#include "Outputs.h"
#include "Prepare.h"
#include "Progressive.h"
#include "distributed/Farm.h"
#include "distributed/Launch.h"
#include "distributed/MpiSession.h"
#include "distributed/SceneHash.h"
#include "rill/Stopwatch.h"
#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Pose.h"

namespace trace_cli {

using Clock = std::chrono::steady_clock;
using rill::ms_since;

namespace {

// and depth are in the scene by now.
std::string pixel_settings(const RenderOptions& o) {
  return std::string("accuracy ") + rill::accuracy_name(o.accuracy) + "; knobs " + o.knobs.str();
}

// The outputs asked for, in the order write_outputs writes them.
std::vector<std::string> output_paths(const RenderOptions& o, const Prepared& p) {
  std::vector<std::string> paths;
  for (const std::string* path : {&p.out, &o.pfm, &o.depth, &o.prim, &o.normal, &o.exr})
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
// it wrote. The note goes first: when a rank dies, mpirun may end rank 0 at any moment, also
// between two of these files (a checkpoint's), and a partial image must never be left
// without its note. Ended between them, the note counts this checkpoint's tiles while the
// images still hold the previous checkpoint's (each file is replaced whole, never torn).
std::vector<std::string> write_partial(const RenderOptions& o, const Prepared& p,
                                       const rt::distributed::FarmResult& R,
                                       const rt::distributed::FramePart& part, const NameOf& file,
                                       const std::string& why) {
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
  rt::write_output_file(note, f.str());
  std::vector<std::string> written = write_outputs(o, p, part.image, [&](const std::string& path) {
    return rt::distributed::partial_name(file(path));
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

struct Rounds;
int finish_distributed(const RenderOptions& o, Prepared& p, const FramePlan& plan,
                       const rt::distributed::FarmResult& R, const DistributedFrames& frames,
                       const Rounds& rounds, rt::distributed::MpiSession& mpi,
                       Clock::time_point t_start);

// --tail-tile: as given, or half of --tile (tiles under 16 pixels are not cut).
int tail_tile_of(const RenderOptions& o) {
  return o.tail_tile >= 0 ? o.tail_tile : (o.tile >= 16 ? o.tile / 2 : 0);
}

// Whether the render goes in rounds: the path integrator's progressive options (prepare
// refuses them for Whitted).
bool in_rounds(const RenderOptions& o) {
  return o.time_limit > 0 || !o.save.empty() || !o.resume.empty();
}

// Rank 0's record of a render in rounds.
struct Rounds {
  int first = 0;    // samples per pixel resumed from (--resume)
  int reached = 0;  // samples per pixel in the image
  bool out_of_time = false;
  double seconds = 0;  // from the first round's start to the last one's end
  struct Round {
    int spp = 0;  // the samples per pixel it reached
    double ms = 0;
  };
  std::vector<Round> done;  // the rounds complete, in order
};

// Rank 0: the image in rounds (docs/distributed.md, "Rounds"). Each round is a farm job over
// every tile, from the sums of the rounds before (or --resume's) to a higher sample count: the
// first round one sample per pixel, each next one twice the last under --time-limit (but no
// more than the last round's rate fits in the time left, and at least one), at most
// --save-every, and without either to --spp at once. After each round rank 0 looks at the
// clock: past --time-limit, the round just done is the last. Each pixel adds its samples in
// sample order into the very floats a single process would, so the image and the sums are
// bitwise the single-process render of the samples reached. The sums go to --save after each
// round with --save-every, and after the last; the image goes to on_frame. A round left
// incomplete (a signal, every rank lost) ends the render: its result is that round's, and
// --save keeps the sums of the rounds complete (unless mpirun is ending the job).
rt::distributed::FarmResult render_rounds(
    const RenderOptions& o, const Prepared& p, rt::distributed::Farm& farm,
    rt::distributed::FarmJob job, const rt::distributed::Farm::RenderTile& render_tile,
    const rt::distributed::Farm::FrameDone& on_frame,
    const std::function<void(const rt::distributed::FarmResult&)>& checkpoint, Rounds& rounds) {
  namespace dist = rt::distributed;
  const rt::AccumulationKey key = accumulation_key(o, p);
  const int target = p.scene.options.spp;
  std::optional<rt::Accumulation> sums;
  if (!o.resume.empty()) sums = read_resume(o, p);
  rounds.first = sums ? sums->samples : 0;
  job.outputs.accumulation = true;
  rill::Stopwatch clock;
  dist::FarmResult total;
  rt::RenderResult image;
  int64_t rays = 0;
  int size = 1;  // the next round's samples under --time-limit
  for (;;) {
    const int done = sums ? sums->samples : 0;
    int next = target - done;
    if (o.time_limit > 0) next = std::min(next, size);
    if (o.save_every > 0) next = std::min(next, o.save_every);
    job.spp = done + next;
    job.resume = sums ? &*sums : nullptr;
    job.label = "round " + std::to_string(rounds.done.size() + 1) + ": samples " +
                std::to_string(done + 1) + ".." + std::to_string(job.spp) + " of " +
                std::to_string(target);
    std::optional<rt::RenderResult> got;
    const double start_ms = clock.ms();
    dist::FarmResult R = *farm.render(
        job, render_tile, [&](int, rt::RenderResult&& im) { got = std::move(im); }, checkpoint);
    // The report of every round: the last round's counts and ranks (whose tiles and busy time
    // the farm sums over the rounds), every round's tile times, gathering and wall time.
    std::vector<dist::FarmResult::TileTime> times = std::move(total.tile_times);
    times.insert(times.end(), R.tile_times.begin(), R.tile_times.end());
    const double wall_ms = total.wall_ms + R.wall_ms;
    const double gathered_bytes = total.gathered_bytes + R.gathered_bytes;
    const double gather_ms = total.gather_ms + R.gather_ms;
    const int gathered = total.gathered + R.gathered;
    total = std::move(R);
    total.tile_times = std::move(times);
    total.wall_ms = wall_ms;
    total.gathered = gathered;
    total.gathered_bytes = gathered_bytes;
    total.gather_ms = gather_ms;
    if (!total.complete() || !got) {
      if (!o.save.empty() && !rounds.done.empty() && !(total.interrupted && total.by_launcher)) {
        rt::write_accumulation(o.save, *sums, key);
        std::fprintf(stderr,
                     "rill-trace: saved the sums of the %d samples per pixel of the rounds "
                     "complete to %s (--resume %s goes on from them)\n",
                     sums->samples, o.save.c_str(), o.save.c_str());
      }
      return total;
    }
    rays += got->rays;
    sums = std::move(got->accumulation);
    got->accumulation = rt::Accumulation{};
    image = std::move(*got);
    rounds.done.push_back({sums->samples, clock.ms() - start_ms});
    const double s = clock.ms() * 1e-3;
    rounds.out_of_time = o.time_limit > 0 && s >= o.time_limit;
    const bool last = sums->samples >= target || rounds.out_of_time;
    if (!o.save.empty() && (last || o.save_every > 0)) rt::write_accumulation(o.save, *sums, key);
    if (last) break;
    if (o.time_limit > 0) {
      // Twice the last round, but no more than its rate fits in the time left.
      const double rate = next / std::max((clock.ms() - start_ms) * 1e-3, 1e-6);
      const double fits = std::min((o.time_limit - s) * rate, 1e9);
      size = std::max(1, std::min(2 * std::max(next, 1), static_cast<int>(fits)));
    }
  }
  farm.stop();
  rounds.reached = sums->samples;
  rounds.seconds = clock.ms() * 1e-3;
  image.rays = rays;
  image.spp = sums->samples;
  on_frame(job.first_frame, std::move(image));
  return total;
}

}  // namespace

// One image, or the frames of --frames, over every rank of the MPI job (distributed/Farm.h,
// docs/distributed.md).
int render_distributed(const RenderOptions& o) {
  namespace dist = rt::distributed;
  if (o.bench_frames > 0)
    throw rt::SceneError("--bench-frames times one process; it does not run under mpirun");
  // --albedo and --variance come back with each tile (Messages.h); --time-limit, --save and
  // --resume render in rounds (render_rounds).
  const bool rounds = in_rounds(o);
  dist::MpiSession mpi;
  const bool root = mpi.rank() == 0;
  const std::string who = "rank " + std::to_string(mpi.rank()) + " on " + mpi.host();
  const auto t_start = Clock::now();
  std::unique_ptr<Prepared> prepared;
  FramePlan plan;
  DistributedFrames frames;
  std::optional<dist::FarmResult> result;
  Rounds round_report;
  // What the farm's render thread uses, here rather than in the try block: after a signal
  // that thread may still be in a tile while rank 0 writes the partial outputs.
  rt::RenderSettings rs;
  int posed = -1;  // the frame the scene is posed at
  rt::Camera camera;
  dist::Farm::RenderTile render_tile;
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
          if (rounds && (plan.span.count() > 1 || plan.animated))
            throw rt::SceneError(
                "--time-limit, --save and --resume render one still frame (not with "
                "--frames or an animated scene)");
          // Every camera of the sequence, before any tile: a bad one stops the start.
          const rt::Scene& scene = prepared->scene;
          for (int k = plan.span.first; plan.animated && k <= plan.span.last; ++k)
            rt::check_camera(rt::camera_at(scene, scene.animation.time.time_of(k)),
                             frame_camera_where(o.scene, scene, k));
          return dist::scene_hash(scene, pixel_settings(o));
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
    render_tile = [&](const dist::Assign& a) {
      const dist::Tile& t = a.tile;
      const rt::Scene& scene = prepared->scene;
      if (plan.animated && t.frame != posed) {
        const double time = scene.animation.time.time_of(t.frame);
        prepared->tracer->set_time(time, plan.bvh_update);
        camera = rt::camera_at(scene, time);
        posed = t.frame;
      }
      rt::RenderSettings s = rs;
      s.window = {t.x, t.y, t.width, t.height};
      // A round's tile: up to the round's sample, from its slice of the sums so far.
      if (a.spp > 0) s.spp = a.spp;
      s.outputs.accumulation = a.accumulation;
      s.resume = a.resume.samples > 0 ? &a.resume : nullptr;
      return prepared->tracer->render(s, camera);
    };
    // Rank 0: each frame written as it completes; the frames begun kept on disk as partial
    // outputs while they render, as mpirun may kill rank 0 without warning.
    Progress progress(plan.span.count(), o.quiet || o.progress || !plan.sequence);
    FrameWriter writer;
    auto on_frame = [&](int frame, rt::RenderResult&& image) {
      writer.check();  // a frame that could not be written ends the render now
      const rt::Scene& scene = prepared->scene;
      frames.done.push_back({frame, plan.animated ? scene.animation.time.time_of(frame) : 0.0,
                             ms_since(t_start), image.rays});
      frames.rays += image.rays;
      frames.width = image.width;
      frames.height = image.height;
      for (const std::string& path : output_paths(o, *prepared))
        frames.written.push_back(plan.file(frame)(path));  // print_notes counts past a few
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
    if (root && rounds) {
      result =
          render_rounds(o, *prepared, farm, job, render_tile, on_frame, checkpoint, round_report);
    } else {
      result = farm.render(job, render_tile, on_frame, checkpoint);  // workers: every round
      if (result && result->complete()) farm.stop();
    }
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
    if (rounds && R.complete() && !o.quiet && (o.time_limit > 0 || round_report.first > 0))
      std::printf("path: %d samples per pixel%s%s in %.1f s, %zu rounds\n", round_report.reached,
                  round_report.first > 0
                      ? (" (" + std::to_string(round_report.first) + " resumed)").c_str()
                      : "",
                  round_report.out_of_time ? ", stopped by --time-limit" : "", round_report.seconds,
                  round_report.done.size());
    return finish_distributed(o, *prepared, plan, R, frames, round_report, mpi, t_start);
  } catch (const std::exception& e) {
    if (!R.must_abort) throw;  // main reports it; MPI_Finalize finds every rank
    std::fprintf(stderr, "rill-trace: %s\n", e.what());
    std::fflush(stderr);
    mpi.abort(1);
  }
}

namespace {

// Rank 0, every frame back (or the farm ended without some): writes what there is of the
// frames not complete, the video and the stats, and reports.
int finish_distributed(const RenderOptions& o, Prepared& p, const FramePlan& plan,
                       const rt::distributed::FarmResult& R, const DistributedFrames& frames,
                       const Rounds& rounds, rt::distributed::MpiSession& mpi,
                       Clock::time_point t_start) {
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
        !R.interrupted ? "every rank was lost"
        : R.by_launcher
            ? "stopped by a signal: mpirun ends the job when a rank dies, and names the rank "
              "and its host (mpirun --enable-recovery goes on without it)"
            : std::string("interrupted by ") + signal_name(R.signal) +
                  " sent to rank 0; the other ranks were stopped";
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
    if (R.interrupted && R.by_launcher) std::_Exit(1);  // mpirun is ending the job
    // Interrupted: every rank was stopped and rank 0's lane is idle, so the job ends through
    // MPI_Finalize with the signal's status; else a tile of rank 0's may still be rendering.
    if (R.interrupted && !R.must_abort) return interrupted_status(R.signal);
    if (R.interrupted) std::_Exit(interrupted_status(R.signal));
    mpi.abort(1);
  }
  std::vector<std::string> written = frames.written;
  if (!o.video.empty()) {
    g_doing = "writing the video";
    write_video(p.out, plan.span.first, p.scene.animation.time.fps, o.video);
    written.push_back(o.video);
  }
  write_source(o, p);  // the variant the tiles ran
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
    if (!rounds.done.empty()) {
      // A render in rounds: each round's samples per pixel reached and wall time.
      nlohmann::json list = nlohmann::json::array();
      for (const Rounds::Round& r : rounds.done) list.push_back({{"spp", r.spp}, {"ms", r.ms}});
      j["distributed"]["rounds"] = list;
      j["spp_reached"] = rounds.reached;
    }
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
      o.backend.c_str(), rill::accuracy_name(o.accuracy), R.ranks.size(), R.tiles, o.tile,
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

}  // namespace

}  // namespace trace_cli
