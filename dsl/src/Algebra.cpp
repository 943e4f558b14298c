// connect and combine (Algebra.h): both build one Function from two captured ones. a's IR is
// copied unchanged; b's variables are appended after a's (those b shares with a map onto a's),
// its body is copied with every variable and array reference remapped, and the interface
// lists are rebuilt from the two. The rules that keep the fused kernel equal to separate
// launches (no discards where they would differ, connected outputs written on every path)
// are checked here, before the verifier sees the result.
#include "rill/Algebra.h"

#include <algorithm>

#include "rill/Parameters.h"
#include "rill/Stopwatch.h"
#include "rill/ir/Verifier.h"
#include "rill/ir/Visitor.h"

namespace rill {

namespace {

using ir::VarId;

enum class Kind { Connect, Combine };

// Which components every path through `block` that reaches its end writes to v (bit c for
// component c). A path that leaves by a jump never reaches the end, so it counts as writing
// everything. Loops are taken conservatively: only what runs before any jump can leave them.
unsigned written_on_every_path(const ir::Block& block, VarId v, unsigned all) {
  unsigned w = 0;
  for (const ir::Stmt& s : block) {
    switch (s.kind) {
      case ir::StmtKind::Assign:
        if (s.dst != v) break;
        if (s.mask.full()) return all;
        for (int i = 0; i < s.mask.count; ++i) w |= 1u << s.mask.comps[static_cast<size_t>(i)];
        break;
      case ir::StmtKind::If:
        w |=
            written_on_every_path(s.then_body, v, all) & written_on_every_path(s.else_body, v, all);
        break;
      case ir::StmtKind::Loop: {
        // The condition block of a while or for loop runs at least once, before any exit.
        // A do-until loop runs its body and then its condition once, unless the body jumps.
        unsigned runs = written_on_every_path(s.cond_body, v, all);
        if (s.loop == ir::LoopKind::DoUntil) {
          bool jumps = ir::jumps_out_of_loop(s.body, ir::StmtKind::Break) ||
                       ir::jumps_out_of_loop(s.body, ir::StmtKind::Continue);
          runs = jumps ? 0 : runs | written_on_every_path(s.body, v, all);
        }
        w |= runs;
        break;
      }
      case ir::StmtKind::Break:
      case ir::StmtKind::Continue:
      case ir::StmtKind::Discard:
        return all;
    }
    if (w == all) return all;
  }
  return w;
}

bool assigns(const ir::Block& block, VarId v) {
  bool found = false;
  ir::for_each_stmt(block, [&](const ir::Stmt& s) {
    found = found || (s.kind == ir::StmtKind::Assign && s.dst == v);
  });
  return found;
}

// A variable of f with this role and name (inputs or outputs), or kNoVar.
VarId find_named(const ir::Function& f, const std::vector<VarId>& list, const std::string& name) {
  for (VarId v : list)
    if (f.var(v).name == name) return v;
  return ir::kNoVar;
}

std::string names_of(const ir::Function& f, const std::vector<VarId>& list) {
  if (list.empty()) return "none";
  std::string s;
  for (VarId v : list)
    s += (s.empty() ? "'" : ", '") + f.var(v).name + "' (" + f.var(v).type.str() + ")";
  return s;
}

class Fusion {
 public:
  Fusion(Kind kind, const Program& a, const Program& b, std::string name, SourceLoc loc)
      : kind_(kind), a_(a), b_(b), loc_(loc) {
    if (!a.valid() || !b.valid())
      throw Error(std::string(op()) + ": the " + (a.valid() ? "second" : "first") +
                      " program is empty (a default-constructed rill::Program)",
                  loc);
    const ir::Function& fa = a.ir();
    fn_ = std::make_shared<ir::Function>(fa);  // a's ids, bodies and arrays stay as they are
    fn_->name = name.empty() ? fa.name + (kind == Kind::Connect ? ">>" : "&") + b.ir().name
                             : std::move(name);
    fn_->inputs.clear();
    fn_->outputs.clear();
    out_.fn = fn_;
    out_.uniforms = a.captured().uniforms;
    out_.arrays = a.captured().arrays;
    bmap_.assign(b.ir().vars.size(), ir::kNoVar);
  }

