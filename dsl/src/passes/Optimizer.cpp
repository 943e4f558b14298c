// The pass pipeline, and the definition counts several passes share.
#include "rill/ir/Verifier.h"
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

std::vector<int> count_definitions(const Function& f) {
  std::vector<int> defs(f.vars.size(), 0);
  // Inputs, uniforms and outputs hold a value on entry (an output starts as its stream's
  // current element, which is what a discarded or unwritten element keeps).
  for (VarId v : f.inputs) ++defs[v];
  for (VarId v : f.uniforms) ++defs[v];
  for (VarId v : f.outputs) ++defs[v];
  for_each_stmt(f.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::Assign) ++defs[s.dst];
  });
  return defs;
}

Function optimize(const Function& input, const PassOptions& p, Accuracy accuracy) {
  Function f = input;
  // lower_math records Rill's math routines with the DSL, in the order the C++ compiler
  // evaluates them: canonicalize puts them, like the capture, in an order of its own.
  if (accuracy == Accuracy::Strict && lower_math(f)) canonicalize(f);
  // A program is small and each pass is linear, so running to a fixed point is cheap; the
  // bound only guards against a pass that keeps reporting changes.
  for (int round = 0; round < 32; ++round) {
    bool changed = false;
    if (p.constant_folding) changed |= constant_fold(f, accuracy);
    if (p.copy_propagation) changed |= copy_propagate(f);
    if (p.common_subexpressions) changed |= eliminate_common_subexpressions(f);
    if (p.dead_code) changed |= eliminate_dead_code(f);
    if (!changed) break;
  }
  if (lower_continue(f) && p.dead_code) eliminate_dead_code(f);  // drop unread skip flags
  // Once more, now that dead code is gone: variables numbered densely, and the only part of
  // the capture left in C++'s order (unread temporaries) no longer shifts the numbers.
  canonicalize(f);
  verify_or_throw(f, "optimizer", /*outputs_written=*/false);
  return f;
}

}  // namespace rill::passes
