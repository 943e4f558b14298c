// Correctly rounded float division and square root in GLSL, for drivers whose own are not.
//
// GLSL only promises 2.5 ulp for `/` and `sqrt` (GLSL 4.30, section 4.7.1); NVIDIA's compute
// a / b as a * rcp(b) and sqrt(x) as x * rsqrt(x). Strict mode needs the correctly rounded
// results every other backend gives, so where the driver is not known to be exact the
// generated shader calls helpers that correct the driver's estimate with exact arithmetic
// built only from +, -, * (which GLSL does round correctly) and bit operations:
//
//   1. Special operands (0, inf, NaN; subnormals count as zero, as on flushing GPUs) are
//      decided from their bits; the significands are scaled into [1, 2) (or [1, 4)).
//   2. The driver's quotient (root) is refined by one Newton step whose residual a - q*b
//      (x - s*s) is computed exactly: Dekker's two-product, Sterbenz's lemma for the
//      subtraction, or where the driver's fma rounds once (fused_fma_mode), one fma. The
//      result is then a faithful rounding.
//   3. For a faithful q the residual is exactly representable (Markstein), so comparing it
//      with half the distance to each neighbour picks the correctly rounded neighbour. A
//      quotient or root of floats is never exactly halfway, so there are no ties.
//   4. The exponent is put back with integer arithmetic; results too small for a normal
//      float are flushed to zero judging by the exact result (tininess before rounding, as
//      llvmpipe does), results too large become infinity.
//
// Where the driver's fma is fused, the lean rule (the default) replaces steps 2-3 with a
// shorter correction (glsl/lean/div.glsl, sqrt.glsl): every normal operand pair is scaled as
// in step 1 and takes one branch-free path. Division: Markstein's step from the driver's
// reciprocal, then the signs of exact residuals at q +- half an ulp pick the neighbour. Square
// root: the driver's inversesqrt, one coupled Newton step and a fused final correction. One
// driver operation instead of two. tools/divsqrt-check proves the exact GLSL text on the host
// with the driver's estimate any float within 3 of the correctly rounded one (GLSL allows 2.5
// ulp): every sqrt input, division's hardest quotients and every pair of exponents.
//
// The mode comes from RILL_GLSL_DIVSQRT (see divsqrt_mode); two test modes replace the
// driver's operations with NVIDIA-like inexact ones, so that the correction can be tested
// on any machine (tests/backends, conformance). The GLSL bodies of rill_div_f, rill_sqrt and
// their parts are entries of the helper table (codegen/Helpers.cpp), one variant per mode.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "../codegen/Helpers.h"

namespace rill::glsl {

enum class DivSqrt {
  Native,            // the driver's / and sqrt (known exact: Mesa llvmpipe)
  Corrected,         // the driver's estimate, corrected to the correctly rounded result
  Inexact,           // test mode: a * (1 / b) and x * inversesqrt(x), uncorrected
  InexactCorrected,  // test mode: the same inexact estimates, corrected
};

const char* divsqrt_name(DivSqrt m);

// RILL_GLSL_DIVSQRT = auto (default) | native | corrected | inexact | inexact-corrected.
// auto: native on drivers known to divide and take roots exactly (Mesa's llvmpipe, which
// compiles them to IEEE instructions), corrected on every other driver. Throws on an unknown
// value.
DivSqrt divsqrt_mode(const std::string& renderer);

// Whether mode m corrects the driver's estimates (Corrected, InexactCorrected).
bool divsqrt_corrects(DivSqrt m);

// Whether the corrections compute their exact residual a - q*b as one fma(-q, b, a) (a
// tenth of the instructions of Dekker's product): only where the driver's fma is fused, which
// GLSL leaves to the driver and DriverProbes.h finds out.
// RILL_GLSL_FMA = auto (default: nullopt, probe the driver) | fused | split. Throws on an
// unknown value.
std::optional<bool> fused_fma_mode();

// Which correction a fused fma gets: the lean one (true) or the fused residual in the split
// rule's steps (false, to compare the two on one binary).
// RILL_GLSL_FUSED = lean (default) | residual. Throws on an unknown value.
bool lean_fused_mode();

// The variants of the helper table's GLSL bodies that define rill_div_f(a, b) and
// rill_sqrt(x) for strict kernels in mode m: with a fused fma the lean correction (`lean`) or
// the residual fused, else the residual split.
std::vector<codegen::Variant> divsqrt_variants(DivSqrt m, bool fused_fma, bool lean);

// What rill-info says of the rule: "native", "corrected", "corrected, fused residual",
// "corrected, fused lean", ...
std::string divsqrt_description(DivSqrt m, bool fused_fma, bool lean);

}  // namespace rill::glsl
