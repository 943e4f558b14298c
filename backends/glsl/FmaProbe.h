// Whether the driver's GLSL fma() rounds once (a fused multiply-add), found by running it.
//
// The strict division and square-root corrections (DivSqrt.h) need an exact residual
// a - q*b. One fma gives it where fma is fused; GLSL leaves that to the driver (GLSL 4.60,
// section 8.3), and drivers differ: NVIDIA's fma is its hardware's fused multiply-add, while
// Mesa's llvmpipe computes it as a product and a sum, each rounded. So the rule is probed, not
// assumed from the driver's name: a one-invocation compute shader evaluates fma(-x, y, z), the
// corrections' form, on operands whose product needs more than 24 bits, and the results are
// compared with the host's std::fma.
#pragma once

#include "GLSession.h"

namespace rill::glsl {

// True when every probe case matches the host's fused result. Needs a GL 4.3 context, current.
bool probe_fused_fma(const GL& gl, const Driver& d, const char* backend);

}  // namespace rill::glsl
