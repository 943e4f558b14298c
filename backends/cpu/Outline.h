// Which blocks of a kernel the C emitter prints as functions of their own ("outlining").
//
// GCC's dataflow passes and register allocator grow faster than linearly with the size of a
// function: the ray tracer's megakernel, one function of 12,000 lines, took 5.5 s of GCC at
// -O2 (docs/benchmarks/2026-12-07-first-image.md). Printed as many functions of bounded
// size, each is compiled, and its registers allocated, on its own, and the functions can be
// spread over translation units that compile in parallel.
//
// The plan picks blocks bottom-up: a then/else side or a loop body whose statements, counted
// after its own nested blocks were outlined, reach `min_cost` becomes a function. Its
// interface is per scalar component (the C code is scalarized): components the block only
// reads and that live outside it are passed by value, components it writes that live outside
// it (or keep a value across calls, in a loop) by pointer, copied in at entry and out at
// every exit; the rest are the function's locals. Jumps that leave the block (discard, a
// break or continue of a loop around it) become return codes its caller acts on. Printing a
// block as a function does not change a result: the same statements run on the same values
// in the same order, and strict kernels are compiled without FMA contraction or excess
// precision, so no value depends on where a function boundary falls.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include "rill/ir/IR.h"

namespace rill::cpu {

// One scalar C variable: component `comp` of IR variable `var`.
struct ScalarRef {
  ir::VarId var;
  int comp;
  bool operator<(const ScalarRef& o) const { return var != o.var ? var < o.var : comp < o.comp; }
};

// Return codes of an outlined function, for the jumps that leave its block.
enum OutlineExit : int { kFallThrough = 0, kDiscard = 1, kBreak = 2, kContinue = 3 };

struct OutlinedPart {
  const ir::Block* block = nullptr;
  int id = 0;       // rill_part<id>: its place in `parts`
  size_t cost = 0;  // its statements' cost, nested parts counted as calls
  std::vector<ScalarRef> by_value, by_pointer, locals;
  std::vector<int> arrays;                       // arrays its gathers read
  bool element_index = false;                    // reads rill_i
  bool element_coord = false;                    // reads rill_x, rill_y
  bool exits[4] = {false, false, false, false};  // which OutlineExit codes it may return
  // It is a loop's body or runs a loop of its own (nested parts' loops are theirs): where a
  // kernel's time goes. A part without is straight-line code run once per call, which the
  // C emitter may compile at a cheaper optimisation level (CEmitter.h's kColdUnitsMark).
  bool loops = false;
};

struct OutlinePlan {
  std::vector<OutlinedPart> parts;           // inner parts before the parts that call them
  std::map<const ir::Block*, size_t> index;  // block -> its part
  size_t root_cost = 0;                      // cost of what stays in the entry function
  // Which scalars (var * 4 + component) the entry function itself mentions, calls included
  // (empty when nothing is outlined).
  std::vector<char> root_scalars;
};

// Cost of a block: one per assigned component (a gather counts as four), one per branch or
// loop test. The default threshold makes functions of a few hundred lines of C.
constexpr size_t kOutlineMinCost = 600;

OutlinePlan plan_outlining(const ir::Function& f, size_t min_cost = kOutlineMinCost);

}  // namespace rill::cpu
