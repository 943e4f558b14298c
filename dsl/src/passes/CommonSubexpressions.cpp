// eliminate_common_subexpressions: `u = op(args)` where an identical `t = op(args)`
// dominates it becomes `u = copy(t)` (copy_propagate then removes it).
//
// Only operations on values that cannot change are considered: constants and variables
// assigned once, writing a variable assigned once. Dominance is positional: an assignment
// dominates the rest of its block and everything nested there, so the table of available
// expressions is scoped by block.
#include <map>

#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

using Key = std::vector<uint32_t>;

class Cse : public Mutator {
 public:
  explicit Cse(Function& f) : f_(f), defs_(count_definitions(f)) {}
  bool changed = false;

  // Every block is a scope: what it computes is available in it and in what it nests.
  void mutate(Block& b) override {
    scopes_.emplace_back();
    Mutator::mutate(b);
    scopes_.pop_back();
  }
  void mutate(Stmt&& s, Block& out) override {
    if (s.kind == StmtKind::Assign) assign(s);
    Mutator::mutate(std::move(s), out);
  }

 private:
  bool stable(const Operand& o) const { return o.is_const() || defs_[o.var] == 1; }

  void push_operand(Key& k, const Operand& o) const {
    k.push_back(static_cast<uint32_t>(o.kind));
    k.push_back((static_cast<uint32_t>(o.type.kind) << 8) | o.type.width);
    if (o.is_var()) {
      k.push_back(o.var);
      for (int i = 0; i < o.width(); ++i) k.push_back(o.swizzle[static_cast<size_t>(i)]);
    } else {
      for (int i = 0; i < o.width(); ++i) k.push_back(o.value.bits[static_cast<size_t>(i)]);
    }
  }

  void assign(Stmt& s) {
    // A lane-group op gives other results under other control flow (other active lanes).
    if (s.op == Op::Copy || !s.mask.full() || !is_pure(s.op) || reads_group(s.op)) return;
    if (defs_[s.dst] != 1 || f_.var(s.dst).role == VarRole::Output) return;
    for (const Operand& a : s.args)
      if (!stable(a)) return;
    Key k{static_cast<uint32_t>(s.op), static_cast<uint32_t>(s.array)};
    std::vector<const Operand*> args;
    for (const Operand& a : s.args) args.push_back(&a);
    if (is_commutative(s.op) && args.size() == 2) {
      Key a0, a1;
      push_operand(a0, *args[0]);
      push_operand(a1, *args[1]);
      if (a1 < a0) std::swap(args[0], args[1]);
    }
    for (const Operand* a : args) push_operand(k, *a);
    for (auto it = scopes_.rbegin(); it != scopes_.rend(); ++it) {
      auto found = it->find(k);
      if (found != it->end()) {
        s.op = Op::Copy;
        s.array = -1;
        s.args = {Operand::of_var(found->second, f_.var(found->second).type)};
        changed = true;
        return;
      }
    }
    scopes_.back().emplace(std::move(k), s.dst);
  }

  Function& f_;
  std::vector<int> defs_;
  std::vector<std::map<Key, VarId>> scopes_;
};

}  // namespace

bool eliminate_common_subexpressions(Function& f) {
  Cse cse(f);
  cse.mutate(f.body);
  return cse.changed;
}

}  // namespace rill::passes
