// The CPU backend: kernels as C compiled by the system compiler, run on every core.
//
// compile() emits C (CEmitter), compiles it to a shared object once (SharedObjectCache) and
// loads it; the host launcher (HostKernel.h) splits the elements into ranges and calls the
// kernel's rill_run on oneTBB worker threads. Streams are used in place in host memory.
//
// The `simd` backend (backends/simd/) runs the lockstep form of the kernel on the same
// launcher: groups of 8 elements in vector registers, bit for bit `cpu`'s results.
//
// Accuracy modes map to compiler flags: strict is ISO C float arithmetic with FMA
// contraction off; fast adds -ffast-math's relaxations (without flushing denormals process-
// wide); double computes every Float in binary64.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rill/Backend.h"

namespace rill::cpu {

std::unique_ptr<Backend> make_backend();  // "cpu"
// The compiler flags used for an accuracy mode (shown by tools and docs).
std::vector<std::string> compiler_flags(Accuracy a);
// Whether this CPU has SSE4.1 (scalar kernels get -msse4.1 then).
bool has_sse41();
// A kernel as cpu compiles it (scalar C), for `backend`'s cache entries: simd's double mode
// runs this too.
// How cpu lays out a kernel's C (CEmitter.h): outlined functions over up to 4 translation
// units, unless $RILL_CPU_OUTLINE says `off` (one function) or another outlining threshold.
struct CLayout;
CLayout c_layout();
// `source_map`: CompileOptions::source_map.
std::unique_ptr<CompiledKernel> compile_scalar_c(const std::string& backend, const ir::Function& f,
                                                 Accuracy a, bool source_map = false);

}  // namespace rill::cpu
