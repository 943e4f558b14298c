// lower_lockstep: rewrites a kernel so that a group of elements (lanes) can run it together,
// as the simd backend does (ISPC- or SIMT-style): control flow becomes lane masks.
//
// The result is ordinary IR with one convention: the condition of every `if` and loop means
// "some lane has it". Every Bool variable is then a lane mask, and
//
// - an `if` computes the masks of the lanes taking each side, and runs a side only if some
//   lane takes it (a side of a few cheap assignments runs unguarded: see guarded());
// - an assignment under a mask keeps the old value in the other lanes: it computes into a
//   temporary, then blends, `x = select(mask, t, x)`; unless no lane that is off can ever
//   read x (see unblended_vars()), which skips the blend;
// - a loop keeps a mask of the lanes still looping and runs while it has one; break,
//   continue and discard clear lanes from masks instead of jumping, and the statements after
//   one that may have cleared lanes re-read the mask;
// - discard clears lanes from `alive`, which says at the end which lanes write their outputs.
//
// The output has no Break but the loops' own exits, and no Continue or Discard, only
// while-loops, and lanes that are off still compute (harmlessly: every helper is total).
//
// With one lane, "some lane has it" is just "it", so the lowered kernel is also a scalar
// kernel that computes what the original computes (with `if (!alive) discard` appended):
// tests check exactly that with the interpreter (tests/dsl/passes/LowerLockstepTest.cpp).
// The simd backend prints it through the lockstep dialect (backends/simd/VectorDialect.h),
// whose branch conditions test rill_any().
#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

// Variables whose lanes that are off may be overwritten: written by exactly one (whole)
// assignment and read only after it, in its block or inside what follows it there. Every
// read then runs for a subset of the lanes the assignment ran for (masks only narrow inside a
// block and its nested blocks), in the same loop iteration, so the value a lane that was off
// gets is never read, and the assignment can skip the blend with the old value.
std::vector<bool> unblended_vars(const Function& f) {
  std::vector<int> writes(f.vars.size(), 0);
  for_each_stmt(f.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::Assign)
      writes[s.dst] += s.mask.full() || s.mask.count == f.var(s.dst).type.width ? 1 : 2;
  });
  std::vector<bool> ok(f.vars.size(), false);
  for (VarId v = 0; v < f.vars.size(); ++v) {
    VarRole r = f.vars[v].role;
    ok[v] = writes[v] == 1 && (r == VarRole::Temp || r == VarRole::Local);
  }
  // Walk in program order with the set of candidates assigned earlier in an enclosing block;
  // a read of a candidate outside that set disqualifies it.
  std::vector<bool> visible(f.vars.size(), false);
  auto read = [&](const Operand& o) {
    if (o.is_var() && !visible[o.var]) ok[o.var] = false;
  };
  // A loop's condition is read at the end of its condition block, by lanes that ran it; a
  // lane that did not is already off the loop mask, so a value it never got is harmless.
  auto walk = [&](auto& self, const Block& b, const Operand* read_at_end) -> void {
    std::vector<VarId> added;
    for (const Stmt& s : b) {
      for (const Operand& o : s.args) read(o);
      if (s.kind == StmtKind::If) read(s.cond);
      for (const Block* sub : {&s.then_body, &s.else_body, &s.body, &s.step})
        self(self, *sub, nullptr);
      if (s.kind == StmtKind::Loop) self(self, s.cond_body, &s.cond);
      if (s.kind == StmtKind::Assign && ok[s.dst] && !visible[s.dst]) {
        visible[s.dst] = true;
        added.push_back(s.dst);
      }
    }
    if (read_at_end) read(*read_at_end);
    for (VarId v : added) visible[v] = false;
  };
  walk(walk, f.body, nullptr);
  return ok;
}

// May statement s turn lanes off for what follows it in its block?
bool exits(const Stmt& s) {
  auto leaves = [](const Block& b) {
    return jumps_out_of_loop(b, StmtKind::Break) || jumps_out_of_loop(b, StmtKind::Continue) ||
           contains(b, StmtKind::Discard);
  };
  switch (s.kind) {
    case StmtKind::Break:
    case StmtKind::Continue:
    case StmtKind::Discard:
      return true;
    case StmtKind::If:
      return leaves(s.then_body) || leaves(s.else_body);
    case StmtKind::Loop:
      return contains(s.cond_body, StmtKind::Discard) || contains(s.body, StmtKind::Discard) ||
             contains(s.step, StmtKind::Discard);
    case StmtKind::Assign:
      return false;
  }
  return false;
}

class LockstepLowering {
 public:
  explicit LockstepLowering(Function& f) : f_(f), unblended_(unblended_vars(f)) {}

