// The Builder behind capture: records statements into the innermost open block and checks
// that control-flow macros nest properly.
#include "rill/Capture.h"

#include <array>
#include <atomic>
#include <cstring>
#include <map>
#include <mutex>
#include <tuple>

#include "rill/Math.h"
#include "rill/Parameters.h"
#include "rill/Stopwatch.h"
#include "rill/Stream.h"
#include "rill/ir/Verifier.h"
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::detail {

namespace {

// One open control-flow construct: the statement being built and which of its blocks is
// being filled.
enum class Section { Then, Else, Cond, Body, Step };

struct Frame {
  ir::Stmt stmt;
  Section section;
  SourceLoc opened;
  bool chained = false;  // an else-if: closed together with the if it hangs off
  const char* macro;     // what opened it, for messages
};

struct Builder {
  uint64_t serial;
  SourceLoc defined_at;
  std::shared_ptr<ir::Function> fn = std::make_shared<ir::Function>();
  std::vector<Frame> open;
  bool pending_else_if = false;
  std::map<const UniformState*, ir::VarId> uniform_vars;
  std::vector<std::shared_ptr<UniformState>> uniforms;
  // (data, boundary mode, border bits) -> index in fn->arrays
  std::map<std::tuple<const ArrayState*, ir::Boundary, std::array<uint32_t, 4>>, int> array_ids;
  std::vector<std::shared_ptr<ArrayState>> arrays;
  std::vector<PrintSite> prints;

  ir::Block* root = nullptr;  // where top-level statements go (fn->body unless extending)
  // Locations (SourceLoc): the latest statement recorded with a location of the user's,
  // which statements recorded by operators get (marked nearest); the chain of open
  // CallSites; and the location every statement gets while a located library call runs
  // (LocatedCall: normalize(v) at the user's line) or while extending a function
  // (ExtendScope: the location of the statement that the recorded code replaces).
  SourceLoc near;
  const SourceLoc* chain = nullptr;
  SourceLoc within;
  Stopwatch started;          // when the program's definition began (capture_ms)

  ir::Block& current() {
    if (open.empty()) return root ? *root : fn->body;
    Frame& f = open.back();
    switch (f.section) {
      case Section::Then: return f.stmt.then_body;
      case Section::Else: return f.stmt.else_body;
      case Section::Cond: return f.stmt.cond_body;
      case Section::Body: return f.stmt.body;
      case Section::Step: return f.stmt.step;
    }
    return fn->body;
  }
};

thread_local std::vector<Builder*> t_builders;
std::atomic<uint64_t> g_next_serial{1};
std::mutex g_names_mutex;
std::map<uint64_t, std::string> g_names;

Builder& builder(const char* what, SourceLoc loc) {
  if (t_builders.empty())
    throw Error(std::string(what) + " outside a program: DSL operations must run inside "
                                    "the body given to rill::program()",
                loc);
  return *t_builders.back();
}

// Rill's own headers and sources record code too (math routines, library kernels): their
// lines say nothing to the user, who gets the nearest line of their own instead.
bool library_file(const char* file) {
  return std::strstr(file, "include/rill/") != nullptr || std::strstr(file, "dsl/src/") != nullptr;
}

bool user_location(SourceLoc loc) {
  return loc.known() && !library_file(loc.file);
}

// The location an error or a statement recorded now names: `loc` itself when it is the
// user's (with the chain of open CallSites), else the nearest located statement.
SourceLoc where(const Builder& b, SourceLoc loc) {
  if (user_location(loc)) {
    loc.nearest = false;
    loc.caller = b.chain;
    return loc;
  }
  if (b.within.known()) return b.within;
  SourceLoc n = b.near;
  n.nearest = n.known();
  return n;
}

// where(), for a statement being recorded: a location of the user's becomes the nearest
// one for the operators that follow.
SourceLoc locate(Builder& b, SourceLoc loc) {
  SourceLoc at = where(b, loc);
  if (at.known() && !at.nearest) b.near = at;
  return at;
}

// A chain link that lives as long as the process (SourceLoc::caller), one per distinct
// call site and outer chain.
const SourceLoc* intern(SourceLoc at, const SourceLoc* outer) {
  static std::mutex mutex;
  static std::map<std::tuple<const char*, unsigned, const SourceLoc*>, SourceLoc> links;
  std::lock_guard<std::mutex> lock(mutex);
  at.nearest = false;
  at.caller = outer;
  return &links.try_emplace(std::make_tuple(at.file, at.line, outer), at).first->second;
}

std::string describe(const Frame& f) {
  return std::string(f.macro) + (f.opened.known() ? " at " + f.opened.describe() : "");
}

// Checks that the innermost open construct is the one `macro` closes or continues.
Frame& expect(Builder& b, const char* macro, SourceLoc loc, bool (*ok)(const Frame&),
              const char* expected) {
  if (b.open.empty())
    throw Error(std::string(macro) + " without a matching " + expected, loc);
  Frame& f = b.open.back();
  if (!ok(f))
    throw Error(std::string(macro) + " does not match the innermost open construct, " +
                    describe(f) + " (expected " + expected + ")",
                loc);
  return f;
}

void close_into_parent(Builder& b) {
  ir::Stmt s = std::move(b.open.back().stmt);
  b.open.pop_back();
  b.current().push_back(std::move(s));
}

bool is_if(const Frame& f) { return f.stmt.kind == ir::StmtKind::If; }
bool is_if_then(const Frame& f) { return is_if(f) && f.section == Section::Then; }
bool is_while_body(const Frame& f) {
  return f.stmt.kind == ir::StmtKind::Loop && f.stmt.loop == ir::LoopKind::While &&
         f.section == Section::Body;
}
bool is_while_cond(const Frame& f) {
  return f.stmt.kind == ir::StmtKind::Loop && f.stmt.loop == ir::LoopKind::While &&
         f.section == Section::Cond;
}
bool is_do_body(const Frame& f) {
  return f.stmt.kind == ir::StmtKind::Loop && f.stmt.loop == ir::LoopKind::DoUntil &&
         f.section == Section::Body;
}
bool is_do_cond(const Frame& f) {
  return f.stmt.kind == ir::StmtKind::Loop && f.stmt.loop == ir::LoopKind::DoUntil &&
         f.section == Section::Cond;
}
bool is_for(ir::LoopKind k, const Frame& f) {
  return f.stmt.kind == ir::StmtKind::Loop && f.stmt.loop == k;
}
bool is_for_cond(const Frame& f) { return is_for(ir::LoopKind::For, f) && f.section == Section::Cond; }
bool is_for_step(const Frame& f) { return is_for(ir::LoopKind::For, f) && f.section == Section::Step; }
bool is_for_body(const Frame& f) { return is_for(ir::LoopKind::For, f) && f.section == Section::Body; }

void push(Builder& b, ir::Stmt s, Section sec, SourceLoc loc, const char* macro,
          bool chained = false) {
  b.open.push_back(Frame{std::move(s), sec, loc, chained, macro});
}

}  // namespace

bool in_program() { return !t_builders.empty(); }

void require_program(const char* what, SourceLoc loc) { builder(what, loc); }

std::string program_name(uint64_t serial) {
  std::lock_guard<std::mutex> lock(g_names_mutex);
  auto it = g_names.find(serial);
  return it == g_names.end() ? std::string() : it->second;
}

ir::Operand operand(const Ref& r, ir::Type t, SourceLoc loc) {
  switch (r.kind) {
    case Ref::Kind::Const: {
      ir::Constant c = r.value;
      c.type = t;
      return ir::Operand::of_const(c);
    }
    case Ref::Kind::Var: {
      Builder& b = builder("reading a DSL variable", loc);
      loc = where(b, loc);
      if (r.program != b.serial) {
        std::string other = program_name(r.program);
        throw Error("a value of program '" + other + "' is used in program '" + b.fn->name +
                        "'; values belong to the program that created them (pass data "
                        "between kernels through streams, or share constants made outside "
                        "any program)",
                    loc);
      }
      return ir::Operand::of_var(r.var, t);
    }
    case Ref::Kind::Uniform: {
      Builder& b = builder("reading a uniform", loc);
      loc = where(b, loc);
      const UniformState* key = r.uniform.get();
      auto it = b.uniform_vars.find(key);
      if (it == b.uniform_vars.end()) {
        for (const auto& u : b.uniforms)
          if (u->name == r.uniform->name)
            throw Error("two different uniforms named '" + u->name + "' are used in program '" +
                            b.fn->name + "'",
                        loc);
        ir::VarId v = b.fn->add_var(t, ir::VarRole::Uniform, r.uniform->name);
        b.fn->vars[v].slot = static_cast<int>(b.fn->uniforms.size());
        b.fn->uniforms.push_back(v);
        b.uniforms.push_back(r.uniform);
        it = b.uniform_vars.emplace(key, v).first;
      }
      return ir::Operand::of_var(it->second, t);
    }
  }
  throw Error("corrupt DSL value");
}

Ref emit(ir::Op op, ir::Type result, std::vector<ir::Operand> args, SourceLoc loc) {
  Builder& b = builder(ir::op_name(op), loc);
  loc = locate(b, loc);
  ir::VarId v = b.fn->add_var(result);
  b.current().push_back(ir::Stmt::assign(v, op, std::move(args), loc));
  Ref r;
  r.kind = Ref::Kind::Var;
  r.program = b.serial;
  r.var = v;
  return r;
}

Ref emit_gather(const std::shared_ptr<ArrayState>& array, std::vector<ir::Operand> index,
                ir::Boundary boundary, const ir::Constant& border, SourceLoc loc) {
  Builder& b = builder("an array gather", loc);
  loc = locate(b, loc);
  // Only Constant reads its border: other modes share one entry whatever the border holds.
  const std::array<uint32_t, 4> border_bits =
      boundary == ir::Boundary::Constant ? border.bits : std::array<uint32_t, 4>{};
  const auto key =
      std::make_tuple(static_cast<const ArrayState*>(array.get()), boundary, border_bits);
  auto it = b.array_ids.find(key);
  if (it == b.array_ids.end()) {
    int id = static_cast<int>(b.fn->arrays.size());
    ir::ArrayDecl decl{array->name, array->type(), array->dims};
    decl.boundary = boundary;
    if (boundary == ir::Boundary::Constant) {
      decl.border = border;
      decl.border.type = array->type();
    }
    b.fn->arrays.push_back(std::move(decl));
    b.arrays.push_back(array);
    it = b.array_ids.emplace(key, id).first;
  }
  ir::VarId v = b.fn->add_var(array->type());
  ir::Stmt s = ir::Stmt::assign(v, ir::Op::Gather, std::move(index), loc);
  s.array = it->second;
  b.current().push_back(std::move(s));
  Ref r;
  r.kind = Ref::Kind::Var;
  r.program = b.serial;
  r.var = v;
  return r;
}

void label(const Ref& r, std::string name, SourceLoc loc) {
  if (name.empty()) throw Error("rill::label: the name is empty", loc);
  if (r.kind == Ref::Kind::Uniform)
    throw Error("rill::label('" + name + "'): a uniform keeps the name it was declared with ('" +
                    r.uniform->name + "')",
                loc);
  if (r.kind == Ref::Kind::Const)
    throw Error("rill::label('" + name +
                    "'): this value is a constant made outside any program, not a variable of "
                    "one; only values created inside a program body can be named",
                loc);
  Builder& b = builder("rill::label", loc);
  loc = locate(b, loc);
  if (r.program != b.serial)
    throw Error("rill::label('" + name + "'): the value belongs to program '" +
                    program_name(r.program) + "', not to '" + b.fn->name + "'",
                loc);
  ir::Variable& v = b.fn->vars.at(r.var);
  if (v.role == ir::VarRole::Input || v.role == ir::VarRole::Output)
    throw Error("rill::label('" + name +
                    "'): " + (v.role == ir::VarRole::Input ? "input '" : "output '") + v.name +
                    "' keeps the name it was declared with (kernels bind streams by it)",
                loc);
  v.name = std::move(name);
}

Ref new_var(ir::Type t, ir::VarRole role, std::string name, SourceLoc loc) {
  const char* what = role == ir::VarRole::Input    ? "declaring an Input"
                     : role == ir::VarRole::Output ? "declaring an Output"
                                                   : "declaring a DSL variable";
  Builder& b = builder(what, loc);
  loc = locate(b, loc);
  if (role == ir::VarRole::Input || role == ir::VarRole::Output) {
    if (!b.open.empty())
      throw Error(std::string(what) + " inside " + describe(b.open.back()) +
                      ": inputs and outputs belong at the top of the program body",
                  loc);
    const auto& same = role == ir::VarRole::Input ? b.fn->inputs : b.fn->outputs;
    if (name.empty())
      name = (role == ir::VarRole::Input ? "in" : "out") + std::to_string(same.size());
    for (ir::VarId other : same)
      if (b.fn->vars[other].name == name)
        throw Error(std::string(what) + ": the name '" + name + "' is already taken", loc);
  }
  ir::VarId v = b.fn->add_var(t, role, std::move(name));
  if (role == ir::VarRole::Input) {
    b.fn->vars[v].slot = static_cast<int>(b.fn->inputs.size());
    b.fn->inputs.push_back(v);
  } else if (role == ir::VarRole::Output) {
    b.fn->vars[v].slot = static_cast<int>(b.fn->outputs.size());
    b.fn->outputs.push_back(v);
  }
  Ref r;
  r.kind = Ref::Kind::Var;
  r.program = b.serial;
  r.var = v;
  return r;
}

Ref new_hidden_output(ir::Type t, std::string name, SourceLoc loc, int* slot) {
  // A variable made where capture is, then made an output: new_var would refuse an output
  // declared inside a block, which a print may well be.
  Ref r = new_var(t, ir::VarRole::Local, std::move(name), loc);
  ir::Function& f = *builder("rill::print", loc).fn;
  f.vars[r.var].role = ir::VarRole::Output;
  f.vars[r.var].slot = *slot = static_cast<int>(f.outputs.size());
  f.outputs.push_back(r.var);
  return r;
}

std::vector<PrintSite>& print_sites(SourceLoc loc) {
  return builder("rill::print", loc).prints;
}

void assign(const Ref& dst, const ir::Mask& mask, const ir::Operand& src, SourceLoc loc) {
  Builder& b = builder("an assignment", loc);
  loc = locate(b, loc);
  if (dst.kind != Ref::Kind::Var) throw Error("assignment to something that is not a variable", loc);
  if (dst.program != b.serial)
    throw Error("assignment to a value of program '" + program_name(dst.program) +
                    "' inside program '" + b.fn->name + "'",
                loc);
  ir::Stmt s = ir::Stmt::assign(dst.var, ir::Op::Copy, {src}, loc);
  s.mask = mask;
  // A scalar written to several components is broadcast, by swizzle or constant splat.
  int width = mask.full() ? b.fn->var(dst.var).type.width : mask.count;
  ir::Operand& a = s.args[0];
  if (a.width() == 1 && width > 1) {
    if (a.is_var()) {
      a.swizzle = {a.swizzle[0], a.swizzle[0], a.swizzle[0], a.swizzle[0]};
    } else {
      for (int i = 1; i < width; ++i) a.value.bits[static_cast<size_t>(i)] = a.value.bits[0];
      a.value.type.width = static_cast<uint8_t>(width);
    }
    a.type.width = static_cast<uint8_t>(width);
  }
  b.current().push_back(std::move(s));
}

// --- control flow ------------------------------------------------------------------------

void begin_if(const ir::Operand& cond, SourceLoc loc) {
  Builder& b = builder("RILL_IF", loc);
  loc = locate(b, loc);
  bool chained = b.pending_else_if;
  b.pending_else_if = false;
  push(b, ir::Stmt::make_if(cond, loc), Section::Then, loc, chained ? "RILL_ELSE_IF" : "RILL_IF",
       chained);
}

void begin_else(SourceLoc loc) {
  Builder& b = builder("RILL_ELSE", loc);
  loc = locate(b, loc);
  if (!b.open.empty() && is_if(b.open.back()) && b.open.back().section == Section::Else)
    throw Error("a second RILL_ELSE for " + describe(b.open.back()), loc);
  Frame& f = expect(b, "RILL_ELSE", loc, is_if_then, "RILL_IF");
  f.section = Section::Else;
}

void begin_else_if(SourceLoc loc) {
  Builder& b = builder("RILL_ELSE_IF", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_ELSE_IF", loc, is_if_then, "RILL_IF");
  f.section = Section::Else;
  b.pending_else_if = true;  // the if that follows is part of this chain
}

void end_if(SourceLoc loc) {
  Builder& b = builder("RILL_ENDIF", loc);
  loc = locate(b, loc);
  expect(b, "RILL_ENDIF", loc, is_if, "RILL_IF");
  bool chained = b.open.back().chained;
  close_into_parent(b);
  while (chained) {  // an else-if chain closes with one RILL_ENDIF
    chained = b.open.back().chained;
    close_into_parent(b);
  }
}

void begin_while(SourceLoc loc) {
  Builder& b = builder("RILL_WHILE", loc);
  loc = locate(b, loc);
  push(b, ir::Stmt::make_loop(ir::LoopKind::While, loc), Section::Cond, loc, "RILL_WHILE");
}

void while_body(const ir::Operand& cond, SourceLoc loc) {
  Builder& b = builder("RILL_WHILE", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_WHILE", loc, is_while_cond, "RILL_WHILE");
  f.stmt.cond = cond;
  f.section = Section::Body;
}

void end_while(SourceLoc loc) {
  Builder& b = builder("RILL_ENDWHILE", loc);
  loc = locate(b, loc);
  expect(b, "RILL_ENDWHILE", loc, is_while_body, "RILL_WHILE");
  close_into_parent(b);
}

void begin_do(SourceLoc loc) {
  Builder& b = builder("RILL_DO", loc);
  loc = locate(b, loc);
  push(b, ir::Stmt::make_loop(ir::LoopKind::DoUntil, loc), Section::Body, loc, "RILL_DO");
}

void begin_until(SourceLoc loc) {
  Builder& b = builder("RILL_UNTIL", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_UNTIL", loc, is_do_body, "RILL_DO");
  f.section = Section::Cond;
}

void end_until(const ir::Operand& cond, SourceLoc loc) {
  Builder& b = builder("RILL_UNTIL", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_UNTIL", loc, is_do_cond, "RILL_DO");
  f.stmt.cond = cond;
  close_into_parent(b);
}

void begin_for(SourceLoc loc) {
  Builder& b = builder("RILL_FOR", loc);
  loc = locate(b, loc);
  push(b, ir::Stmt::make_loop(ir::LoopKind::For, loc), Section::Cond, loc, "RILL_FOR");
}

void for_cond(const ir::Operand& cond, SourceLoc loc) {
  Builder& b = builder("RILL_FOR", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_FOR", loc, is_for_cond, "RILL_FOR");
  f.stmt.cond = cond;
  f.section = Section::Step;
}

void for_body(SourceLoc loc) {
  Builder& b = builder("RILL_FOR", loc);
  loc = locate(b, loc);
  Frame& f = expect(b, "RILL_FOR", loc, is_for_step, "RILL_FOR");
  f.section = Section::Body;
}

void end_for(SourceLoc loc) {
  Builder& b = builder("RILL_ENDFOR", loc);
  loc = locate(b, loc);
  expect(b, "RILL_ENDFOR", loc, is_for_body, "RILL_FOR");
  close_into_parent(b);
}

namespace {
void jump(ir::StmtKind kind, const char* macro, SourceLoc loc) {
  Builder& b = builder(macro, loc);
  loc = locate(b, loc);
  if (kind != ir::StmtKind::Discard) {
    // The innermost loop must be in its body (not computing its condition or step).
    bool ok = false;
    for (auto it = b.open.rbegin(); it != b.open.rend(); ++it) {
      if (it->stmt.kind != ir::StmtKind::Loop) continue;
      ok = it->section == Section::Body;
      if (!ok)
        throw Error(std::string(macro) + " inside the condition or step of " + describe(*it),
                    loc);
      break;
    }
    if (!ok) throw Error(std::string(macro) + " outside a loop", loc);
  }
  b.current().push_back(ir::Stmt::make(kind, loc));
}
}  // namespace

void emit_break(SourceLoc loc) { jump(ir::StmtKind::Break, "RILL_BREAK", loc); }
void emit_continue(SourceLoc loc) { jump(ir::StmtKind::Continue, "RILL_CONTINUE", loc); }
void emit_discard(SourceLoc loc) { jump(ir::StmtKind::Discard, "RILL_DISCARD", loc); }

// --- program scope -----------------------------------------------------------------------

ProgramScope::ProgramScope(std::string name, SourceLoc loc) {
  auto* b = new Builder;
  b->serial = g_next_serial++;
  b->defined_at = loc;
  if (user_location(loc)) b->near = loc;  // operators before any located statement
  b->fn->name = name.empty() ? "kernel" : name;
  b->fn->defined_at = loc;
  {
    std::lock_guard<std::mutex> lock(g_names_mutex);
    g_names[b->serial] = b->fn->name;
  }
  t_builders.push_back(b);
}

ProgramScope::~ProgramScope() {
  if (!t_builders.empty()) {
    delete t_builders.back();
    t_builders.pop_back();
  }
}

ExtendScope::ExtendScope(ir::Function& f, SourceLoc at) {
  auto* b = new Builder;
  b->within = at;
  b->serial = g_next_serial++;
  b->fn = std::shared_ptr<ir::Function>(&f, [](ir::Function*) {});  // not owned
  b->root = &block_;
  serial_ = b->serial;
  t_builders.push_back(b);
}

ExtendScope::~ExtendScope() {
  delete t_builders.back();
  t_builders.pop_back();
}

Ref ExtendScope::var(ir::VarId v) const {
  Ref r;
  r.kind = Ref::Kind::Var;
  r.program = serial_;
  r.var = v;
  return r;
}

SourceLoc nearest_location() {
  if (t_builders.empty()) return {};
  return where(*t_builders.back(), {});
}

ir::Block ExtendScope::take() {
  if (!t_builders.back()->open.empty())
    throw Error("internal: a control-flow construct is left open while extending a function");
  return std::move(block_);
}

CapturedProgram ProgramScope::finish() {
  Builder& b = *t_builders.back();
  if (!b.open.empty())
    throw Error("program '" + b.fn->name + "' ends while " + describe(b.open.back()) +
                    " is still open",
                b.defined_at);
  for (ir::VarId o : b.fn->outputs) {
    bool written = false;
    ir::for_each_stmt(b.fn->body, [&](const ir::Stmt& s) {
      if (s.kind == ir::StmtKind::Assign && s.dst == o) written = true;
    });
    if (!written)
      throw Error("program '" + b.fn->name + "': output '" + b.fn->vars[o].name +
                      "' is never written",
                  b.defined_at);
  }
  ir::verify_or_throw(*b.fn, "capture");
  // The listing in an order of its own, not the one this C++ compiler evaluated the body in
  // (passes::canonicalize); uniforms and arrays follow it, so the lists that launches bind
  // by slot are permuted alike.
  passes::InterfaceOrder order;
  passes::canonicalize(*b.fn, &order);
  ir::verify_or_throw(*b.fn, "canonicalize");
  CapturedProgram out{b.fn, {}, {}, 0.0, {}};
  for (size_t i : order.uniforms) out.uniforms.push_back(b.uniforms[i]);
  for (size_t i : order.arrays) out.arrays.push_back(b.arrays[i]);
  out.capture_ms = b.started.ms();
  out.prints = b.prints;
  return out;
}

}  // namespace rill::detail

namespace rill {

namespace detail {

LocatedCall::LocatedCall(SourceLoc loc) {
  // The outermost located call names the user's line: normalize's own calls of dot and sqrt
  // do not replace it with lines of Math.h.
  if (t_builders.empty() || !user_location(loc)) return;
  Builder& b = *t_builders.back();
  if (b.within.known()) return;
  active_ = true;
  loc.nearest = false;
  loc.caller = b.chain;
  b.within = loc;
}

LocatedCall::~LocatedCall() {
  if (!active_ || t_builders.empty()) return;
  Builder& b = *t_builders.back();
  b.near = b.within;
  b.within = {};
}

}  // namespace detail

CallSite::CallSite(SourceLoc at) {
  if (detail::t_builders.empty() || !detail::user_location(at)) return;
  detail::Builder& b = *detail::t_builders.back();
  active_ = true;
  saved_chain_ = b.chain;
  at.caller = b.chain;
  at.nearest = false;
  call_ = at;
  b.chain = detail::intern(at, b.chain);
  b.near = at;  // operators before the function's first located statement
}

CallSite::~CallSite() {
  if (!active_ || detail::t_builders.empty()) return;
  detail::Builder& b = *detail::t_builders.back();
  b.chain = saved_chain_;
  b.near = call_;  // the caller's statements that follow come after the call
}

Int element_index(SourceLoc loc) {
  return Int(detail::emit(ir::Op::ElementIndex, ir::int_type(1), {}, loc), detail::AdoptTag{});
}
Int2 element_coord(SourceLoc loc) {
  return Int2(detail::emit(ir::Op::ElementCoord, ir::int_type(2), {}, loc), detail::AdoptTag{});
}

}  // namespace rill
