// The flush-to-zero model of the denormal rule (docs/conformance.md): flush_model() rewrites
// a function so that every arithmetic operation (Ops.def's FLUSHES) reads denormal float
// operands as zeros of their sign and flushes denormal results likewise, while data movement
// (copies, swizzles, select, neg, abs, bit reinterpretation) leaves bits alone.
#pragma once

#include "rill/ir/IR.h"

namespace rill::ir {

Function flush_model(const Function& f);

}  // namespace rill::ir