  LockstepFunction run() {
    Block body;
    VarId top = kNoVar;  // no mask: every lane runs every top-level statement
    if (contains(f_.body, StmtKind::Discard)) {
      alive_ = mask_var("alive");
      body.push_back(Stmt::assign(alive_, Op::Copy, {Operand::of_const(Constant::of_bool(true))}));
      top = alive_;
    }
    Block original = std::move(f_.body);
    block(original, body, top, top);
    f_.body = std::move(body);
    return {std::move(f_), alive_};
  }

 private:
  struct LoopMasks {
    VarId looping;  // lanes still in the loop
    VarId running;  // lanes running this iteration's body (looping minus those continued)
  };

  VarId mask_var(const char* name) { return f_.add_var(bool_type(1), VarRole::Local, name); }
  static Operand use(VarId mask) { return Operand::of_var(mask, bool_type(1)); }
  void emit(Block& out, VarId dst, Op op, std::vector<Operand> args, SourceLoc loc) {
    out.push_back(Stmt::assign(dst, op, std::move(args), loc));
  }
  // mask = mask & m (lanes of `mask` that are also in m).
  void narrow(Block& out, VarId mask, const Operand& m, SourceLoc loc) {
    emit(out, mask, Op::And, {use(mask), m}, loc);
  }
  // A new mask holding `mask & cond`, or cond where there is no mask.
  VarId masked(Block& out, const char* name, VarId mask, const Operand& cond, SourceLoc loc) {
    VarId m = mask_var(name);
    if (mask == kNoVar)
      emit(out, m, Op::Copy, {cond}, loc);
    else
      emit(out, m, Op::And, {use(mask), cond}, loc);
    return m;
  }
  Operand negated(Block& out, const Operand& cond, SourceLoc loc) {
    VarId n = f_.add_var(bool_type(1));
    emit(out, n, Op::Not, {cond}, loc);
    return use(n);
  }

  // mask: the lanes this block runs for (kNoVar: all). live: the mask that break, continue
  // and discard clear lanes from, which is where the lanes still running after such a
  // statement are read back: a loop body's running lanes, a loop condition's or step's
  // looping lanes, the live lanes outside loops.
  void block(const Block& in, Block& out, VarId mask, VarId live) {
    for (const Stmt& s : in) {
      stmt(s, out, mask, live);
      if (exits(s) && mask != kNoVar && mask != live) narrow(out, mask, use(live), s.loc);
    }
  }

  void stmt(const Stmt& s, Block& out, VarId mask, VarId live) {
    switch (s.kind) {
      case StmtKind::Assign:
        return assign(s, out, mask);
      case StmtKind::If: {
        // Both masks first: a side may write the condition's variable.
        VarId then_mask = masked(out, "then", mask, s.cond, s.loc);
        VarId else_mask = kNoVar;
        if (!s.else_body.empty())
          else_mask = masked(out, "else", mask, negated(out, s.cond, s.loc), s.loc);
        Block then_body;
        block(s.then_body, then_body, then_mask, live);
        guarded(out, then_mask, std::move(then_body), s.loc);
        if (else_mask != kNoVar) {
          Block else_body;
          block(s.else_body, else_body, else_mask, live);
          guarded(out, else_mask, std::move(else_body), s.loc);
        }
        return;
      }
      case StmtKind::Loop:
        return loop(s, out, mask);
      case StmtKind::Break:
      case StmtKind::Continue:
      case StmtKind::Discard:
        return jump(s, out, mask);
    }
  }

  void assign(const Stmt& in, Block& out, VarId mask) {
    Stmt s = in;
    // A lane-group op reads the lanes running it: the mask they run under, as its last
    // operand (true where every lane runs; the emitter also leaves out spare lanes).
    if (reads_group(s.op))
      s.args.push_back(mask == kNoVar ? Operand::of_const(Constant::of_bool(true)) : use(mask));
    if (mask == kNoVar || unblended_[s.dst]) {
      out.push_back(std::move(s));
      return;
    }
    // t = op(args); dst[.mask] = select(mask, t, dst[.mask]). A copy blends its operand
    // directly: over half of the glass ray tracer's blends were of copies, and each
    // temporary is one more vector variable for the C compiler. (Not one that reads dst, whose
    // components the blend may overwrite before it reads them, nor a broadcast.)
    const Type dst_type = f_.var(s.dst).type;
    const int width = s.mask.full() ? dst_type.width : s.mask.count;
    Operand value;
    if (s.op == Op::Copy && s.args[0].type == dst_type.with_width(width) &&
        !(s.args[0].is_var() && s.args[0].var == s.dst)) {
      value = s.args[0];
    } else {
      VarId t = f_.add_var(dst_type.with_width(width));
      Stmt compute = s;
      compute.dst = t;
      compute.mask = Mask{};
      out.push_back(std::move(compute));
      value = Operand::of_var(t, dst_type.with_width(width));
    }
    Operand old = Operand::of_var(s.dst, dst_type);
    old.type = dst_type.with_width(width);
    for (int c = 0; c < width; ++c)
      old.swizzle[static_cast<size_t>(c)] =
          static_cast<uint8_t>(s.mask.full() ? c : s.mask.comps[static_cast<size_t>(c)]);
    Stmt blend = Stmt::assign(s.dst, Op::Select, {use(mask), value, old}, s.loc);
    blend.mask = s.mask;
    out.push_back(std::move(blend));
  }