  Program run() {
    // Print slots are hidden outputs numbered per program (Print.h): fusing would need them
    // renumbered and merged, which is not done yet, so it is refused rather than lost.
    for (const Program* p : {&a_, &b_})
      if (!p->captured().prints.empty())
        fail("'" + p->name() + "' uses rill::print, which " + op() +
             " cannot fuse yet; launch the programs separately while they print");
    reject_discards();
    match_inputs();
    const ir::Function& fa = a_.ir();
    const ir::Function& fb = b_.ir();
    if (kind_ == Kind::Connect && consumed_.empty())
      fail("nothing to connect: no input of '" + fb.name + "' is named like an output of '" +
           fa.name + "' (outputs of '" + fa.name + "': " + names_of(fa, fa.outputs) +
           "; inputs of '" + fb.name + "': " + names_of(fb, fb.inputs) + ")");
    for (VarId o : consumed_) require_written_everywhere(o);
    if (kind_ == Kind::Connect && consumed_.size() < fa.outputs.size() &&
        ir::contains(fb.body, ir::StmtKind::Discard))
      fail("'" + fb.name + "' contains RILL_DISCARD and '" + fa.name +
           "' has outputs it does not read (" + names_of(fa, unconsumed()) + "): where '" +
           fb.name + "' discards, the fused kernel would not write them, but the launch of '" +
           fa.name +
           "' does; connect only programs whose second half reads all of the "
           "first's outputs, or remove the discard");
    merge_uniforms();
    merge_arrays();
    for (VarId v = 0; v < fb.vars.size(); ++v)  // the rest of b's variables, in order
      if (bmap_[v] == ir::kNoVar)
        bmap_[v] = fn_->add_var(fb.vars[v].type, fb.vars[v].role, fb.vars[v].name);
    append_body();
    set_interface();
    ir::verify_or_throw(*fn_, std::string(op()) + " of '" + fa.name + "' and '" + fb.name + "'");
    out_.capture_ms = a_.capture_ms() + b_.capture_ms() + fusing_.ms();
    return Program(std::move(out_));
  }

 private:
  // Decides what each input of b becomes: a's output of that name (connect), a's input of
  // that name, a copy of it, or an input of its own.
  void match_inputs() {
    const ir::Function& fa = a_.ir();
    const ir::Function& fb = b_.ir();
    for (VarId in : fb.inputs) {
      const ir::Variable& bv = fb.var(in);
      VarId from = kind_ == Kind::Connect ? find_named(fa, fa.outputs, bv.name) : ir::kNoVar;
      if (from != ir::kNoVar) {
        check_types("output", from, "input", in);
        bmap_[in] = from;
        consumed_.push_back(from);
        continue;
      }
      VarId shared = find_named(fa, fa.inputs, bv.name);
      if (shared == ir::kNoVar) {
        b_inputs_.push_back(in);
        continue;
      }
      check_types("input", shared, "input", in);
      if (!assigns(fa.body, shared)) {
        bmap_[in] = shared;
        continue;
      }
      // a overwrites its copy of the input; b must see the element as the stream holds it.
      bmap_[in] = fn_->add_var(bv.type, ir::VarRole::Local, bv.name);
      prologue_.push_back(
          ir::Stmt::assign(bmap_[in], ir::Op::Copy, {ir::Operand::of_var(shared, bv.type)}, loc_));
    }
  }

  // The body: the copies of inputs a overwrites, a's body, b's body remapped.
  void append_body() {
    ir::Block body = b_.ir().body;
    remap(body);
    ir::Block& all = prologue_;
    all.insert(all.end(), std::make_move_iterator(fn_->body.begin()),
               std::make_move_iterator(fn_->body.end()));
    all.insert(all.end(), std::make_move_iterator(body.begin()),
               std::make_move_iterator(body.end()));
    fn_->body = std::move(all);
  }

