// The flush-to-zero model of the denormal rule (docs/conformance.md): a backend that flushes
// behaves as if every arithmetic operation read denormal float operands as zeros of their
// sign and flushed denormal results likewise (x86 DAZ + FTZ, and GPUs), while data movement
// (copies, swizzles, select, neg, abs, bit reinterpretation) leaves bits alone.
//
// flush_model() rewrites an optimized function that way, so that the reference interpreter
// computes what such a backend must compute, intermediate values included (the conformance
// suite), and so that a backend on a device that keeps some denormals and flushes others can
// flush them all itself (the vulkan backend's emulated flushing, VulkanBackend.cpp).
#include "rill/ir/FlushModel.h"

#include "rill/ir/Visitor.h"

namespace rill::ir {

namespace {

// The denormal rule on bits: a denormal becomes a zero of the same sign.
uint32_t flush_bits(uint32_t b) {
  return (b & 0x7f800000u) == 0 ? (b & 0x80000000u) : b;
}

Operand int_const(uint32_t bits) {
  Constant c = Constant::of_int(static_cast<int32_t>(bits));
  return Operand::of_const(c);
}

class Rewriter : public Mutator {
 public:
  explicit Rewriter(Function& f) : f_(f) {}
  using Mutator::mutate;

  void mutate(Stmt&& s, Block& out) override {
    if (s.kind != StmtKind::Assign || !flushes_denormals(s.op))
      return Mutator::mutate(std::move(s), out);
    for (Operand& a : s.args) a = flushed(out, a);
    // Operations made of several roundings flush after each of them.
    if (s.op == Op::Dot || s.op == Op::Cross ||
        (s.op == Op::Mod && f_.var(s.dst).type.is_float())) {
      Operand r = s.op == Op::Dot ? dot(out, s.args[0], s.args[1])
                  : s.op == Op::Cross
                      ? cross(out, s.args[0], s.args[1])
                      : mod(out, s.args[0], s.args[1],
                            s.mask.full() ? f_.var(s.dst).type.width : s.mask.count);
      Stmt back = Stmt::assign(s.dst, Op::Copy, {r});
      back.mask = s.mask;
      out.push_back(std::move(back));
      return;
    }
    const VarId dst = s.dst;
    const Mask mask = s.mask;
    out.push_back(std::move(s));
    const Type vt = f_.var(dst).type;
    if (!vt.is_float()) return;
    // dst[.mask] = flush(dst[.mask])
    Operand written = Operand::of_var(dst, vt);
    if (!mask.full()) {
      written.type = vt.with_width(mask.count);
      for (int k = 0; k < mask.count; ++k)
        written.swizzle[static_cast<size_t>(k)] = mask.comps[static_cast<size_t>(k)];
    }
    Operand r = flushed(out, written);
    Stmt back = Stmt::assign(dst, Op::Copy, {r});
    back.mask = mask;
    out.push_back(std::move(back));
  }

 private:
  // The operand with denormal float components replaced by zeros of their sign.
  Operand flushed(Block& out, const Operand& o) {
    if (!o.type.is_float()) return o;
    if (o.is_const()) {
      Constant c = o.value;
      for (int k = 0; k < c.type.width; ++k)
        c.bits[static_cast<size_t>(k)] = flush_bits(c.bits[static_cast<size_t>(k)]);
      return Operand::of_const(c);
    }
    const Type t = o.type;
    const Type it = int_type(t.width), bt = bool_type(t.width);
    auto temp = [&](Type ty, Op op, std::vector<Operand> args) {
      VarId v = f_.add_var(ty);
      out.push_back(Stmt::assign(v, op, std::move(args)));
      return Operand::of_var(v, ty);
    };
    Operand bits = temp(it, Op::FloatBitsToInt, {o});
    Operand exponent = temp(it, Op::BitAnd, {bits, int_const(0x7f800000u)});
    Operand tiny = temp(bt, Op::Eq, {exponent, int_const(0)});
    Operand sign = temp(it, Op::BitAnd, {bits, int_const(0x80000000u)});
    Operand zero = temp(t, Op::IntBitsToFloat, {sign});
    return temp(t, Op::Select, {tiny, zero, o});
  }

  // One arithmetic step with flushed result: t = flush(op(args)).
  Operand step(Block& out, Type t, Op op, std::vector<Operand> args) {
    VarId v = f_.add_var(t);
    out.push_back(Stmt::assign(v, op, std::move(args)));
    return flushed(out, Operand::of_var(v, t));
  }
  static Operand component(const Operand& o, int c) {
    if (o.is_const()) {
      Constant k;
      k.type = o.type.with_width(1);
      k.bits[0] = o.value.bits[static_cast<size_t>(o.width() == 1 ? 0 : c)];
      return Operand::of_const(k);
    }
    Operand r = o;
    r.type = o.type.with_width(1);
    r.swizzle[0] = static_cast<uint8_t>(o.component(c));
    return r;
  }
  // The helpers' formulas (backends/codegen): dot in component order, cross as
  // a_i b_j - a_j b_i, mod as x - y floor(x / y).
  Operand dot(Block& out, const Operand& a, const Operand& b) {
    const Type t = float_type(1);
    Operand sum;
    for (int c = 0; c < a.width(); ++c) {
      Operand p = step(out, t, Op::Mul, {component(a, c), component(b, c)});
      sum = c == 0 ? p : step(out, t, Op::Add, {sum, p});
    }
    return sum;
  }
  Operand cross(Block& out, const Operand& a, const Operand& b) {
    const Type t = float_type(1);
    std::vector<Operand> parts;
    for (int c = 0; c < 3; ++c) {
      int i = (c + 1) % 3, j = (c + 2) % 3;
      Operand p = step(out, t, Op::Mul, {component(a, i), component(b, j)});
      Operand q = step(out, t, Op::Mul, {component(a, j), component(b, i)});
      parts.push_back(step(out, t, Op::Sub, {p, q}));
    }
    VarId v = f_.add_var(float_type(3));
    out.push_back(Stmt::assign(v, Op::Construct, parts));
    return Operand::of_var(v, float_type(3));
  }
  Operand mod(Block& out, const Operand& a, const Operand& b, int width) {
    const Type t = float_type(width);
    Operand q = step(out, t, Op::Div, {a, b});
    Operand fl = step(out, t, Op::Floor, {q});
    Operand m = step(out, t, Op::Mul, {b, fl});
    return step(out, t, Op::Sub, {a, m});
  }

  Function& f_;
};

}  // namespace

Function flush_model(const Function& f) {
  Function out = f;
  Rewriter r(out);
  r.mutate(out.body);
  return out;
}

}  // namespace rill::ir
