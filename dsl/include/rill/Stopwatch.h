// Stopwatch and ms_since: wall time since a point, in milliseconds, for the stage timings that
// Kernel::info() reports (capture, optimization, code generation, backend compile, driver
// finishing) and the renderer's and tools' own. Steady clock: the figures must not jump when
// the system clock is set.
#pragma once

#include <chrono>

namespace rill {

// Milliseconds from t until now: for timings that start from a stored time point (a frame's
// start, a job's) rather than from a Stopwatch.
inline double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  // Milliseconds since construction (or the last restart()).
  double ms() const { return ms_since(start_); }
  // Returns ms() and starts counting again from now: times consecutive stages.
  double lap() {
    auto now = std::chrono::steady_clock::now();
    double elapsed = std::chrono::duration<double, std::milli>(now - start_).count();
    start_ = now;
    return elapsed;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rill
