// Rill's intermediate representation, all in one place.
//
// A kernel is a Function: typed variables, an interface (inputs, outputs, uniforms, arrays)
// and a structured body. The body is a tree of statements:
//
//   Assign   dst[.mask] = op(operands)      three-address form; operands are variables
//                                           (optionally swizzled) or constants
//   If       if (cond) { then } else { else }
//   Loop     while / do-until / for, each with a condition block that computes the test
//   Break, Continue, Discard
//
// The IR is structured (no gotos), so every emitter prints readable code without recovering
// structure, and every pass can reason about dominance by position: a statement dominates
// what follows it in its block and everything nested there.
//
// Variables are mutable (a DSL value assigned inside RILL_IF is one variable written in two
// places). Temporaries created by operations are written once; the passes exploit that.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rill/Error.h"
#include "rill/ir/Ops.h"
#include "rill/ir/Type.h"

namespace rill::ir {

// Where a statement came from in the user's source (the name diagnostics use): see Stmt::loc.
using SourceLocation = SourceLoc;

using VarId = uint32_t;
constexpr VarId kNoVar = ~VarId{0};

// A constant of up to four components, stored as raw bits so that folding and printing are
// exact (float components are binary32 bit patterns; bool components are 0 or 1).
struct Constant {
  Type type;
  std::array<uint32_t, 4> bits{};

  static Constant of_float(float v);
  static Constant of_int(int32_t v);
  static Constant of_bool(bool v);
  float f(int c) const;
  int32_t i(int c) const;
  bool b(int c) const { return bits[static_cast<size_t>(c)] != 0; }
  bool operator==(const Constant&) const = default;
};

// An operand: a variable read through a swizzle, or a constant.
struct Operand {
  enum class Kind : uint8_t { Var, Const };
  Kind kind = Kind::Const;
  VarId var = kNoVar;
  std::array<uint8_t, 4> swizzle{0, 1, 2, 3};  // which components of var, for Var operands
  Type type;                                   // type of the operand as read (after swizzle)
  Constant value;                              // for Const operands

  static Operand of_var(VarId v, Type var_type);  // identity swizzle
  static Operand of_var(VarId v, ScalarKind kind, std::initializer_list<int> swizzle);
  static Operand of_const(const Constant& c);

  bool is_var() const { return kind == Kind::Var; }
  bool is_const() const { return kind == Kind::Const; }
  int width() const { return type.width; }
  // Which component of `var` gives component c of this operand (broadcast if width 1).
  int component(int c) const { return swizzle[static_cast<size_t>(type.width == 1 ? 0 : c)]; }
  bool identity_swizzle(int var_width) const;
  bool operator==(const Operand&) const = default;
};

// A write mask: which components of the destination an Assign writes, in order.
// An empty mask writes the whole variable.
struct Mask {
  uint8_t count = 0;
  std::array<uint8_t, 4> comps{0, 1, 2, 3};

  bool full() const { return count == 0; }
  bool operator==(const Mask&) const = default;
};

enum class StmtKind : uint8_t { Assign, If, Loop, Break, Continue, Discard };
enum class LoopKind : uint8_t { While, DoUntil, For };

struct Stmt;
using Block = std::vector<Stmt>;

struct Stmt {
  StmtKind kind = StmtKind::Assign;
  // Where the user wrote it (Error.h's SourceLoc): the side table of locations, carried
  // beside each statement. It is not printed in the form that ir::hash reads, nor compared,
  // so it changes neither a kernel's cache key nor the code generated for it; passes copy
  // it to the statements they make from this one.
  SourceLoc loc;

  // Assign
  VarId dst = kNoVar;
  Mask mask;
  Op op = Op::Copy;
  std::vector<Operand> args;
  int array = -1;  // Gather: which of Function::arrays

