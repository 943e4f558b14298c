// `rill-trace accuracy`: what each accuracy knob costs in time and buys in error.
//
// Renders a small built-in scene set (closed meshes, seen from outside and inside, for holes, a lit
// floor far from the origin for acne, a lit floor scaled tiny, the Cornell box with a mirror,
// glass) with every setting of the knobs (math mode x triangle test x self-intersection offset x
// traversal, and the reflection depth and samples per pixel) on every available backend, and
// compares each image with a deep double-precision reference (cpu, double, watertight, scaled
// offset, depth 8). Prints and writes side by side: trace time (median of interleaved repeats),
// RMSE and PSNR, holes (pixels whose camera ray leaks through a closed mesh) and acne
// (self-shadowed pixels of a lit flat floor). Writes accuracy.md, accuracy.csv,
// accuracy.gp and (with gnuplot) accuracy.svg, the error against the time.
//
// A subcommand rather than a program in bench/: it needs the ray tracer's scenes, tracer
// and image code, which live in the rill-trace program's library, and `rill-trace` is
// what a user has at hand to measure a scene of their own the same way.
#pragma once

#include <string>
#include <vector>

namespace rt {

struct AccuracyBenchOptions {
  std::vector<std::string> backends;  // empty: every available backend
  std::vector<std::string> scenes;    // empty: all of the set
  int width = 64, height = 48;
  int repeats = 3;        // interleaved timing repeats (the median is reported)
  bool factorial = true;  // every knob combination (false: one knob at a time)
  std::string out_dir = ".";
};

// Returns the process exit status.
int accuracy_bench(const AccuracyBenchOptions& o);

}  // namespace rt
