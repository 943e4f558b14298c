// The debug mode's instrumentation (CompileOptions::debug): after the optimizer, every
// clamp-mode gather checks its indices against the array's shape and, with
// CompileOptions::debug_nonfinite, every float result is checked for NaN and infinity.
//
// A check only writes hidden outputs (named "rill$debug..."), one report per element: the
// first failing gather in the order the element ran them (its site number and indices), and
// the first statement that produced a non-finite value (its site and the value's bits). The
// kernel's own statements are left exactly as they were, so an in-range kernel computes the
// same bits with debug on. Kernel reads the reports back after each launch (DebugReport.cpp).
#include <algorithm>
#include <functional>

#include "rill/ir/Printer.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

class Instrumenter {
 public:
  Instrumenter(Function& f, bool nonfinite, DebugTable& t) : f_(f), nonfinite_(nonfinite), t_(t) {}

  void run() {
    int dims = 0;
    for (const ArrayDecl& a : f_.arrays) dims = std::max(dims, a.dims);
    t_.shape_uniforms.assign(f_.arrays.size(), -1);
    bool any_gather = false;
    for_each(f_.body, [&](const Stmt& s) {
      if (checked_gather(s)) any_gather = true;
    });
    if (any_gather) {
      code_ = output(int_type(1), "rill$debug.gather", &t_.code_slot);
      for (int d = 0; d < dims; ++d) {
        t_.index_slots.push_back(-1);
        index_.push_back(
            output(int_type(1), "rill$debug.index" + std::to_string(d), &t_.index_slots.back()));
      }
    }
    if (nonfinite_) {
      bad_ = output(int_type(1), "rill$debug.nonfinite", &t_.nonfinite_slot);
      bad_bits_ = output(int_type(1), "rill$debug.value", &t_.value_slot);
    }
    block(f_.body);
  }

 private:
  static void for_each(const Block& b, const std::function<void(const Stmt&)>& fn) {
    for (const Stmt& s : b) {
      fn(s);
      for (const Block* inner : {&s.then_body, &s.else_body, &s.cond_body, &s.body, &s.step})
        for_each(*inner, fn);
    }
  }

  bool checked_gather(const Stmt& s) const {
    return s.kind == StmtKind::Assign && s.op == Op::Gather &&
           f_.arrays.at(static_cast<size_t>(s.array)).boundary == Boundary::Clamp;
  }

  VarId output(Type t, const std::string& name, int* slot) {
    VarId v = f_.add_var(t, VarRole::Output, name);
    f_.vars[v].slot = static_cast<int>(f_.outputs.size());
    f_.outputs.push_back(v);
    *slot = f_.vars[v].slot;
    return v;
  }

  VarId shape_of(int array) {
    int& u = t_.shape_uniforms[static_cast<size_t>(array)];
    if (u < 0) {
      VarId v = f_.add_var(int_type(3), VarRole::Uniform, "rill$shape" + std::to_string(array));
      u = static_cast<int>(f_.uniforms.size());
      f_.vars[v].slot = u;
      f_.uniforms.push_back(v);
      shape_vars_.resize(f_.arrays.size(), kNoVar);
      shape_vars_[static_cast<size_t>(array)] = v;
    }
    return shape_vars_[static_cast<size_t>(array)];
  }

  // dst = op(args), a new temporary of type t.
  Operand emit(Block& out, Op op, Type t, std::vector<Operand> args, SourceLoc loc) {
    VarId v = f_.add_var(t);
    out.push_back(Stmt::assign(v, op, std::move(args), loc));
    return Operand::of_var(v, t);
  }
  static Operand int_const(int32_t v) { return Operand::of_const(Constant::of_int(v)); }

  // `report = (hit && report == 0) ? code : report` and the same choice for each extra
  // slot: the element's first failure is the one kept.
  void record(Block& out, const Operand& hit, VarId report, int code,
              const std::vector<std::pair<VarId, Operand>>& extra, SourceLoc loc) {
    const Operand r = Operand::of_var(report, int_type(1));
    Operand fresh = emit(out, Op::Eq, bool_type(1), {r, int_const(0)}, loc);
    Operand take = emit(out, Op::And, bool_type(1), {hit, fresh}, loc);
    for (const auto& [slot, value] : extra) {
      const Operand old = Operand::of_var(slot, int_type(1));
      out.push_back(Stmt::assign(slot, Op::Select, {take, value, old}, loc));
    }
    out.push_back(Stmt::assign(report, Op::Select, {take, int_const(code), r}, loc));
  }

