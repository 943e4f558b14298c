#include "CFamilyPrinter.h"

#include "SourceMap.h"
#include "rill/ir/Printer.h"
#include "rill/ir/Visitor.h"

namespace rill::codegen {

using namespace ir;

namespace {
const char* kComp[] = {"x", "y", "z", "w"};

std::string pad_of(int indent) {
  return std::string(static_cast<size_t>(indent) * 2, ' ');
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
      const bool interface =
          var.role == VarRole::Input || var.role == VarRole::Output || var.role == VarRole::Uniform;
      for (int c = 0; c < var.type.width; ++c)
        if (!declare || interface || declare(v, c))
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
  if (outline && outline(out, b, indent)) return;
  out += statements(b, indent);
}

std::string CFamilyPrinter::statements(const Block& b, int indent) const {
  std::string out;
  if (!source_map_) {
    for (const Stmt& s : b) stmt(out, s, indent);
    return out;
  }
  // Every line a statement prints follows the line naming its source (one per line, so
  // that a compiler counting lines from a #line names this statement for each of them);
  // where the block ends, the generated numbering comes back for what follows.
  bool marked = false;
  for (const Stmt& s : b) {
    std::string text;
    stmt(text, s, indent);
    if (!s.loc.known()) {
      out += text;
      continue;
    }
    const std::string mark = pad_of(indent) + d_.source_line(s.loc) + "\n";
    const bool nested = s.kind == StmtKind::If || s.kind == StmtKind::Loop;
    size_t start = 0;
    while (start < text.size()) {
      size_t nl = text.find('\n', start);
      if (nl == std::string::npos) nl = text.size() - 1;
      // A nested statement's own blocks mark their lines: only its first line is its own.
      if (!nested || start == 0) out += mark;
      out += text.substr(start, nl - start + 1);
      start = nl + 1;
    }
    marked = true;
  }
  if (marked && d_.source_line_renumbers())
    out += pad_of(indent) + std::string(kSourceLineRestore) + "\n";
  return out;
}

std::string CFamilyPrinter::jump(StmtKind kind) const {
  switch (kind) {
    case StmtKind::Break:
      return loop_depth_ == 0 && !escape_break_text.empty() ? escape_break_text : "break;";
    case StmtKind::Continue:
      return loop_depth_ == 0 && !escape_continue_text.empty() ? escape_continue_text : "continue;";
    case StmtKind::Discard:
      return discard_text.empty() ? d_.discard() : discard_text;
    default:
      break;
  }
  throw Error("internal: jump() of a statement that is no jump");
}

void CFamilyPrinter::stmt(std::string& out, const Stmt& s, int indent) const {
  std::string pad = pad_of(indent);
  switch (s.kind) {
    case StmtKind::Assign:
      assign(out, s, pad);
      return;
    case StmtKind::If:
      if (s.then_body.empty()) {  // if (!c) { else }
        out += pad + "if (!" + d_.branch_condition(operand(s.cond, 0)) + ") {\n";
        block(out, s.else_body, indent + 1);
        out += pad + "}\n";
        return;
      }
      out += pad + "if (" + d_.branch_condition(operand(s.cond, 0)) + ") {\n";
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
      ++loop_depth_;
      if (s.loop != LoopKind::DoUntil) {
        block(out, s.cond_body, indent + 1);
        out += pad + "  if (!" + d_.branch_condition(operand(s.cond, 0)) + ") break;\n";
      }
      block(out, s.body, indent + 1);
      block(out, s.step, indent + 1);
      if (s.loop == LoopKind::DoUntil) {
        block(out, s.cond_body, indent + 1);
        out += pad + "  if (" + d_.branch_condition(operand(s.cond, 0)) + ") break;\n";
      }
      --loop_depth_;
      out += pad + "}\n";
      return;
    }
    case StmtKind::Break:
    case StmtKind::Continue:
    case StmtKind::Discard:
      out += pad + jump(s.kind) + "\n";
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

std::string Dialect::source_line(const SourceLoc& loc) const {
  return "#line " + std::to_string(loc.line) + " \"" + quoted_file(loc) + "\"";
}

std::string Dialect::group(Op op, ScalarKind, int c, const std::vector<std::string>& args) const {
  const std::string zero = literal(ScalarKind::Int, 0), one = literal(ScalarKind::Int, 1);
  switch (op) {
    case Op::GroupSize:
      return one;
    case Op::LaneIndex:
      return zero;
    case Op::GroupBallot:  // bit 0 of component 0
      return c == 0 ? select(ScalarKind::Int, args[0], one, zero) : zero;
    case Op::GroupCount:
      return select(ScalarKind::Int, args[0], one, zero);
    default:  // any, all, min, max, sum, broadcast: the element's own value
      return args[0];
  }
}

// Component c of an assignment's value, spelled as Ops.def's form column says.
std::string CFamilyPrinter::scalar_expr(const Stmt& s, int c) const {
  auto a = [&](size_t i) { return operand(s.args[i], c); };
  // The kind the op computes on: its operands' (select: its branches').
  const ScalarKind k =
      s.args.empty() ? ScalarKind::Int : s.args[s.op == Op::Select ? 1 : 0].type.kind;
  const OpForm& form = op_info(s.op).form(k);
  switch (form.kind) {
    case FormKind::Copy:
      return a(0);
    case FormKind::Negate: {
      std::string x = a(0);
      return x[0] == '-' ? "(-(" + x + "))" : "(-" + x + ")";  // never print "--"
    }
    case FormKind::Infix:
      return "(" + a(0) + " " + form.text + " " + a(1) + ")";
    case FormKind::Prefix:
      return "(" + std::string(form.text) + a(0) + ")";
    case FormKind::Logic: {
      const std::string op = d_.lane_masks() ? form.lanes : form.text;
      return s.args.size() == 1 ? "(" + op + a(0) + ")" : "(" + a(0) + " " + op + " " + a(1) + ")";
    }
    case FormKind::Helper: {
      std::string call = d_.helper(form.text) + "(";
      for (size_t i = 0; i < s.args.size(); ++i) call += (i ? ", " : "") + a(i);
      return call + ")";
    }
    case FormKind::Compare:
      return d_.compare(k, form.text, a(0), a(1));
    case FormKind::FloatDiv:
      return d_.float_div(a(0), a(1));
    case FormKind::Select:
      return d_.select(k, a(0), a(1), a(2));
    case FormKind::Fixed:
      return fixed_form_expr(s, c, [&](const Operand& o, int i) { return operand(o, i); });
    case FormKind::Element:
      return s.op == Op::ElementIndex ? d_.element_index() : d_.element_coord(c);
    case FormKind::Group: {
      std::vector<std::string> args;
      for (size_t i = 0; i < s.args.size(); ++i) args.push_back(a(i));
      return d_.group(s.op, k, c, args);
    }
    case FormKind::Gather:  // a statement of its own (assign() prints it), not an expression
    case FormKind::None:
      break;
  }
  throw Error(std::string("internal: no C-family form for op ") + op_name(s.op) + " on " +
              kind_name(k));
}

}  // namespace rill::codegen