  // A side of an if runs under `if (some lane has mask)`, unless it is a few cheap
  // assignments (kUnguardedLimit, no gathers or transcendentals): those run for every lane,
  // which changes nothing, since every assignment under a mask blends or is unblended (its
  // value in lanes that are off is never read; see unblended_vars()). The guard costs a test,
  // a branch and two basic blocks per side: a kernel of 400 short ifs compiled 2.5x faster
  // unguarded (docs/benchmarks/2026-11-24-simd-compile.md).
  static constexpr size_t kUnguardedLimit = 8;
  static bool needs_guard(const Block& body) {
    if (body.size() > kUnguardedLimit) return true;
    for (const Stmt& s : body)
      if (s.kind != StmtKind::Assign || s.op == Op::Gather || is_transcendental(s.op)) return true;
    return false;
  }
  void guarded(Block& out, VarId mask, Block body, SourceLoc loc) {
    if (!needs_guard(body)) {
      for (Stmt& s : body) out.push_back(std::move(s));
      return;
    }
    Stmt side = Stmt::make_if(use(mask), loc);
    side.then_body = std::move(body);
    out.push_back(std::move(side));
  }

  // The loop runs while some lane is looping: for every kind of source loop, a while loop
  // whose condition is the looping mask.
  void loop(const Stmt& s, Block& out, VarId mask) {
    LoopMasks m{mask_var("looping"), kNoVar};
    emit(out, m.looping, Op::Copy,
         {mask == kNoVar ? Operand::of_const(Constant::of_bool(true)) : use(mask)}, s.loc);
    const bool continues = jumps_out_of_loop(s.body, StmtKind::Continue);
    m.running = continues ? mask_var("running") : m.looping;
    loops_.push_back(m);

    Stmt l = Stmt::make_loop(LoopKind::While, s.loc);
    if (s.loop != LoopKind::DoUntil) {
      block(s.cond_body, l.cond_body, m.looping, m.looping);
      narrow(l.cond_body, m.looping, s.cond, s.loc);
    }
    l.cond = use(m.looping);
    if (continues) emit(l.body, m.running, Op::Copy, {use(m.looping)}, s.loc);
    block(s.body, l.body, m.running, m.running);
    block(s.step, l.body, m.looping, m.looping);
    if (s.loop == LoopKind::DoUntil) {
      block(s.cond_body, l.body, m.looping, m.looping);
      narrow(l.body, m.looping, negated(l.body, s.cond, s.loc), s.loc);
    }
    // Leave as soon as no lane loops, before the next condition block runs for none.
    if (!l.cond_body.empty()) {
      Stmt done = Stmt::make_if(use(m.looping), s.loc);
      done.else_body.push_back(Stmt::make(StmtKind::Break, s.loc));
      l.body.push_back(std::move(done));
    }
    loops_.pop_back();
    out.push_back(std::move(l));
  }

  // The lanes in `mask` leave: clear them from the masks the jump leaves.
  void jump(const Stmt& s, Block& out, VarId mask) {
    // Computed before any mask is cleared: `mask` may be one of them.
    const Operand staying = mask == kNoVar ? Operand::of_const(Constant::of_bool(false))
                                           : negated(out, use(mask), s.loc);
    if (s.kind == StmtKind::Discard) {
      if (alive_ == kNoVar) throw Error("internal: lower_lockstep: discard without an alive mask");
      narrow(out, alive_, staying, s.loc);
      for (const LoopMasks& l : loops_) {
        narrow(out, l.looping, staying, s.loc);
        if (l.running != l.looping) narrow(out, l.running, staying, s.loc);
      }
      return;
    }
    if (loops_.empty()) throw Error("internal: lower_lockstep: break or continue outside a loop");
    const LoopMasks& l = loops_.back();
    if (s.kind == StmtKind::Break) narrow(out, l.looping, staying, s.loc);
    if (l.running != l.looping) narrow(out, l.running, staying, s.loc);
  }

  Function& f_;
  std::vector<bool> unblended_;  // see unblended_vars()
  std::vector<LoopMasks> loops_;
  VarId alive_ = kNoVar;
};

}  // namespace

LockstepFunction lower_lockstep(const Function& optimized) {
  Function f = optimized;
  return LockstepLowering(f).run();
}

}  // namespace rill::passes
