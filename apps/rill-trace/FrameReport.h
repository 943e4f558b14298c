// The report of a sequence's frames (rill-trace render --frames, --bench-frames): each
// frame's times for --stats-json, and the summary line.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "rill/rt/Tracer.h"

namespace trace_cli {

// One frame of a sequence (--frames): where it is in time, what moving its objects cost
// (Tracer::set_time), its trace time, rays and launches.
struct FrameStats {
  int frame = 0;
  double time = 0;
  rt::FrameUpdate update;
  double trace_ms = 0, compile_ms = 0;
  double first_launch_ms = 0;  // of compile_ms: first launches at the size (RenderResult)
  bool cold = false;           // the first frame traced at its size (RenderResult::cold)
  int64_t compiles = 0;        // kernels compiled for it (misses of Rill's in-process kernel cache)
  int64_t rays = 0, launches = 0;
};

// The frames together: what the stats line and --stats-json report for a sequence, every
// frame counted (as a distributed render counts them).
struct FrameTotals {
  int64_t rays = 0, launches = 0;
  double trace_ms = 0;
};
FrameTotals totals(const std::vector<FrameStats>& frames);

// The speed a render reports (the stats line's Mrays/s, --stats-json's rays_per_second): from
// warm traces where there are any, --bench-frames' repeats (the frame's rays over their median
// trace time) or else the frames of a sequence that were not cold; from the cold first frame
// only when nothing else was traced, and then labelled so.
struct Speed {
  double rays_per_second = 0;
  bool cold = false;
  const char* from = "";  // "bench frames", "warm frames", "cold first frame"
};
Speed speed(const std::vector<FrameStats>& frames, int64_t bench_rays,
            const std::vector<double>& bench_trace_ms);

// The frames as --stats-json's "frames" array (with each frame's update when the scene is
// dynamic).
nlohmann::json frames_json(const std::vector<FrameStats>& frames, const rt::Features& f);

// A frame's trace time step by step (Tracer.h, FrameTimes) as JSON.
nlohmann::json split_json(const rt::FrameTimes& t);

// The middle element of v (the upper one of an even count); 0 for none.
double median(std::vector<double> v);

// "48 frames (0..47): trace median 12.3 ms; BVH rebuilt, median 0.4 ms (600 moving
// triangles); upload 0.2 ms; compiled once".
void print_frames_summary(const std::vector<FrameStats>& frames);

}  // namespace trace_cli
