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

// A compiled kernel over so's rill_run. lanes: 0 for scalar C (emit_c), else the lanes of a
// lockstep kernel (simd), which takes unmasked 2D launches in row pairs and arrays under 2^31
// words.
std::unique_ptr<CompiledKernel> make_host_kernel(std::string source, SharedObject so, int lanes);

// "NAME: WHAT<compiler>, N threads (oneTBB), cache DIR": a CPU backend's info line.
std::string host_backend_description(const std::string& name, const std::string& what);

}  // namespace rill::cpu