  // If: cond (scalar bool) selects then_body or else_body.
  // Loop: cond_body computes cond.
  //   While:   each iteration runs cond_body, exits if !cond, then body.
  //   DoUntil: each iteration runs body, then cond_body, exits if cond.
  //   For:     like While, with step run after body (the init is emitted before the loop).
  Operand cond;
  Block then_body, else_body;
  LoopKind loop = LoopKind::While;
  Block cond_body, body, step;

  static Stmt assign(VarId dst, Op op, std::vector<Operand> args, SourceLoc loc = {});
  static Stmt make_if(Operand cond, SourceLoc loc = {});
  static Stmt make_loop(LoopKind kind, SourceLoc loc = {});
  static Stmt make(StmtKind kind, SourceLoc loc = {});
};

enum class VarRole : uint8_t { Temp, Local, Input, Output, Uniform };

struct Variable {
  std::string name;  // user name or "" (printers then use "t<id>")
  Type type;
  VarRole role = VarRole::Temp;
  int slot = -1;  // index in Function::inputs / outputs / uniforms
};

// What a gather reads at an index outside an array, per dimension of n elements. One
// definition for every backend (the interpreter, ir::boundary_index, is the reference):
//   Clamp     the nearest element: i < 0 reads 0, i >= n reads n - 1.
//   Wrap      periodic: i mod n, always in [0, n) (-1 reads n - 1).
//   Mirror    reflected at the edges with the edge repeated, as GL's MIRRORED_REPEAT:
//             ... 2 1 0 | 0 1 2 ... n-1 | n-1 n-2 ... (period 2n; -1 reads 0, n reads n - 1).
//   Constant  the ArrayDecl's border value when any index is outside its dimension.
// Indices are int32; the arithmetic never overflows (INT32_MIN and INT32_MAX included).
enum class Boundary : uint8_t { Clamp, Wrap, Mirror, Constant };
const char* boundary_name(Boundary b);  // "clamp", "wrap", "mirror", "constant"

// The index a gather reads in a dimension of n >= 1 elements, for Clamp, Wrap and Mirror
// (Constant reads the clamped index and replaces out-of-range results: index_inside).
int64_t boundary_index(Boundary b, int32_t i, int64_t n);
inline bool index_inside(int32_t i, int64_t n) {
  return i >= 0 && i < n;
}

struct ArrayDecl {
  std::string name;
  Type elem;
  int dims = 1;  // 1, 2 or 3: how many indices a Gather takes
  Boundary boundary = Boundary::Clamp;
  Constant border{};  // what a Constant-boundary gather reads outside the array (type elem)
};

// A whole kernel.
struct Function {
  std::string name;
  // Where the program was defined (rill::program's call): named by errors about the whole
  // kernel. Like Stmt::loc, outside the printed form that the caches hash.
  SourceLoc defined_at;
  std::vector<Variable> vars;
  std::vector<VarId> inputs;    // stream elements read, in declaration order
  std::vector<VarId> outputs;   // stream elements written, in declaration order
  std::vector<VarId> uniforms;  // host values, read-only, set per launch
  std::vector<ArrayDecl> arrays;
  Block body;

  VarId add_var(Type t, VarRole role = VarRole::Temp, std::string name = {});
  const Variable& var(VarId v) const { return vars.at(v); }
  // "x" for named variables, "t12" for temporaries.
  std::string var_name(VarId v) const;
};

// Structural queries shared by passes, emitters and tests.
int count_statements(const Block& b);  // all statements, nested ones included
int count_loops(const Block& b);
// Does b contain a statement of this kind anywhere, nested loops included?
bool contains(const Block& b, StmtKind kind);
// Does b compute op anywhere (element_coord, say, which an emitter sets up for)?
bool contains(const Block& b, Op op);
// Does b contain a jump (Break or Continue) of the loop whose body it is in: searched through
// ifs, not into nested loops, whose jumps are their own?
bool jumps_out_of_loop(const Block& b, StmtKind jump);

}  // namespace rill::ir
