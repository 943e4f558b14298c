// Emits a kernel as a C translation unit for the CPU backend (see CEmitter.cpp).
#pragma once

#include <string>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::codegen {
class Dialect;
}

namespace rill::cpu {

// `source_map`: with #line directives naming the user's lines (codegen/SourceMap.h).
std::string emit_c(const ir::Function& optimized, Accuracy accuracy, bool source_map = false);

// Pieces every C translation unit of the CPU backends shares (the scalar one above and the
// lockstep one in simd/LockstepEmitter.h):
// the header comment, rill_real, the launch struct and the rill_* helpers;
std::string c_head(const ir::Function& f, Accuracy accuracy);
// the entry point's locals: in<k>/out<k> pointers, u<k>_<c> uniforms, arr<k> and shapes.
std::string c_entry_locals(const ir::Function& f, const codegen::Dialect& d);

}  // namespace rill::cpu
