#include "CFamilyPrinter.h"

#include "rill/ir/Printer.h"
#include "rill/ir/Visitor.h"

namespace rill::codegen {

using namespace ir;

namespace {
const char* kComp[] = {"x", "y", "z", "w"};

std::string pad_of(int indent) {
  return std::string(static_cast<size_t>(indent) * 2, ' ');
}

// Suffix of the rill_* helper for a scalar kind: rill_min_f, rill_min_i.
const char* suffix(ScalarKind k) {
  return k == ScalarKind::Float ? "_f" : k == ScalarKind::Int ? "_i" : "_b";
}

std::string call(const std::string& fn, std::initializer_list<std::string> args) {
  std::string s = fn + "(";
  bool first = true;
  for (const auto& a : args) {
    if (!first) s += ", ";
    s += a;
    first = false;
  }
  return s + ")";
}
}  // namespace

std::string fixed_form_expr(const Stmt& s, int c,
                            const std::function<std::string(const Operand&, int)>& operand) {
  switch (s.op) {
    case Op::Dot: {
      // ((a.x*b.x + a.y*b.y) + a.z*b.z) + a.w*b.w: one fixed order everywhere.
      std::string sum;
      for (int i = 0; i < s.args[0].width(); ++i) {
        std::string p = "(" + operand(s.args[0], i) + " * " + operand(s.args[1], i) + ")";
        sum = i == 0 ? p : "(" + sum + " + " + p + ")";
      }
      return sum;
    }
    case Op::Cross: {
      int i = (c + 1) % 3, j = (c + 2) % 3;
      return "((" + operand(s.args[0], i) + " * " + operand(s.args[1], j) + ") - (" +
             operand(s.args[0], j) + " * " + operand(s.args[1], i) + "))";
    }
    case Op::Construct: {
      int k = c;
      for (const Operand& o : s.args) {
        if (k < o.width()) return operand(o, k);
        k -= o.width();
      }
      throw Error("internal: construct has too few components");
    }
    default:
      throw Error(std::string("internal: ") + op_name(s.op) + " has no fixed form");
  }
}

std::string helper_function(Op op, ScalarKind k) {
  switch (op) {
    case Op::Mod:
    case Op::Min:
    case Op::Max:
    case Op::Abs:
    case Op::Sign:
      return std::string(op_name(op)) + suffix(k);
    case Op::Floor:
    case Op::Ceil:
    case Op::Fract:
    case Op::Sqrt:
    case Op::Rsqrt:
    case Op::Exp:
    case Op::Log:
    case Op::Exp2:
    case Op::Log2:
    case Op::Sin:
    case Op::Cos:
    case Op::Tan:
    case Op::Atan:
    case Op::Pow:
    case Op::Atan2:
    case Op::Shl:
    case Op::Shr:
      return op_name(op);
    default:
      return "";
  }
}

std::string CFamilyPrinter::component(VarId v, int c) const {
  std::string n = f_.var_name(v);
  if (f_.var(v).type.width == 1) return n;
  if (d_.scalarize()) return n + "_" + std::to_string(c);
  return n + "." + kComp[c];
}

std::string CFamilyPrinter::operand(const Operand& o, int c) const {
  if (o.is_const()) {
    int k = o.width() == 1 ? 0 : c;
    return d_.literal(o.type.kind, o.value.bits[static_cast<size_t>(k)]);
  }
  return component(o.var, o.component(c));
}

std::string CFamilyPrinter::declarations(int indent) const {
  std::string out, pad = pad_of(indent);
  // Only variables the body mentions (passes leave the others behind), plus the interface.
  std::vector<bool> used(f_.vars.size(), false);
  for (VarId v : f_.inputs) used[v] = true;
  for (VarId v : f_.outputs) used[v] = true;
  for_each_operand(f_.body, [&](const Operand& o) {
    if (o.is_var()) used[o.var] = true;
  });
  for_each_stmt(f_.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::Assign) used[s.dst] = true;
  });
  for (VarId v = 0; v < f_.vars.size(); ++v) {
    if (!used[v]) continue;
    const Variable& var = f_.vars[v];
    std::string qual = var.type.is_float() ? d_.float_qualifier() : "";
    if (d_.scalarize() || var.type.width == 1) {
      for (int c = 0; c < var.type.width; ++c)
        out += pad + qual + d_.scalar_type(var.type.kind) + " " + component(v, c) + " = " +
               d_.initial_value(f_, v, c) + ";\n";
    } else {
      std::string init = d_.vector_type(var.type) + "(";
      for (int c = 0; c < var.type.width; ++c) init += (c ? ", " : "") + d_.initial_value(f_, v, c);
      out += pad + qual + d_.vector_type(var.type) + " " + f_.var_name(v) + " = " + init + ");\n";
    }
  }
  return out;
}

