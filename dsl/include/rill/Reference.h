// Running a captured program on the reference interpreter (ir/Interpreter.h), which defines
// what a strict kernel computes: the conformance suite and the differential tests compare
// every backend with it.
#pragma once

#include "rill/Program.h"
#include "rill/ir/Interpreter.h"

namespace rill {

// A launch of `p` on the interpreter with the program's uniforms (their current values) and
// arrays (their host copies, read back first where a device copy is newer). The caller adds
// the streams (inputs, outputs), the element count and the row width.
ir::InterpreterLaunch reference_launch(const Program& p);

}  // namespace rill
