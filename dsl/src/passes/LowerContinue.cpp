// lower_continue: removes `continue` from for and do-until loops.
//
// Emitters print every loop as `while (true) { ... }` with explicit exits, which keeps one
// printing scheme for C, OpenCL C and GLSL. A `continue` there would jump straight back to
// the top, skipping a for loop's step or a do-until loop's condition. So inside such loops
// `continue` becomes `skip = true`, and what follows it, up to the end of the body, runs
// under `if (!skip)`. While loops keep their `continue`: jumping to the top is right there.
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

class ContinueLowering : public Mutator {
 public:
  explicit ContinueLowering(Function& f) : f_(f) {}
  using Mutator::mutate;
  bool changed = false;

  // Inner loops first, then this one.
  void mutate(Stmt&& s, Block& out) override {
    Mutator::mutate(std::move(s), out);
    Stmt& done = out.back();
    if (done.kind == StmtKind::Loop && done.loop != LoopKind::While && has_continue(done.body))
      lower_loop(done);
  }

 private:
  // Does b contain a continue of the loop whose body it is (not of a nested loop)?
  static bool has_continue(const Block& b) { return jumps_out_of_loop(b, StmtKind::Continue); }

  void lower_loop(Stmt& loop) {
    changed = true;
    VarId skip = f_.add_var(bool_type(1), VarRole::Local, "skip");
    Block body;
    body.push_back(Stmt::assign(skip, Op::Copy, {Operand::of_const(Constant::of_bool(false))}, loop.loc));
    Block rest = std::move(loop.body);
    guard(rest, skip);
    for (Stmt& s : rest) body.push_back(std::move(s));
    loop.body = std::move(body);
  }

  // Rewrites the continues in b, guarding what follows each statement that may continue.
  void guard(Block& b, VarId skip) {
    for (size_t i = 0; i < b.size(); ++i) {
      Stmt& s = b[i];
      if (s.kind == StmtKind::Continue) {
        SourceLoc loc = s.loc;
        b.resize(i);  // the rest of the block is unreachable
        b.push_back(Stmt::assign(skip, Op::Copy, {Operand::of_const(Constant::of_bool(true))}, loc));
        return;
      }
      if (s.kind != StmtKind::If || !(has_continue(s.then_body) || has_continue(s.else_body))) continue;
      guard(s.then_body, skip);
      guard(s.else_body, skip);
      if (i + 1 == b.size()) return;
      // Move the rest of the block under `if (!skip)`.
      Block tail(std::make_move_iterator(b.begin() + static_cast<long>(i) + 1),
                 std::make_move_iterator(b.end()));
      b.resize(i + 1);
      VarId go = f_.add_var(bool_type(1));
      b.push_back(Stmt::assign(go, Op::Not, {Operand::of_var(skip, bool_type(1))}, s.loc));
      Stmt cont = Stmt::make_if(Operand::of_var(go, bool_type(1)), b[i].loc);
      guard(tail, skip);
      cont.then_body = std::move(tail);
      b.push_back(std::move(cont));
      return;
    }
  }

  Function& f_;
};

}  // namespace

bool lower_continue(Function& f) {
  ContinueLowering l(f);
  l.mutate(f.body);
  return l.changed;
}

}  // namespace rill::passes
