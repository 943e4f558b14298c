// `rill-trace noise`: what accuracy costs in time, for sampling (docs/accuracy.md, "Sampling
// noise against time").
//
// Renders a path-traced scene (default builtin:cornell-path) once with many samples per pixel
// as the reference (cached in an accumulation file, resumed to more samples when asked), then
// for spp = 1, 2, 4, ..., max on every backend, in every math mode, for each sampling variant
// (nee+mis: light sampling and BSDF sampling weighted by MIS; nee: light sampling only; bsdf:
// BSDF sampling only), renders the image with another seed (independent errors), times it
// (median of repeats after a warm-up render that compiles) and measures its RMSE over pixels
// and channels against the reference, and its relative RMSE (RMSE over the reference's mean).
// Fits log RMSE against log spp per series, over every spp and over spp >= 16 (the slope;
// -1/2 for an unbiased Monte Carlo estimate once the pixel-area error has gone), and for each
// target relative RMSE gives the samples and the time each backend needs. Checks that under strict
// every backend's image is bitwise the same (then so is the RMSE). Writes noise.md, noise.csv and
// noise.svg (two log-log panels, error against spp with the 1/sqrt(spp) line, and error against
// time).
//
// A subcommand beside `rill-trace accuracy` (AccuracyBench.h), not a bench/ program, for the
// same reason: it needs the ray tracer's scenes and tracer, and a user can measure a scene of
// their own with it.
#pragma once

#include <rill/rill.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rt {

struct NoiseBenchOptions {
  std::string scene = "builtin:cornell-path";
  std::vector<std::string> backends;  // empty: every available backend
  std::vector<std::string> variants;  // of nee+mis, nee, bsdf; empty: all three
  std::vector<rill::Accuracy> modes;  // empty: strict and fast
  int width = 32, height = 32;
  int max_spp = 256;  // spp runs over the powers of two up to this
  int repeats = 3;    // timed renders per point (the median is reported)
  // The reference: this many samples per pixel with nee+mis, strict, on ref_backend (empty:
  // simd if it can run here, else cpu), with ref_seed; the measured renders use `seed`.
  int ref_spp = 8192;
  std::string ref_backend;
  uint32_t ref_seed = 1000003, seed = 1;
  // Where the reference's sums are kept (empty: not kept). An existing file of the same
  // scene, size and seed is used as it is when it holds ref_spp samples or more, and resumed
  // to ref_spp when it holds fewer.
  std::string reference;
  std::vector<double> targets = {0.05, 0.01};  // relative RMSE
  // The line the targets and comparisons use is fitted over spp >= fit_from (and the slope
  // over every spp is reported beside it).
  int fit_from = 16;
  std::string out_dir = ".";
};

// Returns the process exit status (1 when strict images differ between backends).
int noise_bench(const NoiseBenchOptions& o);

}  // namespace rt
