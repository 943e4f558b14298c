// The one printer for C-family targets (C for the CPU backend, OpenCL C, GLSL).
//
// The three languages share statements, expressions, operators and structured control
// flow; they differ in type names, literals, built-in function names, how a vector's
// component is named, and how a kernel reads its inputs and ends an element. The printer
// owns everything shared; a Dialect answers the differences. A backend then wraps the
// printed body in its own entry point (an element loop, an OpenCL kernel, a main()).
//
// Semantics are fixed here, not in the dialects: every componentwise operation is printed
// per component, in a fixed evaluation order and fully parenthesized, as the form column of
// ir/Ops.def says, and every operation whose meaning the languages disagree on (min/max with
// NaN, integer division by zero, float-to-int overflow, mod, sign, fract) calls a rill_*
// helper whose definition each dialect's prelude gives with the same semantics (the helper
// table, Helpers.cpp).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::codegen {

class Dialect {
 public:
  virtual ~Dialect() = default;

  // True: a vector variable is printed as one scalar variable per component (C).
  // False: as a native vector with .x/.y/.z/.w components (OpenCL C, GLSL).
  virtual bool scalarize() const = 0;
  // Type of one component of kind k ("float", "double", "int", "bool").
  virtual std::string scalar_type(ir::ScalarKind k) const = 0;
  // Type of a whole variable (for non-scalarizing dialects): "float3", "vec3".
  virtual std::string vector_type(ir::Type t) const = 0;
  // A literal of one component, exact (float bits preserved).
  virtual std::string literal(ir::ScalarKind k, uint32_t bits) const = 0;
  // Header of an endless loop: "for (;;)" or "while (true)".
  virtual std::string loop_header() const { return "for (;;)"; }
  // What ends an element without writing it (goto, return, discard).
  virtual std::string discard() const = 0;
  // Qualifier put before float declarations (GLSL's "precise" in strict mode).
  virtual std::string float_qualifier() const { return ""; }

  // Value a variable starts with: inputs, outputs (the stream's current element) and
  // uniforms come from the launch; everything else starts at zero.
  virtual std::string initial_value(const ir::Function& f, ir::VarId v, int comp) const = 0;
  // Statements computing a Gather; `dst(c)` names component c of the destination.
  virtual std::string gather(const ir::Function& f, const ir::Stmt& s,
                             const std::vector<std::string>& index,
                             const std::vector<std::string>& dst) const = 0;
  virtual std::string element_index() const = 0;
  virtual std::string element_coord(int comp) const = 0;
  // a OP b for one component of kind k (OP: < <= > >= == !=).
  virtual std::string compare(ir::ScalarKind, const char* op, const std::string& a,
                              const std::string& b) const {
    return "(" + a + " " + op + " " + b + ")";
  }
  // a / b on floats. GLSL routes it through a correctly rounded helper where the driver's
  // division is not exact (see backends/glsl/DivSqrt.h).
  virtual std::string float_div(const std::string& a, const std::string& b) const {
    return "(" + a + " / " + b + ")";
  }
  // c ? a : b for one component of kind k.
  virtual std::string select(ir::ScalarKind, const std::string& c, const std::string& a,
                             const std::string& b) const {
    return "(" + c + " ? " + a + " : " + b + ")";
  }
  // The function a HELPER form of Ops.def calls: rill_NAME (lockstep C: rill_v_NAME).
  virtual std::string helper(const std::string& name) const { return "rill_" + name; }
  // True: bools are lane masks (lockstep C), and LOGIC forms take their lane spelling.
  virtual bool lane_masks() const { return false; }
  // The test an `if` or a loop exit makes of a bool condition (lockstep C: whether any lane
  // has it).
  virtual std::string branch_condition(const std::string& c) const { return c; }
  // Component c of a lane-group op (class Group of Ops.def) on operands of kind k, the
  // operands printed in `args` (lockstep code: the active-lane mask last). By default a
  // group of one, the element alone: its own value, its predicate as a count or ballot bit,
  // size 1 and lane 0 (docs/programming-model.md).
  virtual std::string group(ir::Op op, ir::ScalarKind k, int c,
                            const std::vector<std::string>& args) const;
  // Source maps (SourceMap.h): the line put before generated code from the user's `loc`.
  // C and OpenCL C take a #line directive, which compilers' messages then follow; GLSL,
  // whose #line names no file, a comment.
  virtual std::string source_line(const SourceLoc& loc) const;
  // True when source_line() renumbers the lines after it (then a block's end puts the
  // generated numbering back: SourceMap.h).
  virtual bool source_line_renumbers() const { return true; }
};

