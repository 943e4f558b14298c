#include "rill/ir/IR.h"

#include "rill/ir/Visitor.h"

#include <bit>

namespace rill::ir {

Constant Constant::of_float(float v) {
  Constant c;
  c.type = float_type(1);
  c.bits[0] = std::bit_cast<uint32_t>(v);
  return c;
}
Constant Constant::of_int(int32_t v) {
  Constant c;
  c.type = int_type(1);
  c.bits[0] = static_cast<uint32_t>(v);
  return c;
}
Constant Constant::of_bool(bool v) {
  Constant c;
  c.type = bool_type(1);
  c.bits[0] = v ? 1u : 0u;
  return c;
}
float Constant::f(int c) const { return std::bit_cast<float>(bits[static_cast<size_t>(c)]); }
int32_t Constant::i(int c) const { return static_cast<int32_t>(bits[static_cast<size_t>(c)]); }

Operand Operand::of_var(VarId v, Type var_type) {
  Operand o;
  o.kind = Kind::Var;
  o.var = v;
  o.type = var_type;
  return o;
}
Operand Operand::of_var(VarId v, ScalarKind kind, std::initializer_list<int> swz) {
  Operand o;
  o.kind = Kind::Var;
  o.var = v;
  o.type = Type{kind, static_cast<uint8_t>(swz.size())};
  size_t i = 0;
  for (int s : swz) o.swizzle[i++] = static_cast<uint8_t>(s);
  return o;
}
Operand Operand::of_const(const Constant& c) {
  Operand o;
  o.kind = Kind::Const;
  o.type = c.type;
  o.value = c;
  return o;
}
bool Operand::identity_swizzle(int var_width) const {
  if (!is_var() || type.width != var_width) return false;
  for (int i = 0; i < var_width; ++i)
    if (swizzle[static_cast<size_t>(i)] != i) return false;
  return true;
}

Stmt Stmt::assign(VarId dst, Op op, std::vector<Operand> args, SourceLoc loc) {
  Stmt s;
  s.kind = StmtKind::Assign;
  s.dst = dst;
  s.op = op;
  s.args = std::move(args);
  s.loc = loc;
  return s;
}
Stmt Stmt::make_if(Operand cond, SourceLoc loc) {
  Stmt s;
  s.kind = StmtKind::If;
  s.cond = cond;
  s.loc = loc;
  return s;
}
Stmt Stmt::make_loop(LoopKind kind, SourceLoc loc) {
  Stmt s;
  s.kind = StmtKind::Loop;
  s.loop = kind;
  s.loc = loc;
  return s;
}
Stmt Stmt::make(StmtKind kind, SourceLoc loc) {
  Stmt s;
  s.kind = kind;
  s.loc = loc;
  return s;
}

VarId Function::add_var(Type t, VarRole role, std::string n) {
  vars.push_back(Variable{std::move(n), t, role, -1});
  return static_cast<VarId>(vars.size() - 1);
}

const char* boundary_name(Boundary b) {
  switch (b) {
    case Boundary::Clamp:
      return "clamp";
    case Boundary::Wrap:
      return "wrap";
    case Boundary::Mirror:
      return "mirror";
    case Boundary::Constant:
      return "constant";
  }
  return "?";
}

// The reference for every backend's helpers (rill_wrap_index, rill_mirror_index: same
// arithmetic). A negative index is mapped through -1 - i (~i), which is never negative and
// never overflows, so no backend takes a remainder of a negative number (C truncates it,
// GLSL leaves it undefined).
int64_t boundary_index(Boundary b, int32_t i, int64_t n) {
  const int64_t j = i >= 0 ? i : -1 - static_cast<int64_t>(i);
  switch (b) {
    case Boundary::Wrap:
      return i >= 0 ? j % n : n - 1 - j % n;
    case Boundary::Mirror: {
      // mirror(i) == mirror(-1 - i); from 0 up, even periods run forwards, odd ones back.
      const int64_t r = j % n;
      return (j / n) % 2 == 0 ? r : n - 1 - r;
    }
    case Boundary::Clamp:
    case Boundary::Constant:
      break;
  }
  return i < 0 ? 0 : (i >= n ? n - 1 : i);
}

std::string Function::var_name(VarId v) const {
  const Variable& var = vars.at(v);
  if (var.name.empty()) return "t" + std::to_string(v);
  // Keep only identifier characters, and add the id: names stay unique and can never
  // collide with a keyword of any target language.
  std::string out;
  for (char ch : var.name) {
    bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9');
    out += ok ? ch : '_';
  }
  if (out.empty() || (out[0] >= '0' && out[0] <= '9')) out = "v" + out;
  return out + "_" + std::to_string(v);
}

int count_statements(const Block& b) {
  int n = 0;
  for_each_stmt(b, [&](const Stmt&) { ++n; });
  return n;
}

int count_loops(const Block& b) {
  int n = 0;
  for_each_stmt(b, [&](const Stmt& s) { n += s.kind == StmtKind::Loop; });
  return n;
}

bool contains(const Block& b, StmtKind kind) {
  bool found = false;
  for_each_stmt(b, [&](const Stmt& s) { found = found || s.kind == kind; });
  return found;
}

bool contains(const Block& b, Op op) {
  bool found = false;
  for_each_stmt(b, [&](const Stmt& s) {
    found = found || (s.kind == StmtKind::Assign && s.op == op);
  });
  return found;
}

bool jumps_out_of_loop(const Block& b, StmtKind jump) {
  for (const Stmt& s : b) {
    if (s.kind == jump) return true;
    if (s.kind == StmtKind::If &&
        (jumps_out_of_loop(s.then_body, jump) || jumps_out_of_loop(s.else_body, jump)))
      return true;
  }
  return false;
}

}  // namespace rill::ir