std::string CFamilyPrinter::body(int indent) const {
  std::string out;
  block(out, f_.body, indent);
  return out;
}

void CFamilyPrinter::block(std::string& out, const Block& b, int indent) const {
  for (const Stmt& s : b) stmt(out, s, indent);
}

void CFamilyPrinter::stmt(std::string& out, const Stmt& s, int indent) const {
  std::string pad = pad_of(indent);
  switch (s.kind) {
    case StmtKind::Assign:
      assign(out, s, pad);
      return;
    case StmtKind::If:
      out += pad + "if (" + operand(s.cond, 0) + ") {\n";
      block(out, s.then_body, indent + 1);
      if (!s.else_body.empty()) {
        out += pad + "} else {\n";
        block(out, s.else_body, indent + 1);
      }
      out += pad + "}\n";
      return;
    case StmtKind::Loop: {
      // Every loop is an endless loop with explicit exits (see passes/LowerContinue.cpp).
      out += pad + d_.loop_header() + " {\n";
      if (s.loop != LoopKind::DoUntil) {
        block(out, s.cond_body, indent + 1);
        out += pad + "  if (!" + operand(s.cond, 0) + ") break;\n";
      }
      block(out, s.body, indent + 1);
      block(out, s.step, indent + 1);
      if (s.loop == LoopKind::DoUntil) {
        block(out, s.cond_body, indent + 1);
        out += pad + "  if (" + operand(s.cond, 0) + ") break;\n";
      }
      out += pad + "}\n";
      return;
    }
    case StmtKind::Break:
      out += pad + "break;\n";
      return;
    case StmtKind::Continue:
      out += pad + "continue;\n";
      return;
    case StmtKind::Discard:
      out += pad + d_.discard() + "\n";
      return;
  }
}

void CFamilyPrinter::assign(std::string& out, const Stmt& s, const std::string& pad) const {
  const Type dst_type = f_.var(s.dst).type;
  const int width = s.mask.full() ? dst_type.width : s.mask.count;
  auto dst_comp = [&](int c) {
    return s.mask.full() ? c : static_cast<int>(s.mask.comps[static_cast<size_t>(c)]);
  };

  if (s.op == Op::Gather) {
    std::vector<std::string> index, dst;
    for (const Operand& a : s.args) index.push_back(operand(a, 0));
    for (int c = 0; c < width; ++c) dst.push_back(component(s.dst, dst_comp(c)));
    std::string g = d_.gather(f_, s, index, dst);
    // Indent every line the dialect produced.
    size_t start = 0;
    while (start < g.size()) {
      size_t nl = g.find('\n', start);
      out += pad + g.substr(start, nl - start + 1);
      start = nl + 1;
    }
    return;
  }

  std::vector<std::string> values;
  for (int c = 0; c < width; ++c) values.push_back(scalar_expr(s, c));

  // If the destination is also read, component-by-component writes could clobber a
  // component before it is read (v = v.yx): compute into temporaries first.
  bool aliased = false;
  if (width > 1)
    for (const Operand& a : s.args) aliased = aliased || (a.is_var() && a.var == s.dst);
  if (!aliased) {
    for (int c = 0; c < width; ++c)
      out += pad + component(s.dst, dst_comp(c)) + " = " + values[static_cast<size_t>(c)] + ";\n";
    return;
  }
  out += pad + "{\n";
  std::string qual = dst_type.is_float() ? d_.float_qualifier() : "";
  for (int c = 0; c < width; ++c)
    out += pad + "  " + qual + d_.scalar_type(dst_type.kind) + " r" + std::to_string(c) + " = " +
           values[static_cast<size_t>(c)] + ";\n";
  for (int c = 0; c < width; ++c)
    out += pad + "  " + component(s.dst, dst_comp(c)) + " = r" + std::to_string(c) + ";\n";
  out += pad + "}\n";
}

