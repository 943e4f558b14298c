// The rill_* helper functions shared by the C and OpenCL C emitters.
//
// These give operations one meaning on every backend where C-family languages leave it
// open or disagree: wrapping integer arithmetic, division by zero, min/max with NaN, mod,
// sign, fract, saturating float-to-int conversion, clamped array indices. The text is
// valid C99 and OpenCL C 1.2. Before it, a dialect's prelude defines:
//   rill_real       float, or double in the `double` accuracy mode
//   RILL_M(fn)      the math library function for rill_real (sqrtf / sqrt)
//   RILL_FN         the storage class of helpers ("static inline")
//   int32_t, uint32_t, int64_t
#pragma once

#include <cstddef>
#include <string>

namespace rill::codegen {

const std::string& c_family_helpers();

// The 32-bit element count of each array (arr<k>_n32, from arr<k>_shape[0]) that 1D clamped
// gathers index with (CDialect::gather): declarations for an entry point that has set up
// arr<k>_shape.
std::string array_counts32(size_t arrays, const std::string& indent);

}  // namespace rill::codegen