  // Inputs: a's, then b's own. Outputs: connect b's, then a's kept; combine a's, then b's.
  // a's outputs that b reads become locals of the fused program.
  void set_interface() {
    const ir::Function& fa = a_.ir();
    const ir::Function& fb = b_.ir();
    for (VarId v : fa.inputs) fn_->inputs.push_back(v);
    for (VarId v : b_inputs_) fn_->inputs.push_back(bmap_[v]);
    for (VarId v : consumed_) {
      fn_->vars[v].role = ir::VarRole::Local;
      fn_->vars[v].slot = -1;
    }
    std::vector<VarId> outs;
    for (VarId v : fb.outputs) outs.push_back(bmap_[v]);
    std::vector<VarId> kept = unconsumed();
    outs.insert(kind_ == Kind::Connect ? outs.end() : outs.begin(), kept.begin(), kept.end());
    for (VarId v : outs) {
      VarId same = find_named(*fn_, fn_->outputs, fn_->vars[v].name);
      if (same != ir::kNoVar)
        fail("both programs have an output named '" + fn_->vars[v].name + "' (" +
             fn_->vars[same].type.str() + " and " + fn_->vars[v].type.str() +
             (kind_ == Kind::Connect ? "; connect keeps the outputs of '" + fa.name + "' that '" +
                                           fb.name + "' does not read"
                                     : "") +
             "): rename one of them");
      fn_->outputs.push_back(v);
    }
    for (size_t i = 0; i < fn_->inputs.size(); ++i)
      fn_->vars[fn_->inputs[i]].slot = static_cast<int>(i);
    for (size_t i = 0; i < fn_->outputs.size(); ++i)
      fn_->vars[fn_->outputs[i]].slot = static_cast<int>(i);
  }

  const char* op() const { return kind_ == Kind::Connect ? "connect" : "combine"; }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(std::string(op()) + "('" + a_.ir().name + "', '" + b_.ir().name + "'): " + what,
                loc_);
  }

  void check_types(const char* a_role, VarId av, const char* b_role, VarId bv) const {
    const ir::Variable& x = a_.ir().var(av);
    const ir::Variable& y = b_.ir().var(bv);
    if (x.type != y.type)
      fail("the name '" + x.name + "' is " + a_role + " " + x.type.str() + " of '" + a_.ir().name +
           "' but " + b_role + " " + y.type.str() + " of '" + b_.ir().name +
           "'; the types must match");
  }

  void reject_discards() const {
    const ir::Function& fa = a_.ir();
    const ir::Function& fb = b_.ir();
    if (ir::contains(fa.body, ir::StmtKind::Discard))
      fail("'" + fa.name + "' contains RILL_DISCARD: " +
           (kind_ == Kind::Connect
                ? "where it discards, launching the two programs one after the other still "
                  "runs '" +
                      fb.name +
                      "' on the stale intermediate element, but the fused "
                      "kernel would end the element and skip '" +
                      fb.name + "'"
                : "where it discards, the fused kernel would skip '" + fb.name +
                      "', which its own launch runs") +
           "; launch the programs separately");
    if (kind_ == Kind::Combine && ir::contains(fb.body, ir::StmtKind::Discard))
      fail("'" + fb.name +
           "' contains RILL_DISCARD: where it discards, the fused kernel "
           "would write none of the outputs of '" +
           fa.name +
           "', which its own launch "
           "writes; launch the programs separately");
  }

  // connect: where an output b reads is not written, two launches give b the intermediate
  // stream's old value, which the fused kernel does not have.
  void require_written_everywhere(VarId o) const {
    const ir::Function& fa = a_.ir();
    const ir::Type t = fa.var(o).type;
    unsigned all = (1u << t.width) - 1;
    unsigned w = written_on_every_path(fa.body, o, all);
    if (w == all) return;
    std::string missing = t.width == 1 ? "it" : "";
    if (t.width > 1) {
      missing = "component(s) ";
      for (int c = 0; c < t.width; ++c)
        if (!(w & (1u << c))) missing += "xyzw"[c];
    }
    fail("output '" + fa.var(o).name + "' (" + t.str() + ") of '" + fa.name + "' feeds '" +
         b_.ir().name + "' but some path through '" + fa.name + "' does not write " + missing +
         ": there, two launches would give '" + b_.ir().name +
         "' the intermediate stream's previous value, which the fused kernel does not "
         "have; write the output on every path (e.g. assign a default first)");
  }

