// lower_math: in the strict accuracy mode, replaces every transcendental operation (exp,
// log, sin, pow, ...) by Rill's own routine for it (StrictMath.h), inlined component by
// component. Afterwards the kernel uses only operations every backend computes exactly
// (+, -, *, /, sqrt, floor, comparisons, selects, integer and bit operations), so all
// backends give the same bits. The routines are DSL code, recorded into the function with
// an ExtendScope.
#include "rill/StrictMath.h"
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

Float scalar_operand(const Operand& o, int c) {
  if (o.is_const()) return Float(o.value.f(o.width() == 1 ? 0 : c));
  Operand one = o;
  one.type = float_type(1);
  one.swizzle[0] = static_cast<uint8_t>(o.component(c));
  return Float(detail::emit(Op::Copy, float_type(1), {one}), detail::AdoptTag{});
}

// Rill's routine for each transcendental op (the ops Ops.def marks TRANSCENDENTAL).
Float routine(Op op, const Float& a, const Float& b) {
  switch (op) {
    case Op::Exp: return strict::exp(a);
    case Op::Exp2: return strict::exp2(a);
    case Op::Log: return strict::log(a);
    case Op::Log2: return strict::log2(a);
    case Op::Pow: return strict::pow(a, b);
    case Op::Sin: return strict::sin(a);
    case Op::Cos: return strict::cos(a);
    case Op::Tan: return strict::tan(a);
    case Op::Atan: return strict::atan(a);
    case Op::Atan2: return strict::atan2(a, b);
    default: throw Error("internal: lower_math on a non-transcendental op");
  }
}

class MathLowering : public Mutator {
 public:
  explicit MathLowering(Function& f) : f_(f) {}
  using Mutator::mutate;
  bool changed = false;

  void mutate(Stmt&& s, Block& out) override {
    if (s.kind != StmtKind::Assign || !is_transcendental(s.op)) return Mutator::mutate(std::move(s), out);
    for (Stmt& t : expand(s)) out.push_back(std::move(t));
    changed = true;
  }

 private:
  Block expand(const Stmt& s) {
    detail::ExtendScope scope(f_, s.loc);
    const int width = s.mask.full() ? f_.var(s.dst).type.width : s.mask.count;
    std::vector<Float> results;
    for (int c = 0; c < width; ++c) {
      Float a = scalar_operand(s.args[0], c);
      Float b = s.args.size() > 1 ? scalar_operand(s.args[1], c) : Float(0.0f);
      results.push_back(routine(s.op, a, b));
    }
    for (int c = 0; c < width; ++c) {
      Mask m;
      if (f_.var(s.dst).type.width > 1) {
        m.count = 1;
        m.comps[0] = static_cast<uint8_t>(s.mask.full() ? c : s.mask.comps[static_cast<size_t>(c)]);
      }
      detail::assign(scope.var(s.dst), m, results[static_cast<size_t>(c)].operand(), s.loc);
    }
    return scope.take();
  }

  Function& f_;
};

}  // namespace

bool lower_math(Function& f) {
  MathLowering l(f);
  l.mutate(f.body);
  return l.changed;
}

}  // namespace rill::passes
