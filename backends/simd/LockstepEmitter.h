// Emits a kernel as lockstep SIMD C for the `simd` backend (see LockstepEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::simd {

// Lanes per group: 8 binary32 values fill one AVX register; 16 fill an AVX-512 register,
// the simd backend's strict kernels where the CPU has AVX-512 (SimdBackend.cpp).
constexpr int kLockstepLanes = 8;
constexpr int kWideLanes = 16;

// The kernel as C over `lanes` elements at a time: every variable becomes a GCC/Clang vector
// of `lanes` values, control flow becomes masks, and each element computes exactly the
// operations the scalar C of emit_c() computes, so the results are bit for bit the same.
// `source_map`: with #line directives naming the user's lines (codegen/SourceMap.h).
std::string emit_c_lockstep(const ir::Function& optimized, Accuracy accuracy,
                            int lanes = kLockstepLanes, bool source_map = false);

}  // namespace rill::simd
