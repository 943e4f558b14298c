// Emits a kernel as OpenCL C 1.2 (see OpenCLEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::opencl {

std::string emit_opencl(const ir::Function& optimized, Accuracy accuracy);

}  // namespace rill::opencl
