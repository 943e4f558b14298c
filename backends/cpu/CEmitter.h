// Emits a kernel as a C translation unit for the CPU backend (see CEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::cpu {

std::string emit_c(const ir::Function& optimized, Accuracy accuracy);

}  // namespace rill::cpu
