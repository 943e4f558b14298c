// Emits a kernel as a GLSL fragment shader (see GLSLEmitter.cpp).
#pragma once

#include <string>
#include <vector>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::glsl {

// The fragment shader computing `optimized` and writing the outputs listed (indices into
// Function::outputs), at draw-buffer locations 0, 1, ... in that order.
std::string emit_glsl(const ir::Function& optimized, Accuracy accuracy, const std::vector<int>& outputs);
// The vertex shader every kernel is drawn with.
std::string vertex_shader();

}  // namespace rill::glsl