  void gather_check(Block& out, const Stmt& s) {
    const ArrayDecl& a = f_.arrays.at(static_cast<size_t>(s.array));
    const VarId shape = shape_of(s.array);
    Operand outside;
    for (int d = 0; d < a.dims; ++d) {
      const Operand& i = s.args[static_cast<size_t>(d)];
      Operand n = Operand::of_var(shape, ScalarKind::Int, {d});
      Operand below = emit(out, Op::Lt, bool_type(1), {i, int_const(0)}, s.loc);
      Operand above = emit(out, Op::Ge, bool_type(1), {i, n}, s.loc);
      Operand here = emit(out, Op::Or, bool_type(1), {below, above}, s.loc);
      outside = d == 0 ? here : emit(out, Op::Or, bool_type(1), {outside, here}, s.loc);
    }
    DebugSite site;
    site.kind = DebugSite::Kind::Gather;
    site.statement = statement_text(s);
    site.array = a.name;
    site.array_slot = s.array;
    site.dims = a.dims;
    site.loc = s.loc;
    t_.sites.push_back(site);
    std::vector<std::pair<VarId, Operand>> extra;
    for (int d = 0; d < a.dims; ++d)
      extra.emplace_back(index_[static_cast<size_t>(d)], s.args[static_cast<size_t>(d)]);
    record(out, outside, code_, static_cast<int>(t_.sites.size()), extra, s.loc);
  }

  // After `s`: is any component it wrote NaN or infinite? (All exponent bits set, tested on
  // the bits, so that no backend's relaxed float comparisons can hide it.)
  void nonfinite_check(Block& out, const Stmt& s) {
    const Type t = f_.var(s.dst).type;
    const int n = s.mask.full() ? t.width : s.mask.count;
    Operand hit, value;
    for (int k = n - 1; k >= 0; --k) {
      const int c = s.mask.full() ? k : s.mask.comps[static_cast<size_t>(k)];
      Operand x = Operand::of_var(s.dst, ScalarKind::Float, {c});
      Operand bits = emit(out, Op::FloatBitsToInt, int_type(1), {x}, s.loc);
      Operand exp = emit(out, Op::BitAnd, int_type(1), {bits, int_const(0x7f800000)}, s.loc);
      Operand bad = emit(out, Op::Eq, bool_type(1), {exp, int_const(0x7f800000)}, s.loc);
      // The lowest bad component's bits: later (lower) components override.
      value = k == n - 1 ? bits : emit(out, Op::Select, int_type(1), {bad, bits, value}, s.loc);
      hit = k == n - 1 ? bad : emit(out, Op::Or, bool_type(1), {bad, hit}, s.loc);
    }
    DebugSite site;
    site.kind = DebugSite::Kind::NonFinite;
    site.statement = statement_text(s);
    site.loc = s.loc;
    t_.sites.push_back(site);
    record(out, hit, bad_, static_cast<int>(t_.sites.size()), {{bad_bits_, value}}, s.loc);
  }

  std::string statement_text(const Stmt& s) const {
    std::string text = print(f_, Block{s});
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    const size_t start = text.find_first_not_of(' ');
    return start == std::string::npos ? text : text.substr(start);
  }

  void block(Block& b) {
    Block out;
    out.reserve(b.size());
    for (Stmt& s : b) {
      for (Block* inner : {&s.then_body, &s.else_body, &s.cond_body, &s.body, &s.step})
        block(*inner);
      if (checked_gather(s)) gather_check(out, s);
      // Copies and selects pass a value on; the statement that made it is the one reported.
      const bool check = nonfinite_ && s.kind == StmtKind::Assign && s.op != Op::Copy &&
                         s.op != Op::Select && f_.var(s.dst).type.is_float();
      out.push_back(std::move(s));
      if (check) {
        const Stmt made = out.back();  // out grows below
        nonfinite_check(out, made);
      }
    }
    b = std::move(out);
  }

  Function& f_;
  bool nonfinite_;
  DebugTable& t_;
  VarId code_ = kNoVar, bad_ = kNoVar, bad_bits_ = kNoVar;
  std::vector<VarId> index_;
  std::vector<VarId> shape_vars_;
};

}  // namespace

DebugTable instrument_debug(Function& f, bool nonfinite) {
  DebugTable t;
  Instrumenter(f, nonfinite, t).run();
  return t;
}

}  // namespace rill::passes