// The helper mapping one gather index into its dimension under an array's boundary mode
// (ir::Boundary; ir::boundary_index is its reference): rill_clamp_index, rill_wrap_index or
// rill_mirror_index, defined by each dialect family's prelude (lockstep C: rill_v_*). A
// Constant-mode gather loads at the clamped index, so the load never leaves the array, and
// its dialect replaces the result by the border value unless rill_index_inside holds for
// every index.
inline std::string boundary_index_helper(ir::Boundary b) {
  switch (b) {
    case ir::Boundary::Wrap:
      return "wrap_index";
    case ir::Boundary::Mirror:
      return "mirror_index";
    case ir::Boundary::Clamp:
    case ir::Boundary::Constant:
      break;
  }
  return "clamp_index";
}

// Component c of Dot, Cross or Construct, the operations that combine components, spelled in
// one fixed order for every C-family printer (scalar or lockstep): `operand(o, i)` names
// component i of an operand.
std::string fixed_form_expr(const ir::Stmt& s, int c,
                            const std::function<std::string(const ir::Operand&, int)>& operand);

class CFamilyPrinter {
 public:
  // `source_map`: each statement's lines follow a line naming where the user wrote it
  // (Dialect::source_line); off, the text is exactly as without source maps.
  CFamilyPrinter(const ir::Function& f, const Dialect& d, bool source_map = false)
      : f_(f), d_(d), source_map_(source_map) {}

  // Declarations of every variable with its initial value, one per line.
  std::string declarations(int indent) const;
  // When set (scalarizing dialects), declarations() leaves out the components of non-
  // interface variables it says no to (outlining: those only outlined functions use).
  std::function<bool(ir::VarId, int)> declare;
  // The kernel body's statements.
  std::string body(int indent) const;

  // Names used by the backends' wrappers.
  std::string component(ir::VarId v, int c) const;  // one component, as an lvalue
  std::string operand(const ir::Operand& o, int c) const;

  // Outlining (backends/cpu/Outline.h): `outline`, when set, is asked about every nested
  // block before it is printed and may print it itself (as a call) by returning true.
  std::function<bool(std::string& out, const ir::Block& b, int indent)> outline;
  // What Discard prints, and Break or Continue outside every loop of the block being printed
  // (inside an outlined function: a return code); empty: the dialect's discard, a plain
  // break or continue.
  std::string discard_text, escape_break_text, escape_continue_text;
  // Statement kind Break, Continue or Discard as printed at the current point.
  std::string jump(ir::StmtKind kind) const;
  // The statements of b (b itself not offered to `outline`, its nested blocks are).
  std::string statements(const ir::Block& b, int indent) const;

 private:
  void block(std::string& out, const ir::Block& b, int indent) const;
  void stmt(std::string& out, const ir::Stmt& s, int indent) const;
  void assign(std::string& out, const ir::Stmt& s, const std::string& pad) const;
  std::string scalar_expr(const ir::Stmt& s, int c) const;

  const ir::Function& f_;
  const Dialect& d_;
  mutable int loop_depth_ = 0;  // loops open around the statement being printed
  bool source_map_ = false;
};

}  // namespace rill::codegen
