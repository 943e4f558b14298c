// What a GLSL driver does that its strings do not say, found by running it: small compute
// shaders of one invocation over one storage buffer, compared with the host's arithmetic.
//
// - Denormals: 2 * the smallest denormal comes back as zero where the driver's compute
//   arithmetic flushes them (llvmpipe flushes in fragment shaders but not in compute shaders;
//   NVIDIA flushes in both).
// - fma: the strict division and square-root corrections (DivSqrt.h) need an exact residual
//   a - q*b. One fma gives it where fma is fused; GLSL leaves that to the driver (GLSL 4.60,
//   section 8.3), and drivers differ: NVIDIA's fma is its hardware's fused multiply-add, while
//   Mesa's llvmpipe computes it as a product and a sum, each rounded. So fma(-x, y, z), the
//   corrections' form, runs on operands whose product needs more than 24 bits, and the results
//   are compared with the host's std::fma.
// Both need a GL 4.3 context, current. The vulkan backend runs the same probes through its
// own device (VulkanBackend.cpp) with the fma probe's data, body and verdict from here.
#pragma once

#include <string>
#include <vector>

#include "GLSession.h"

namespace rill::glsl {

// Runs `main_body` (GLSL statements over `buffer B { float v[]; } b`) once on `data` and
// returns the buffer afterwards. `kernel` and `backend` name the probe in errors.
std::vector<float> run_probe(const GL& gl, const Driver& d, const char* backend,
                             const std::string& kernel, const std::string& main_body,
                             std::vector<float> data);

bool probe_flushes_denormals(const GL& gl, const Driver& d, const char* backend);
bool probe_fused_fma(const GL& gl, const Driver& d, const char* backend);

// The fma probe's parts: its buffer before the run, its main() body (over
// `buffer B { float v[]; } b`), and whether the buffer after the run shows a fused fma.
std::vector<float> fma_probe_data();
extern const char* const kFmaProbeBody;
bool fma_probe_fused(const std::vector<float>& out);

}  // namespace rill::glsl
