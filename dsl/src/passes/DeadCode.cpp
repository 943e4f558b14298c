// eliminate_dead_code: removes assignments to variables nobody reads (outputs are read by
// the store at the end of the kernel), ifs with two empty branches, and statements that
// follow a break, continue or discard in the same block. Repeats until nothing changes,
// since removing one assignment can make its operands dead.
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {
class Sweeper : public Mutator {
 public:
  Sweeper(const Function& f, const std::vector<bool>& read) : f_(f), read_(read) {}
  bool changed = false;
  using Mutator::mutate;

  void mutate(Block& b) override {
    Mutator::mutate(b);
    for (size_t i = 0; i < b.size(); ++i) {
      StmtKind k = b[i].kind;
      if ((k == StmtKind::Break || k == StmtKind::Continue || k == StmtKind::Discard) &&
          i + 1 < b.size()) {
        b.resize(i + 1);
        changed = true;
        break;
      }
    }
  }

  void mutate(Stmt&& s, Block& out) override {
    if (s.kind == StmtKind::Assign && is_pure(s.op) && !read_[s.dst] &&
        f_.var(s.dst).role != VarRole::Output) {
      changed = true;
      return;
    }
    if (s.kind == StmtKind::If) {
      mutate(s.then_body);
      mutate(s.else_body);
      if (s.then_body.empty() && s.else_body.empty()) {
        changed = true;
        return;
      }
      out.push_back(std::move(s));
      return;
    }
    Mutator::mutate(std::move(s), out);
  }

 private:
  const Function& f_;
  const std::vector<bool>& read_;
};
}  // namespace

bool eliminate_dead_code(Function& f) {
  bool any = false;
  for (;;) {
    std::vector<bool> read(f.vars.size(), false);
    for_each_operand(f.body, [&](const Operand& o) {
      if (o.is_var()) read[o.var] = true;
    });
    Sweeper sweep(f, read);
    sweep.mutate(f.body);
    if (!sweep.changed) return any;
    any = true;
  }
}

}  // namespace rill::passes
