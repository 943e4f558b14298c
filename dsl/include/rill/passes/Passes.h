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
