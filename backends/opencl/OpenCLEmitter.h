// Emits a kernel as OpenCL C 1.2 (see OpenCLEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::opencl {

// `source_map`: with #line directives naming the user's lines (codegen/SourceMap.h).
std::string emit_opencl(const ir::Function& optimized, Accuracy accuracy, bool source_map = false);

}  // namespace rill::opencl
