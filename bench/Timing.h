// Timing helpers shared by the benchmarks: wall-clock milliseconds and the median of
// repeated measurements (benchmarks report medians of interleaved repeats, never means, so
// one descheduled run on a shared machine does not move the figure).
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

#include "rill/Stopwatch.h"

namespace rill::bench {

using Clock = std::chrono::steady_clock;

using rill::ms_since;

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace rill::bench
