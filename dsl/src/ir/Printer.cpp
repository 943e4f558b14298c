#include "rill/ir/Printer.h"

#include <bit>
#include <charconv>
#include <cstdio>
#include <sstream>

namespace rill::ir {

namespace {
const char kComp[] = "xyzw";

std::string float_text(float v) {
  if (v != v) {  // NaN: keep the payload, so the text stays complete
    char nb[32];
    std::snprintf(nb, sizeof nb, "nan(0x%08x)", std::bit_cast<uint32_t>(v));
    return nb;
  }
  // Shortest text that reads back to the same float: exact and readable.
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, r.ptr);
  if (s.find_first_of(".eni") == std::string::npos) s += ".0";
  return s;
}

std::string scalar_text(const Constant& c, int i) {
  switch (c.type.kind) {
    case ScalarKind::Float: return float_text(c.f(i));
    case ScalarKind::Int: return std::to_string(c.i(i));
    case ScalarKind::Bool: return c.b(i) ? "true" : "false";
  }
  return "?";
}

std::string indent_str(int n) { return std::string(static_cast<size_t>(n) * 2, ' '); }

void print_block(std::ostringstream& os, const Function& f, const Block& b, int indent,
                 bool locations);

// With locations: the statement's source location after its line, "  @ file.cpp:12".
std::string at(const Stmt& s, bool locations) {
  return locations && s.loc.known() ? "  @ " + s.loc.describe() : "";
}

void print_stmt(std::ostringstream& os, const Function& f, const Stmt& s, int indent,
                bool locations) {
  std::string pad = indent_str(indent);
  switch (s.kind) {
    case StmtKind::Assign: {
      os << pad << f.var_name(s.dst);
      if (!s.mask.full()) {
        os << '.';
        for (int i = 0; i < s.mask.count; ++i) os << kComp[s.mask.comps[static_cast<size_t>(i)]];
      }
      os << " = " << op_name(s.op);
      if (s.op == Op::Gather) os << " a" << s.array << ':' << f.arrays.at(static_cast<size_t>(s.array)).name;
      os << '(';
      for (size_t i = 0; i < s.args.size(); ++i) {
        if (i) os << ", ";
        os << print_operand(f, s.args[i]);
      }
      os << ')' << at(s, locations) << "\n";
      break;
    }
    case StmtKind::If:
      os << pad << "if " << print_operand(f, s.cond) << " {" << at(s, locations) << "\n";
      print_block(os, f, s.then_body, indent + 1, locations);
      if (!s.else_body.empty()) {
        os << pad << "} else {\n";
        print_block(os, f, s.else_body, indent + 1, locations);
      }
      os << pad << "}\n";
      break;
    case StmtKind::Loop: {
      const char* kind = s.loop == LoopKind::While ? "while" : s.loop == LoopKind::For ? "for" : "do";
      os << pad << kind << " {" << at(s, locations) << "\n";
      if (s.loop != LoopKind::DoUntil) {
        print_block(os, f, s.cond_body, indent + 1, locations);
        os << pad << "  exit unless " << print_operand(f, s.cond) << "\n";
      }
      print_block(os, f, s.body, indent + 1, locations);
      if (s.loop == LoopKind::For) {
        os << pad << "  step:\n";
        print_block(os, f, s.step, indent + 1, locations);
      }
      if (s.loop == LoopKind::DoUntil) {
        os << pad << "  until:\n";
        print_block(os, f, s.cond_body, indent + 1, locations);
        os << pad << "  exit if " << print_operand(f, s.cond) << "\n";
      }
      os << pad << "}\n";
      break;
    }
    case StmtKind::Break:
      os << pad << "break" << at(s, locations) << "\n";
      break;
    case StmtKind::Continue:
      os << pad << "continue" << at(s, locations) << "\n";
      break;
    case StmtKind::Discard:
      os << pad << "discard" << at(s, locations) << "\n";
      break;
  }
}

void print_block(std::ostringstream& os, const Function& f, const Block& b, int indent,
                 bool locations) {
  for (const Stmt& s : b) print_stmt(os, f, s, indent, locations);
}

void print_params(std::ostringstream& os, const Function& f, const std::vector<VarId>& ids,
                  const char* dir) {
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i) os << ", ";
    os << dir << ' ' << f.var(ids[i]).type.str() << ' ' << f.var_name(ids[i]);
  }
}
}  // namespace

std::string print_constant(const Constant& c) {
  if (c.type.width == 1) return scalar_text(c, 0);
  std::string s = c.type.str() + "(";
  for (int i = 0; i < c.type.width; ++i) s += (i ? ", " : "") + scalar_text(c, i);
  return s + ")";
}

std::string print_operand(const Function& f, const Operand& o) {
  if (o.is_const()) return print_constant(o.value);
  std::string s = f.var_name(o.var);
  if (!o.identity_swizzle(f.var(o.var).type.width)) {
    s += '.';
    for (int i = 0; i < o.type.width; ++i) s += kComp[o.swizzle[static_cast<size_t>(i)]];
  }
  return s;
}

std::string print(const Function& f, const Block& b, int indent) {
  std::ostringstream os;
  print_block(os, f, b, indent, false);
  return os.str();
}

std::string print(const Function& f) {
  return print(f, PrintOptions{});
}

std::string print(const Function& f, const PrintOptions& options) {
  std::ostringstream os;
  os << "kernel " << f.name << '(';
  print_params(os, f, f.inputs, "in");
  os << ") -> (";
  print_params(os, f, f.outputs, "out");
  os << ")\n";
  for (VarId u : f.uniforms)
    os << "  uniform " << f.var(u).type.str() << ' ' << f.var_name(u) << "\n";
  for (const ArrayDecl& a : f.arrays) {
    os << "  array" << a.dims << "d " << a.elem.str() << " a" << (&a - f.arrays.data()) << ':'
       << a.name;
    // Clamp, the default, prints nothing (the text of programs without modes is unchanged).
    if (a.boundary != Boundary::Clamp) os << ' ' << boundary_name(a.boundary);
    if (a.boundary == Boundary::Constant) os << '(' << print_constant(a.border) << ')';
    os << "\n";
  }
  // Locals and temporaries with their types, so the text alone determines the program.
  for (VarId v = 0; v < f.vars.size(); ++v) {
    VarRole r = f.vars[v].role;
    if (r == VarRole::Temp || r == VarRole::Local)
      os << "  var " << f.vars[v].type.str() << ' ' << f.var_name(v) << "\n";
  }
  print_block(os, f, f.body, 1, options.locations);
  return os.str();
}

}  // namespace rill::ir
