// How the CPU backends (cpu, and simd: backends/simd/) run a kernel: its C compiled to a
// shared object once (SharedObjectCache), whose rill_run the host calls over ranges of
// elements on oneTBB's worker threads, summing the written counts; masked launches run each
// maximal run of selected elements. Streams are used in place in host memory.
#pragma once

#include <memory>
#include <string>

#include "SharedObjectCache.h"
#include "rill/Backend.h"

namespace rill::cpu {

// The rows of a lockstep kernel's tiles on a 2D stream (rill_next_group in
// backends/simd/LockstepEmitter.cpp): 4 x 2 tiles at 8 lanes, 4 x 4 at 16 (nearer neighbours
// than 8 x 2, so fewer divergent lanes). The host hands such a kernel ranges of whole tile rows.
constexpr int lockstep_tile_rows(int lanes) {
  return lanes >= 16 ? 4 : 2;
}

// A compiled kernel over so's rill_run. lanes: 0 for scalar C (emit_c), else the lanes of a
// lockstep kernel (simd), which takes unmasked 2D launches in ranges of whole tile rows
// (lockstep_tile_rows) and arrays under 2^31 words.
std::unique_ptr<CompiledKernel> make_host_kernel(std::string source, SharedObject so, int lanes);

// "NAME: WHAT<compiler>, N threads (oneTBB), cache DIR": a CPU backend's info line.
std::string host_backend_description(const std::string& name, const std::string& what);

}  // namespace rill::cpu
