// The rill_* helper functions of every dialect, in one table (Helpers.cpp).
//
// Generated code calls a rill_* helper wherever C-family languages leave an operation's
// meaning open or disagree on it: wrapping integer arithmetic, division by zero, min/max with
// NaN, mod, sign, fract, saturating float-to-int conversion, array indices under a boundary
// mode, and in GLSL comparisons and selections on bit patterns and correctly rounded division
// and square root. Each helper is one entry of the table, with its body in every dialect that
// has one; every emitter assembles its prelude from the table (helper_bodies), after a frame
// of its own that defines what the bodies assume:
//   C, OpenCL C, lockstep C: rill_real (float, or double in the `double` accuracy mode),
//     RILL_M(fn) (the math library function for rill_real: sqrtf / sqrt), RILL_FN (the
//     storage class of helpers, "static inline"), int32_t, uint32_t, int64_t; lockstep C
//     also its vector types, rill_sel_i/r, RILL_CMP, RILL_AVX2, RILL_AVX512 (RILL_ROUND16,
//     RILL_SQRT16) and RILL_LANES1/2.
//   GLSL: RILL_PRECISE, RILL_ONE, RILL_ZERO_I, RILL_NATIVE_COMPARE, RILL_FLUSHES_DENORMALS,
//   RILL_ABS_ON_BITS (the Vulkan dialect).
// An op's HELPER form (dsl/include/rill/ir/Ops.def) names its entry; tests/backends/
// HelpersTest.cpp fails when a dialect's generated source lacks one of them.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "rill/ir/IR.h"

namespace rill::codegen {

// The languages a body is written in. A C body serves OpenCL C too, unless the helper has
// an OpenCL body of its own. Lockstep C bodies define the lane-wise twin, rill_v_NAME.
enum class Language { C, OpenCL, Glsl, Lockstep };

// The preludes of a language that take a body: Any, all of them; the others only GLSL's
// division and square root use, which depend on the accuracy mode and the driver's rule
// (glsl/DivSqrt.h): Fast, the fast mode's; in strict mode, DriverOps or InexactOps (the
// driver's `/` and sqrt, or the inexact test stand-ins) and Uncorrected or Corrected, and for
// Corrected the exact residual's form: SplitResidual (Dekker's product, any driver) or
// FusedResidual (one fma, drivers whose fma rounds once); or, in place of Corrected and the
// residual, Lean (the short correction by fmas of glsl/lean/*.glsl, drivers whose fma rounds
// once).
enum class Variant {
  Any,
  Fast,
  DriverOps,
  InexactOps,
  Uncorrected,
  Corrected,
  SplitResidual,
  FusedResidual,
  Lean
};

struct Body {
  Language language;
  // Whole definitions, with the comments the generated code carries (a newline is added
  // after a last line that has none).
  const char* text;
  Variant variant = Variant::Any;
};

struct Helper {
  const char* name;  // the function is rill_NAME (lockstep C: rill_v_NAME)
  std::vector<Body> bodies;
  // Defined only in the kernels that call it (on_demand_bodies), not in every prelude: the
  // helpers added after the kernel caches and the identity records of today's kernels, so that
  // a kernel that does not use them keeps its source, and with it its cache entries.
  bool on_demand = false;
};

// The table, in the order every prelude defines the helpers (a helper before its users).
const std::vector<Helper>& helper_table();

// The bodies in language d, in the table's order, for the prelude that takes `variants` (and
// Any). `missing`, when given, supplies the text of a helper that has no body in d (lockstep
// C's lane-wise wrappers); it may return "".
std::string helper_bodies(Language d, const std::vector<Variant>& variants = {},
                          const std::function<std::string(const Helper&)>& missing = {});

// The bodies in language d of the on-demand helpers (Helper::on_demand) that kernel f calls
// through an op's HELPER form, in the table's order; helper_bodies leaves them out. They use
// no other helper, so a prelude may end with them.
std::string on_demand_bodies(Language d, const ir::Function& f,
                             const std::function<std::string(const Helper&)>& missing = {});

// The 32-bit element count of each array (arr<k>_n32, from arr<k>_shape[0]) that 1D clamped
// gathers index with (CDialect::gather): declarations for an entry point that has set up
// arr<k>_shape.
std::string array_counts32(size_t arrays, const std::string& indent);

}  // namespace rill::codegen