  // a's outputs that b does not read (all of them for combine).
  std::vector<VarId> unconsumed() const {
    std::vector<VarId> out;
    for (VarId v : a_.ir().outputs)
      if (std::find(consumed_.begin(), consumed_.end(), v) == consumed_.end()) out.push_back(v);
    return out;
  }

  // b's uniforms: one that a also reads is a's variable; a new one is appended.
  void merge_uniforms() {
    const ir::Function& fb = b_.ir();
    const auto& states = b_.captured().uniforms;
    for (size_t i = 0; i < fb.uniforms.size(); ++i) {
      const auto& st = states[i];
      auto same = std::find(out_.uniforms.begin(), out_.uniforms.end(), st);
      if (same != out_.uniforms.end()) {
        bmap_[fb.uniforms[i]] = fn_->uniforms[static_cast<size_t>(same - out_.uniforms.begin())];
        continue;
      }
      for (const auto& other : out_.uniforms)
        if (other->name == st->name)
          fail("two different uniforms are named '" + st->name +
               "', one read by each program; a program's uniforms need distinct names "
               "(name them: Uniform<V>(value, \"name\"))");
      VarId v = fn_->add_var(fb.var(fb.uniforms[i]).type, ir::VarRole::Uniform, st->name);
      fn_->vars[v].slot = static_cast<int>(fn_->uniforms.size());
      fn_->uniforms.push_back(v);
      out_.uniforms.push_back(st);
      bmap_[fb.uniforms[i]] = v;
    }
  }

  // b's arrays: one that a also gathers from keeps a's index; a new one is appended.
  void merge_arrays() {
    const ir::Function& fb = b_.ir();
    const auto& states = b_.captured().arrays;
    for (size_t i = 0; i < fb.arrays.size(); ++i) {
      auto same = std::find(out_.arrays.begin(), out_.arrays.end(), states[i]);
      if (same != out_.arrays.end()) {
        array_map_.push_back(static_cast<int>(same - out_.arrays.begin()));
        continue;
      }
      array_map_.push_back(static_cast<int>(fn_->arrays.size()));
      fn_->arrays.push_back(fb.arrays[i]);
      out_.arrays.push_back(states[i]);
    }
  }

  void remap(ir::Block& body) const {
    ir::for_each_operand(body, [&](ir::Operand& o) {
      if (o.is_var()) o.var = bmap_[o.var];
    });
    ir::for_each_stmt(body, [&](ir::Stmt& s) {
      if (s.kind != ir::StmtKind::Assign) return;
      s.dst = bmap_[s.dst];
      if (s.array >= 0) s.array = array_map_[static_cast<size_t>(s.array)];
    });
  }

  Kind kind_;
  const Program& a_;
  const Program& b_;
  SourceLoc loc_;
  Stopwatch fusing_;  // the fused program's capture time adds this to both halves'
  std::shared_ptr<ir::Function> fn_;
  detail::CapturedProgram out_;
  std::vector<VarId> consumed_;  // a's outputs that b reads (connect)
  std::vector<VarId> b_inputs_;  // b's inputs that stay inputs
  ir::Block prologue_;           // copies of inputs a overwrites, for b
  std::vector<VarId> bmap_;      // b's variable -> the fused program's
  std::vector<int> array_map_;   // b's array index -> the fused program's
};

}  // namespace

Program connect(const Program& a, const Program& b, std::string name, SourceLoc loc) {
  return Fusion(Kind::Connect, a, b, std::move(name), loc).run();
}

Program combine(const Program& a, const Program& b, std::string name, SourceLoc loc) {
  return Fusion(Kind::Combine, a, b, std::move(name), loc).run();
}

}  // namespace rill
