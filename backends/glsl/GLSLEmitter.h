// Emits a kernel as a GLSL fragment shader (see GLSLEmitter.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::glsl {

struct GLSLShader {
  std::string source;
  std::vector<uint32_t> constants;  // bits of uniform uint rill_k[] (strict mode)
};

// The fragment shader computing `optimized` and writing the outputs listed (indices into
// Function::outputs), at draw-buffer locations 0, 1, ... in that order.
GLSLShader emit_glsl(const ir::Function& optimized, Accuracy accuracy, const std::vector<int>& outputs);
// The vertex shader every kernel is drawn with.
std::string vertex_shader();

}  // namespace rill::glsl
