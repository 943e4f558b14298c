// The optimizer passes and the pipeline that runs them.
//
// Each pass rewrites a Function in place, returns whether it changed anything, and leaves
// a valid Function behind (tests check this with the verifier). They are small on purpose:
//
//   constant_fold            ops on constants, with exact binary32 semantics (the host's
//                            float arithmetic, never wider), plus exact identities
//                            (i + 0, b && true, select on a constant) and constant branches
//   copy_propagate           reads of `t = copy(s)` read s instead, when both are written once
//   eliminate_common_subexpressions
//                            a pure op recomputed where an identical one dominates it
//   eliminate_dead_code      assignments nobody reads, empty ifs, code after a jump
//   lower_continue           `continue` in for / do-until loops becomes a guard flag, so that
//                            every emitter can print loops as `while (true)` (not optional)
//
//   lower_math               in strict mode, exp/log/sin/pow/... become Rill's own routines
//                            built from exact operations (StrictMath.h), so every backend
//                            computes the same bits (not optional in strict mode)
//
//   canonicalize             statements and variables in an order of their own, not the one the
//                            C++ compiler evaluated the DSL in: the same kernel source
//                            whichever compiler built Rill (not optional: capture runs it,
//                            and optimize() after lower_math, which records DSL code too)
//
// optimize() runs lower_math (strict), canonicalize, the enabled passes to a fixed point,
// then lower_continue.
//
// For the simd backend, after optimize():
//
//   lower_lockstep           control flow becomes lane masks, so that a group of elements
//                            runs the kernel together (LowerLockstep.cpp)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rill/Options.h"
#include "rill/ir/IR.h"

namespace rill::passes {

bool constant_fold(ir::Function& f, Accuracy accuracy = Accuracy::Strict);
bool copy_propagate(ir::Function& f);
bool eliminate_common_subexpressions(ir::Function& f);
bool eliminate_dead_code(ir::Function& f);
bool lower_continue(ir::Function& f);
// Strict mode only: transcendental ops become Rill's own routines (StrictMath.h).
bool lower_math(ir::Function& f);

// Where canonicalize moved the uniforms and arrays: new slot i holds what old slot
// uniforms[i] (arrays[i]) held. Whoever keeps lists parallel to them permutes those alike.
struct InterfaceOrder {
  std::vector<size_t> uniforms, arrays;
};
// Without `interface`, uniforms and arrays keep their slots (a compiled kernel's launch
// already binds them by slot); with it, they too are ordered by first use.
void canonicalize(ir::Function& f, InterfaceOrder* interface = nullptr);

ir::Function optimize(const ir::Function& f, const PassOptions& passes, Accuracy accuracy);

// The debug mode (CompileOptions::debug), run on the optimized function: each clamp-mode
// gather checks its indices and, with `nonfinite`, each float result is checked for NaN and
// infinity (InstrumentDebug.cpp). The checks write hidden outputs only; the table says
// where, for the report after a launch.
struct DebugSite {
  enum class Kind : uint8_t { Gather, NonFinite };
  Kind kind = Kind::Gather;
  std::string statement;  // the IR statement checked, as the IR printer writes it
  std::string array;      // Gather: the array's name
  int array_slot = -1;    // Gather: its index in Function::arrays
  int dims = 1;
  SourceLoc loc;  // the user's line where capture recorded one
};
struct DebugTable {
  int code_slot = -1;               // Function::outputs: 1 + the element's first failing gather
  std::vector<int> index_slots;     // outputs: that gather's indices
  int nonfinite_slot = -1;          // outputs: 1 + the first site that made a NaN or infinity
  int value_slot = -1;              // outputs: that value's bits
  std::vector<int> shape_uniforms;  // per array: the Function::uniforms slot of its Int3
                                    // shape (set by Kernel at each launch), or -1
  std::vector<DebugSite> sites;     // code k is sites[k - 1]
  bool active() const { return code_slot >= 0 || nonfinite_slot >= 0; }
};
DebugTable instrument_debug(ir::Function& f, bool nonfinite);

// How many times each variable is assigned; inputs and uniforms count one assignment on
// entry. Variables assigned exactly once hold one value wherever they are read.
std::vector<int> count_definitions(const ir::Function& f);

// A kernel lowered for lanes that run in lockstep: every `if` and loop condition means "some
// lane has it", and `alive` (a Bool variable, kNoVar when the kernel never discards) says at
// the end which lanes write their outputs.
struct LockstepFunction {
  ir::Function f;
  ir::VarId alive = ir::kNoVar;
};
LockstepFunction lower_lockstep(const ir::Function& optimized);

// Folds one operation on constants; nullopt when the op cannot be folded exactly.
std::optional<ir::Constant> fold(ir::Op op, ir::Type result, const std::vector<ir::Constant>& args);

}  // namespace rill::passes
