// constant_fold: evaluates operations whose operands are all constants, applies identities
// that are exact for every input, and resolves branches on constant conditions.
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

namespace {
using namespace ir;

bool is_const(const Operand& o, uint32_t bits) {
  if (!o.is_const()) return false;
  for (int c = 0; c < o.width(); ++c)
    if (o.value.bits[static_cast<size_t>(c)] != bits) return false;
  return true;
}

Type result_of(const Function& f, const Stmt& s) {
  Type t = f.var(s.dst).type;
  return s.mask.full() ? t : t.with_width(s.mask.count);
}

// Widens a scalar operand to `width` components (constants splat, variables swizzle).
Operand widen(Operand o, int width) {
  if (o.width() == width) return o;
  if (o.is_const()) {
    for (int c = 1; c < width; ++c) o.value.bits[static_cast<size_t>(c)] = o.value.bits[0];
    o.value.type.width = static_cast<uint8_t>(width);
  } else {
    for (int c = 1; c < width; ++c) o.swizzle[static_cast<size_t>(c)] = o.swizzle[0];
  }
  o.type.width = static_cast<uint8_t>(width);
  return o;
}

class Folder : public Mutator {
 public:
  Folder(Function& f, Accuracy a) : f_(f), accuracy_(a) {}
  using Mutator::mutate;
  bool changed = false;

  void mutate(Stmt&& s, Block& out) override {
    if (s.kind == StmtKind::Assign) {
      fold_assign(s);
      out.push_back(std::move(s));
      return;
    }
    if (s.kind == StmtKind::If && s.cond.is_const()) {
      changed = true;
      Block& taken = s.cond.value.b(0) ? s.then_body : s.else_body;
      mutate(taken);
      for (Stmt& t : taken) out.push_back(std::move(t));
      return;
    }
    if (s.kind == StmtKind::Loop && s.loop != LoopKind::DoUntil && s.cond_body.empty() &&
        s.cond.is_const() && !s.cond.value.b(0)) {
      changed = true;  // a while / for whose condition is false never runs
      return;
    }
    Mutator::mutate(std::move(s), out);
  }

 private:
  void to_copy(Stmt& s, Operand src) {
    int width = result_of(f_, s).width;
    s.op = Op::Copy;
    s.args = {widen(std::move(src), width)};
    changed = true;
  }

  void fold_assign(Stmt& s) {
    if (s.op == Op::Copy) return;
    bool all_const = !s.args.empty();
    bool touches_float = f_.var(s.dst).type.is_float();
    for (const Operand& a : s.args) {
      all_const = all_const && a.is_const();
      touches_float = touches_float || a.type.is_float();
    }
    // In double mode float arithmetic happens in binary64, which binary32 folding would not
    // reproduce; only data movement is folded there.
    bool exact_here = accuracy_ != Accuracy::Double || !touches_float || s.op == Op::Construct ||
                      s.op == Op::Select;
    if (all_const && exact_here) {
      std::vector<Constant> args;
      for (const Operand& a : s.args) args.push_back(a.value);
      if (auto r = fold(s.op, result_of(f_, s), args)) {
        to_copy(s, Operand::of_const(*r));
        return;
      }
    }
    simplify(s);
  }

  // Identities exact for every input, NaN and signed zero included.
  void simplify(Stmt& s) {
    const Type t = result_of(f_, s);
    auto& a = s.args;
    if (s.op == Op::Select && a[0].is_const() && a[0].width() == 1) {
      to_copy(s, a[0].value.b(0) ? a[1] : a[2]);
      return;
    }
    if (t.is_int()) {
      if ((s.op == Op::Add || s.op == Op::Sub || s.op == Op::BitOr || s.op == Op::BitXor ||
           s.op == Op::Shl || s.op == Op::Shr) && is_const(a[1], 0) && a[0].width() == t.width)
        return to_copy(s, a[0]);
      if (s.op == Op::Add && is_const(a[0], 0) && a[1].width() == t.width) return to_copy(s, a[1]);
      if (s.op == Op::Mul && is_const(a[1], 1) && a[0].width() == t.width) return to_copy(s, a[0]);
      if (s.op == Op::Mul && is_const(a[0], 1) && a[1].width() == t.width) return to_copy(s, a[1]);
    }
    if (t.is_bool() && (s.op == Op::And || s.op == Op::Or)) {
      uint32_t neutral = s.op == Op::And ? 1u : 0u;
      for (int i = 0; i < 2; ++i) {
        const Operand& k = a[static_cast<size_t>(i)];
        const Operand& other = a[static_cast<size_t>(1 - i)];
        if (is_const(k, neutral) && other.width() == t.width) return to_copy(s, other);
        if (is_const(k, 1u - neutral)) return to_copy(s, Operand::of_const(Constant::of_bool(!neutral)));
      }
    }
  }

  Function& f_;
  Accuracy accuracy_;
};
}  // namespace

bool constant_fold(Function& f, Accuracy accuracy) {
  Folder folder(f, accuracy);
  folder.mutate(f.body);
  return folder.changed;
}

}  // namespace rill::passes
