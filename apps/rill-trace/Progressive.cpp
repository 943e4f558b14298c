// Progressive path rendering (Progressive.h).
#include "Progressive.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "Interrupt.h"
#include "ProgressBar.h"
#include "distributed/SceneHash.h"
#include "rill/Stopwatch.h"
#include "rill/rt/film/AccumulationFile.h"

namespace trace_cli {

// The scene as loaded with the command line's changes, and what decides its pixels beyond the
// scene (the accuracy and the knobs).
rt::AccumulationKey accumulation_key(const RenderOptions& o, const Prepared& p) {
  const std::string settings = std::string(rill::accuracy_name(o.accuracy)) + " " + o.knobs.str();
  return {rt::distributed::accumulation_hash(p.scene, settings), p.scene.options.seed};
}

rt::Accumulation read_resume(const RenderOptions& o, const Prepared& p) {
  rt::Accumulation sums =
      rt::read_accumulation(o.resume, accumulation_key(o, p), p.scene.width, p.scene.height);
  if (sums.samples > p.scene.options.spp)
    throw rt::SceneError(o.resume + ": holds " + std::to_string(sums.samples) +
                         " samples per pixel, more than the " +
                         std::to_string(p.scene.options.spp) + " asked for (--spp)");
  if (o.variance && sums.squares.empty())
    throw rt::SceneError(o.resume +
                         ": saved without --variance, so it holds no sums of squares and the "
                         "variance of a render resumed from it cannot be known (save with "
                         "--variance, or resume without it)");
  return sums;
}

namespace {

// "samples 12/64 [=====>     ] 18%, 35.2 samples/s, 1.5 s left" on stderr, where it is a
// terminal and not --quiet.
class SampleProgress {
 public:
  SampleProgress(int first, int total, double limit_s, bool quiet)
      : first_(first), total_(total), limit_s_(limit_s), on_(!quiet && isatty(2)) {}
  void update(int done) {
    if (!on_) return;
    const double s = clock_.ms() * 1e-3;
    const double rate = s > 0 ? (done - first_) / s : 0.0;
    double left = rate > 0 ? (total_ - done) / rate : 0.0;
    if (limit_s_ > 0) left = std::min(left, std::max(limit_s_ - s, 0.0));
    std::fprintf(stderr, "\rsamples %d/%d %s %3d%%, %.1f samples/s, %.1f s left   ", done, total_,
                 progress_bar(done, total_).c_str(), total_ > 0 ? 100 * done / total_ : 100, rate,
                 left);
    std::fflush(stderr);
  }
  void finish() {
    if (on_) std::fprintf(stderr, "\n");
  }
  double seconds() const { return clock_.ms() * 1e-3; }

 private:
  int first_, total_;
  double limit_s_;
  bool on_;
  rill::Stopwatch clock_;
};

}  // namespace

bool progressive(const RenderOptions& o, const Prepared& p) {
  if (p.scene.options.integrator != rt::Integrator::Path) return false;
  return o.time_limit > 0 || !o.save.empty() || !o.resume.empty() || p.rs.spp > 1 ||
         p.scene.options.spp > 1;
}

rt::RenderResult render_progressive(const RenderOptions& o, Prepared& p, const rt::Camera& camera) {
  const rt::AccumulationKey key = accumulation_key(o, p);
  const int target = p.scene.options.spp;
  std::optional<rt::Accumulation> sums;
  if (!o.resume.empty()) sums = read_resume(o, p);
  const int first = sums ? sums->samples : 0;
  SampleProgress progress(first, target, o.time_limit, o.quiet);
  bool out_of_time = false;
  rt::RenderSettings rs = p.rs;
  rs.spp = target;
  // A time limit is checked after each launch: one sample each, so that it stops on time (the
  // path megakernel otherwise runs several per launch, Megakernel.h).
  if (o.time_limit > 0) rs.path_samples_per_launch = 1;
  rs.after_pass = [&](int done) {
    progress.update(done);
    out_of_time = o.time_limit > 0 && progress.seconds() >= o.time_limit;
    // SIGINT or SIGTERM: the sums of the passes done are saved below, as for --time-limit.
    return !out_of_time && interrupted() == 0;
  };
  const bool chunks = o.save_every > 0;
  rt::RenderResult total, first_chunk;  // first_chunk: sample 0's AOVs (RenderResult.h)
  const rt::FrameOutputs outputs = rs.outputs;
  int64_t rays = 0;
  double trace_ms = 0;
  int chunk = 0;
  do {
    const int done = sums ? sums->samples : 0;
    rs.spp = chunks ? std::min(target, done + o.save_every) : target;
    rs.resume = sums ? &*sums : nullptr;
    rs.outputs = chunk == 0 ? outputs : outputs.without_aovs();
    rs.outputs.accumulation = !o.save.empty() || (chunks && rs.spp < target);
    p.tracer->render(rs, camera, total);
    if (chunk++ == 0) rt::move_aovs(total, first_chunk);
    rays += total.rays;
    trace_ms += total.trace_ms;
    if (rs.outputs.accumulation) {
      sums = std::move(total.accumulation);
      if (!o.save.empty()) rt::write_accumulation(o.save, *sums, key);
    }
  } while (chunks && !out_of_time && interrupted() == 0 && sums && sums->samples < target);
  progress.finish();
  rt::move_aovs(first_chunk, total);
  total.rays = rays;
  total.trace_ms = trace_ms;
  if (!o.quiet && (o.time_limit > 0 || first > 0) && interrupted() == 0)
    std::printf("path: %d samples per pixel%s%s in %.1f s\n", total.spp,
                first > 0 ? (" (" + std::to_string(first) + " resumed)").c_str() : "",
                out_of_time ? ", stopped by --time-limit" : "", progress.seconds());
  return total;
}

}  // namespace trace_cli
