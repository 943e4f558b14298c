// The CPU backend: kernels as C compiled by the system compiler, run on every core.
//
// compile() emits C (CEmitter), compiles it to a shared object once (SharedObjectCache) and
// loads it; run() splits the elements into ranges and calls the kernel's rill_run on oneTBB
// worker threads, summing the written counts. Streams are used in place in host memory.
//
// The same backend also registers as `simd`, which compiles the lockstep form of the
// kernel (LockstepEmitter): groups of 8 elements in vector registers, with masks for
// divergent control flow. Its results are bit for bit those of `cpu`.
//
// Accuracy modes map to compiler flags: strict is ISO C float arithmetic with FMA
// contraction off; fast adds -ffast-math's relaxations (without flushing denormals process-
// wide); double computes every Float in binary64.
#pragma once

#include <memory>

#include "rill/Backend.h"

namespace rill::cpu {

std::unique_ptr<Backend> make_backend();           // "cpu"
std::unique_ptr<Backend> make_lockstep_backend();  // "simd"
// The compiler flags used for an accuracy mode (shown by tools and docs).
std::vector<std::string> compiler_flags(Accuracy a);

}  // namespace rill::cpu
