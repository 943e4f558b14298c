#include "FrameReport.h"

#include <algorithm>
#include <cstdio>

namespace trace_cli {

nlohmann::json split_json(const rt::FrameTimes& t) {
  return {{"setup", t.setup},           {"launch", t.launch}, {"kernel", t.kernel},
          {"accumulate", t.accumulate}, {"reduce", t.reduce}, {"read_back", t.read_back}};
}

nlohmann::json frames_json(const std::vector<FrameStats>& frames, const rt::Features& f) {
  nlohmann::json a = nlohmann::json::array();
  for (const FrameStats& s : frames) {
    nlohmann::json j = {{"frame", s.frame},
                        {"time", s.time},
                        {"trace_ms", s.trace_ms},
                        {"rays", s.rays},
                        {"compile_ms", s.compile_ms},
                        {"kernels_compiled", s.compiles},
                        {"first_launch_ms", s.first_launch_ms},
                        {"cold", s.cold}};
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

FrameTotals totals(const std::vector<FrameStats>& frames) {
  FrameTotals t;
  for (const FrameStats& s : frames) {
    t.rays += s.rays;
    t.launches += s.launches;
    t.trace_ms += s.trace_ms;
  }
  return t;
}

Speed speed(const std::vector<FrameStats>& frames, int64_t bench_rays,
            const std::vector<double>& bench_trace_ms) {
  auto per_second = [](int64_t rays, double ms) {
    return ms > 0 ? static_cast<double>(rays) / (ms * 1e-3) : 0.0;
  };
  if (!bench_trace_ms.empty())
    return {per_second(bench_rays, median(bench_trace_ms)), false, "bench frames"};
  FrameTotals warm;
  for (const FrameStats& s : frames)
    if (!s.cold) {
      warm.rays += s.rays;
      warm.trace_ms += s.trace_ms;
    }
  if (warm.trace_ms > 0) return {per_second(warm.rays, warm.trace_ms), false, "warm frames"};
  const FrameTotals all = totals(frames);
  return {per_second(all.rays, all.trace_ms), true, "cold first frame"};
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

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

}  // namespace trace_cli
