// Running generated programs on backends and on the reference interpreter, comparing the
// results bit for bit, and shrinking a failing program to a small reproducer.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "Generator.h"

namespace rill::difftest {

// One way of running kernels whose results are compared with the reference.
struct Target {
  std::string backend;      // "cpu", "opencl", "glsl"
  bool passes_off = false;  // compiled with every optimizer pass switched off
  bool ftz = false;         // the backend flushes denormals to zero (probed)
  std::string name() const;
};

// Whether `backend` flushes denormals to zero; probed once with a small kernel.
bool flushes_denormals(const std::string& backend);

struct Options {
  std::vector<Target> targets;
  // Also interpret the program optimized with every pass off, and compare with the reference
  // (the optimizer must not change results; costs no compile).
  bool check_unoptimized = false;
  // Also interpret the reference lowered for lockstep lanes (passes::lower_lockstep, read as a
  // scalar kernel), and compare (the simd backend's lowering must not change results).
  bool check_lockstep = false;
  bool denormals = true;       // launch data may contain denormals
  bool verbose = false;        // print every program's IR
  bool stop_at_first = false;  // stop a batch at its first failure
};

struct Failure {
  // "mismatch", or what threw: "capture", "optimize", "interpret" (the reference's steps),
  // "compile", "run" (a target's).
  std::string kind;
  std::string target;  // Target::name(), "reference" or "reference (passes off)"
  size_t sub = 0;      // which program of the batch
  std::string message;
  bool same_as(const Failure& o) const { return kind == o.kind && target == o.target; }
  // "mismatch on glsl", "compile threw (opencl)", "optimize threw (reference)".
  std::string title() const {
    return kind == "mismatch" ? kind + " on " + target : kind + " threw (" + target + ")";
  }
};

struct Stats {
  int64_t programs = 0, failed = 0, kernels = 0, launches = 0, elements = 0;
  int64_t excused = 0;  // denormal-tainted elements that differed on a flushing backend
  int64_t tainted = 0;  // denormal-tainted elements seen on flushing backends
  double capture_s = 0, reference_s = 0, compile_s = 0, run_s = 0, shrink_s = 0;
  std::string summary() const;
};

// Captures `subs` as one kernel, runs program k of it (with its own launch data) on every
// target and on the reference, and returns each failing program's first failure (one
// failure for the whole batch if capturing, optimizing or compiling fails).
std::vector<Failure> run_batch(const std::vector<ProgramSpec>& subs, const Options& opt,
                               Stats& stats);

// The full report for a failure: seed, program IR, first difference; then, unless disabled,
// a shrunk reproducer with the same. `filter` is the gtest filter that reruns this test.
std::string report_failure(const std::vector<ProgramSpec>& subs, const Failure& failure,
                           const Options& opt, bool shrink, double shrink_seconds, Stats& stats,
                           const std::string& filter);

// CPU time of this process and its waited-for children (the CPU backend's C compiler), in
// seconds: what a run costs on a machine of its own, however loaded this one is.
double cpu_seconds();

// "0x1234abcd...".
std::string hex(uint64_t v);

}  // namespace rill::difftest
