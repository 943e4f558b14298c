// Stopwatch: wall time since a point, in milliseconds, for the stage timings that
// Kernel::info() reports (capture, optimization, code generation, backend compile, driver
// finishing). Steady clock: the figures must not jump when the system clock is set.
#pragma once

#include <chrono>

namespace rill {

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  // Milliseconds since construction (or the last restart()).
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }
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
