#include "rill/ir/Verifier.h"

#include <sstream>

#include "rill/ir/Printer.h"

namespace rill::ir {

namespace {

class Checker {
 public:
  Checker(const Function& f, bool outputs_written) : f_(f), outputs_written_(outputs_written) {}

  std::vector<std::string> run() {
    written_.assign(f_.vars.size(), false);
    for (const ArrayDecl& a : f_.arrays) array(a);
    block(f_.body, 0);
    for (VarId v : f_.outputs)
      if (outputs_written_ && v < f_.vars.size() && !written_[v])
        problem({}, "output '" + f_.var(v).name + "' is never written");
    return problems_;
  }

 private:
  void problem(const Stmt* s, const std::string& what) {
    std::string where = s && s->loc.known() ? s->loc.describe() + ": " : "";
    problems_.push_back(where + what);
  }
  void problem(SourceLoc loc, const std::string& what) {
    problems_.push_back((loc.known() ? loc.describe() + ": " : "") + what);
  }

  void array(const ArrayDecl& a) {
    const std::string what = "array '" + a.name + "'";
    if (a.dims < 1 || a.dims > 3)
      problem({}, what + " has " + std::to_string(a.dims) + " dimensions (1 to 3)");
    if (a.boundary > Boundary::Constant)
      problem({}, what + " has an unknown boundary mode " +
                      std::to_string(static_cast<int>(a.boundary)));
    if (a.boundary == Boundary::Constant && a.border.type != a.elem)
      problem({}, what + " of " + a.elem.str() + " has a constant boundary of type " +
                      a.border.type.str());
  }

  bool operand(const Stmt& s, const Operand& o) {
    if (o.is_const()) {
      if (o.type != o.value.type) {
        problem(&s, "constant operand has inconsistent type");
        return false;
      }
      return true;
    }
    if (o.var >= f_.vars.size()) {
      problem(&s, "operand reads unknown variable t" + std::to_string(o.var));
      return false;
    }
    const Type vt = f_.var(o.var).type;
    if (o.type.kind != vt.kind || o.type.width < 1 || o.type.width > 4) {
      problem(&s, "operand " + print_operand(f_, o) + " has type " + o.type.str() +
                      " but its variable is " + vt.str());
      return false;
    }
    for (int i = 0; i < o.type.width; ++i)
      if (o.swizzle[static_cast<size_t>(i)] >= vt.width) {
        problem(&s, "swizzle of " + f_.var_name(o.var) + " reads component " +
                        std::to_string(o.swizzle[static_cast<size_t>(i)]) + " of a " + vt.str());
        return false;
      }
    return true;
  }

  void assign(const Stmt& s) {
    if (s.dst >= f_.vars.size()) return problem(&s, "assignment to unknown variable");
    const Variable& dv = f_.var(s.dst);
    if (dv.role == VarRole::Uniform)
      problem(&s, "assignment to uniform '" + dv.name + "' (uniforms are read-only in kernels)");
    written_[s.dst] = true;
    bool ok = true;
    std::vector<Type> types;
    for (const Operand& a : s.args) {
      ok = operand(s, a) && ok;
      types.push_back(a.type);
    }
    if (!ok) return;
    int dst_width = s.mask.full() ? dv.type.width : s.mask.count;
    if (!s.mask.full()) {
      unsigned seen = 0;
      for (int i = 0; i < s.mask.count; ++i) {
        int c = s.mask.comps[static_cast<size_t>(i)];
        if (c >= dv.type.width) return problem(&s, "write mask component out of range");
        if (seen & (1u << c)) return problem(&s, "write mask repeats a component");
        seen |= 1u << c;
      }
    }
    Type result;
    if (s.op == Op::Construct) {
      int w = 0;
      for (const Type& t : types) {
        w += t.width;
        if (t.kind != dv.type.kind) return problem(&s, "construct mixes kinds");
      }
      result = dv.type.with_width(w);
    } else if (s.op == Op::Gather) {
      if (s.array < 0 || s.array >= static_cast<int>(f_.arrays.size()))
        return problem(&s, "gather from unknown array");
      const ArrayDecl& a = f_.arrays[static_cast<size_t>(s.array)];
      if (static_cast<int>(types.size()) != a.dims) return problem(&s, "gather index count differs from array dimensions");
      for (const Type& t : types)
        if (t != int_type(1)) return problem(&s, "gather index must be a scalar int");
      result = a.elem;
    } else {
      std::string why;
      auto r = result_type(s.op, types, &why);
      if (!r) return problem(&s, why);
      result = *r;
    }
    if (result.kind != dv.type.kind || result.width != dst_width)
      problem(&s, std::string(op_name(s.op)) + " yields " + result.str() + " but writes " +
                      std::to_string(dst_width) + " component(s) of " + dv.type.str() + " " +
                      f_.var_name(s.dst));
  }

  void cond(const Stmt& s) {
    if (operand(s, s.cond) && s.cond.type != bool_type(1))
      problem(&s, "condition must be a scalar bool, got " + s.cond.type.str());
  }

  void block(const Block& b, int loop_depth) {
    for (const Stmt& s : b) {
      switch (s.kind) {
        case StmtKind::Assign: assign(s); break;
        case StmtKind::If:
          cond(s);
          block(s.then_body, loop_depth);
          block(s.else_body, loop_depth);
          break;
        case StmtKind::Loop:
          block(s.cond_body, loop_depth);
          cond(s);
          block(s.body, loop_depth + 1);
          block(s.step, loop_depth + 1);
          break;
        case StmtKind::Break:
        case StmtKind::Continue:
          if (loop_depth == 0) problem(&s, std::string(s.kind == StmtKind::Break ? "break" : "continue") + " outside a loop");
          break;
        case StmtKind::Discard: break;
      }
    }
  }

  const Function& f_;
  bool outputs_written_;
  std::vector<bool> written_;
  std::vector<std::string> problems_;
};

}  // namespace

std::vector<std::string> verify(const Function& f, bool outputs_written) {
  return Checker(f, outputs_written).run();
}

void verify_or_throw(const Function& f, const std::string& context, bool outputs_written) {
  auto problems = verify(f, outputs_written);
  if (problems.empty()) return;
  std::ostringstream os;
  os << context << ": kernel '" << f.name << "' is malformed:";
  for (const auto& p : problems) os << "\n  " << p;
  throw Error(os.str());
}

}  // namespace rill::ir
