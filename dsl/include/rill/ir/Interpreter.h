// A reference interpreter for the IR: runs a kernel element by element on the host with
// exact binary32 semantics (the same evaluation constant folding uses).
//
// It defines what a `strict` kernel must compute, so the conformance suite and the random
// differential tests compare every backend against it. It is slow on purpose simple: no
// backend should use it in a hot path. Transcendental operations must have been lowered
// (passes::optimize in strict mode does that).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rill/ir/IR.h"

namespace rill::ir {

struct InterpreterArray {
  const uint32_t* data = nullptr;  // elements of the array's type, components interleaved
  int64_t shape[3] = {1, 1, 1};
};

struct InterpreterLaunch {
  std::vector<const uint32_t*> inputs;  // one per Function::inputs
  std::vector<uint32_t*> outputs;       // one per Function::outputs; read and written
  std::vector<std::array<uint32_t, 4>> uniforms;
  std::vector<InterpreterArray> arrays;
  int64_t count = 0, width = 0;
};

// Runs every element; returns how many were written (not discarded). Throws rill::Error on
// an operation it cannot evaluate exactly.
int64_t interpret(const Function& f, const InterpreterLaunch& launch);

}  // namespace rill::ir