std::string CFamilyPrinter::scalar_expr(const Stmt& s, int c) const {
  auto a = [&](size_t i) { return operand(s.args[i], c); };
  ScalarKind k = s.args.empty() ? ScalarKind::Int : s.args[0].type.kind;
  if (std::string fn = helper_function(s.op, k); !fn.empty())
    return op_info(s.op).arity == 1 ? call("rill_" + fn, {a(0)}) : call("rill_" + fn, {a(0), a(1)});
  switch (s.op) {
    case Op::Copy:
      return a(0);
    case Op::Neg: {
      if (k == ScalarKind::Int) return call("rill_neg_i", {a(0)});
      std::string x = a(0);
      return x[0] == '-' ? "(-(" + x + "))" : "(-" + x + ")";  // never print "--"
    }
    case Op::Add:
      return k == ScalarKind::Int ? call("rill_add_i", {a(0), a(1)})
                                  : "(" + a(0) + " + " + a(1) + ")";
    case Op::Sub:
      return k == ScalarKind::Int ? call("rill_sub_i", {a(0), a(1)})
                                  : "(" + a(0) + " - " + a(1) + ")";
    case Op::Mul:
      return k == ScalarKind::Int ? call("rill_mul_i", {a(0), a(1)})
                                  : "(" + a(0) + " * " + a(1) + ")";
    case Op::Div:
      return k == ScalarKind::Int ? call("rill_div_i", {a(0), a(1)}) : d_.float_div(a(0), a(1));
    case Op::BitAnd:
      return "(" + a(0) + " & " + a(1) + ")";
    case Op::BitOr:
      return "(" + a(0) + " | " + a(1) + ")";
    case Op::BitXor:
      return "(" + a(0) + " ^ " + a(1) + ")";
    case Op::BitNot:
      return "(~" + a(0) + ")";
    case Op::And:
      return "(" + a(0) + " && " + a(1) + ")";
    case Op::Or:
      return "(" + a(0) + " || " + a(1) + ")";
    case Op::Not:
      return "(!" + a(0) + ")";
    case Op::Lt:
      return d_.compare(k, "<", a(0), a(1));
    case Op::Le:
      return d_.compare(k, "<=", a(0), a(1));
    case Op::Gt:
      return d_.compare(k, ">", a(0), a(1));
    case Op::Ge:
      return d_.compare(k, ">=", a(0), a(1));
    case Op::Eq:
      return d_.compare(k, "==", a(0), a(1));
    case Op::Ne:
      return d_.compare(k, "!=", a(0), a(1));
    case Op::Select:
      return d_.select(s.args[1].type.kind, a(0), a(1), a(2));
    case Op::IntToFloat:
      return call("rill_i2f", {a(0)});
    case Op::FloatToInt:
      return call("rill_f2i", {a(0)});
    case Op::FloatBitsToInt:
      return call("rill_fbits", {a(0)});
    case Op::IntBitsToFloat:
      return call("rill_ibits", {a(0)});
    case Op::Dot:
    case Op::Cross:
    case Op::Construct:
      return fixed_form_expr(s, c, [&](const Operand& o, int i) { return operand(o, i); });
    case Op::ElementIndex:
      return d_.element_index();
    case Op::ElementCoord:
      return d_.element_coord(c);
    case Op::Gather:  // a statement of its own, not an expression
    default:          // the helper calls, handled above (helper_function)
      break;
  }
  throw Error(std::string("internal: no C-family form for op ") + op_name(s.op));
}

}  // namespace rill::codegen
