// Emits a kernel as a GLSL fragment shader (see GLSLEmitter.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rill/Backend.h"
#include "rill/ir/IR.h"
#include "DivSqrt.h"

namespace rill::glsl {

struct GLSLShader {
  std::string source;
  std::vector<uint32_t> constants;  // bits of uniform uint rill_k[] (strict mode)
};

// The fragment shader computing `optimized` and writing the outputs listed (indices into
// Function::outputs), at draw-buffer locations 0, 1, ... in that order.
// Strict kernels divide and take square roots as `divsqrt` says (DivSqrt.h).
GLSLShader emit_glsl(const ir::Function& optimized, Accuracy accuracy, const std::vector<int>& outputs,
                     DivSqrt divsqrt = DivSqrt::Native);
// The vertex shader every kernel is drawn with.
std::string vertex_shader();

}  // namespace rill::glsl
