// Capture: how running C++ records IR (retained mode, as in Sh).
//
// While a program's body runs (see Program.h), a Builder is current on this thread. Every
// operation on a DSL value appends an Assign to the block the Builder is filling, and the
// control-flow macros (ControlFlow.h) open and close nested blocks. Host C++ between them
// runs once, at definition time: it is the metaprogramming layer that decides what code
// exists.
//
// This header is the narrow interface between the value types and the Builder; users never
// call it directly.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rill/Error.h"
#include "rill/ir/IR.h"

namespace rill::detail {

struct UniformState;
struct ArrayState;

// What a DSL value refers to: a constant (values made outside any program), a variable of
// one particular program, or a uniform (bound to a variable in whichever program reads it).
struct Ref {
  enum class Kind : uint8_t { Const, Var, Uniform };
  Kind kind = Kind::Const;
  uint64_t program = 0;  // serial of the owning program, for Var
  ir::VarId var = ir::kNoVar;
  ir::Constant value;  // for Const
  std::shared_ptr<UniformState> uniform;

  static Ref constant(const ir::Constant& c) {
    Ref r;
    r.value = c;
    return r;
  }
};

bool in_program();
// Throws unless a program is being defined; `what` names the operation for the message.
void require_program(const char* what, SourceLoc loc = {});

// Turns a value into an operand of the current program, checking that it belongs there.
ir::Operand operand(const Ref& r, ir::Type t, SourceLoc loc = {});
// Appends `result = op(args)` and returns the new temporary.
Ref emit(ir::Op op, ir::Type result, std::vector<ir::Operand> args, SourceLoc loc = {});
// Appends a gather from `array` read with `boundary` (`border`: the value outside the array
// for Boundary::Constant), registering the pair with the program on first use: the same data
// read with two modes is two arrays of the program, bound to the same storage.
Ref emit_gather(const std::shared_ptr<ArrayState>& array, std::vector<ir::Operand> index,
                ir::Boundary boundary = ir::Boundary::Clamp, const ir::Constant& border = {},
                SourceLoc loc = {});
// Names the variable `r` refers to (rill::label): the name then appears in printed IR and
// generated code. Throws for constants, uniforms, inputs and outputs.
void label(const Ref& r, std::string name, SourceLoc loc = {});
// A new variable of the current program.
Ref new_var(ir::Type t, ir::VarRole role, std::string name = {}, SourceLoc loc = {});
// Appends `dst[.mask] = src`. dst must be a variable of the current program.
void assign(const Ref& dst, const ir::Mask& mask, const ir::Operand& src, SourceLoc loc = {});
// While it lives, the statements recorded get `loc` (a library function's call site, such as
// normalize(v)'s), unless an outer LocatedCall already named one. Nothing outside a program
// or for a location in Rill's own headers.
class LocatedCall {
 public:
  explicit LocatedCall(SourceLoc loc);
  ~LocatedCall();
  LocatedCall(const LocatedCall&) = delete;
  LocatedCall& operator=(const LocatedCall&) = delete;

 private:
  bool active_ = false;
};

// The location of the latest statement of the user's recorded in the program being defined
// (marked nearest), for errors raised where no location can be passed, such as inside
// operator=. Unknown outside a program.
SourceLoc nearest_location();
// Name of the program a serial belongs to ("" if unknown), for error messages.
std::string program_name(uint64_t serial);

// Control flow (called by the RILL_* macros; each checks that it closes what is open).
void begin_if(const ir::Operand& cond, SourceLoc loc);
void begin_else(SourceLoc loc);
void begin_else_if(SourceLoc loc);  // followed by begin_if(cond) on the chained if
void end_if(SourceLoc loc);
void begin_while(SourceLoc loc);
void while_body(const ir::Operand& cond, SourceLoc loc);
void end_while(SourceLoc loc);
void begin_do(SourceLoc loc);
void begin_until(SourceLoc loc);
void end_until(const ir::Operand& cond, SourceLoc loc);
void begin_for(SourceLoc loc);
void for_cond(const ir::Operand& cond, SourceLoc loc);
void for_body(SourceLoc loc);
void end_for(SourceLoc loc);
void emit_break(SourceLoc loc);
void emit_continue(SourceLoc loc);
void emit_discard(SourceLoc loc);

// One rill::print in a program (Print.h): its format and the hidden outputs (named "rill$...",
// bound by Kernel, never by the user) that hold, per element, how often it ran and the raw
// bits of its arguments the first time. Slots are indices into Function::outputs.
struct PrintSite {
  std::string format;
  std::vector<ir::Type> args;
  int count_slot = -1;
  std::vector<int> arg_slots;  // parallel to args
  SourceLoc loc;
};
// A hidden output of the current program (its index in Function::outputs in *slot), declared
// wherever capture is (print may sit inside any block), and the current program's print table.
Ref new_hidden_output(ir::Type t, std::string name, SourceLoc loc, int* slot);
std::vector<PrintSite>& print_sites(SourceLoc loc);

// Program definition scope (used by rill::program).
struct CapturedProgram {
  std::shared_ptr<ir::Function> fn;
  std::vector<std::shared_ptr<UniformState>> uniforms;  // parallel to fn->uniforms
  std::vector<std::shared_ptr<ArrayState>> arrays;      // parallel to fn->arrays
  // Milliseconds spent making it: running the body, checking and hashing the IR (for a
  // program made by connect/combine, both halves' and the fusion's).
  double capture_ms = 0;
  std::vector<PrintSite> prints;  // rill::print statements, in the order captured
};

class ProgramScope {
 public:
  ProgramScope(std::string name, SourceLoc loc);
  ~ProgramScope();
  ProgramScope(const ProgramScope&) = delete;
  ProgramScope& operator=(const ProgramScope&) = delete;
  // Checks the captured program (macros closed, outputs written, IR valid) and returns it.
  CapturedProgram finish();
};

// Records DSL code into a block of an existing function: passes use it to write IR with the
// DSL itself (Rill's own math routines are ordinary DSL code, see passes/LowerMath.cpp).
class ExtendScope {
 public:
  // Statements recorded without a location of the user's get `at`: the location of the
  // statement that the recorded code replaces.
  explicit ExtendScope(ir::Function& f, SourceLoc at = {});
  ~ExtendScope();
  ExtendScope(const ExtendScope&) = delete;
  ExtendScope& operator=(const ExtendScope&) = delete;
  // A reference to an existing variable of f, usable as a DSL value.
  Ref var(ir::VarId v) const;
  // The statements recorded so far.
  ir::Block take();

 private:
  uint64_t serial_ = 0;
  ir::Block block_;
};

}  // namespace rill::detail

namespace rill {

// Marks a function of the user's that records DSL code, so that errors and source maps name
// the chain of calls ("shade.cpp:12, called from main.cpp:40") and not only the line inside
// it. The function takes its call site as a defaulted last argument and opens a CallSite for
// its body:
//
//   Float3 shade(const Float3& n, SourceLoc at = RILL_HERE) {
//     rill::CallSite site(at);
//     ...
//   }
//
// Outside a program it does nothing. CallSites nest.
class CallSite {
 public:
  explicit CallSite(SourceLoc at);
  ~CallSite();
  CallSite(const CallSite&) = delete;
  CallSite& operator=(const CallSite&) = delete;

 private:
  bool active_ = false;
  const SourceLoc* saved_chain_ = nullptr;
  SourceLoc call_;
};

}  // namespace rill
