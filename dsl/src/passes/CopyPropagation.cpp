// copy_propagate: where `t = copy(s)` is t's only assignment and s is a constant or is itself
// assigned only once, every read of t reads s instead (swizzles composed). The copy is then
// dead and eliminate_dead_code removes it. A name t had passes to an unnamed s it copies
// whole.
//
// Why this is safe: a variable assigned once holds one value wherever it is read (reads are
// dominated by the assignment in the structured IR), so s read anywhere t is read gives the
// value t was given.
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

bool copy_propagate(Function& f) {
  std::vector<int> defs = count_definitions(f);
  std::vector<const Operand*> source(f.vars.size(), nullptr);
  std::vector<Operand> sources;
  sources.reserve(f.vars.size());
  for_each_stmt(f.body, [&](const Stmt& s) {
    if (s.kind != StmtKind::Assign || s.op != Op::Copy || !s.mask.full()) return;
    if (defs[s.dst] != 1 || f.var(s.dst).role == VarRole::Output) return;
    const Operand& src = s.args[0];
    if (src.is_var() && (defs[src.var] != 1 || src.var == s.dst)) return;
    // A named copy of an unnamed temporary (Float t = v.x(); rill::label(t, "t")) disappears
    // here: the temporary, which holds the same value, takes the name, so it stays readable.
    if (src.is_var() && src.identity_swizzle(f.var(src.var).type.width) &&
        f.var(src.var).role == VarRole::Temp && f.var(src.var).name.empty())
      f.vars[src.var].name = f.var(s.dst).name;
    sources.push_back(src);
    source[s.dst] = &sources.back();
  });

  // Resolves chains (t = copy(u), u = copy(s)) by composing as we go.
  bool changed = false;
  auto rewrite = [&](Operand& o) {
    for (int guard = 0; guard < 64 && o.is_var() && source[o.var]; ++guard) {
      const Operand& src = *source[o.var];
      Operand n;
      if (src.is_const()) {
        Constant c;
        c.type = o.type;
        for (int i = 0; i < o.width(); ++i)
          c.bits[static_cast<size_t>(i)] = src.value.bits[o.swizzle[static_cast<size_t>(i)]];
        n = Operand::of_const(c);
      } else {
        n = src;
        n.type = o.type;
        for (int i = 0; i < o.width(); ++i)
          n.swizzle[static_cast<size_t>(i)] = src.swizzle[o.swizzle[static_cast<size_t>(i)]];
      }
      o = n;
      changed = true;
    }
  };
  for_each_operand(f.body, rewrite);
  return changed;
}

}  // namespace rill::passes
