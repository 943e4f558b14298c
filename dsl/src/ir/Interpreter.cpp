#include "rill/ir/Interpreter.h"

#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::ir {

namespace {

enum class Flow { Normal, Break, Continue, Discard };

// Runs one element at a time: a Visitor whose walk stops at a jump (flow_ says which) and
// whose ifs and loops follow the values they read.
class Machine : public Visitor {
 public:
  using Visitor::visit;
  Machine(const Function& f, const InterpreterLaunch& l) : f_(f), l_(l), vals_(f.vars.size()) {}

  bool element(int64_t i) {
    i_ = i;
    for (VarId v = 0; v < f_.vars.size(); ++v) {
      const Variable& var = f_.vars[v];
      Constant c;
      c.type = var.type;
      int w = var.type.width;
      for (int k = 0; k < w; ++k) {
        uint32_t bits = 0;
        if (var.role == VarRole::Input) bits = l_.inputs[static_cast<size_t>(var.slot)][i * w + k];
        else if (var.role == VarRole::Output) bits = l_.outputs[static_cast<size_t>(var.slot)][i * w + k];
        else if (var.role == VarRole::Uniform) bits = l_.uniforms[static_cast<size_t>(var.slot)][static_cast<size_t>(k)];
        c.bits[static_cast<size_t>(k)] = bits;
      }
      vals_[v] = c;
    }
    flow_ = Flow::Normal;
    visit(f_.body);
    if (flow_ == Flow::Discard) return false;
    for (size_t o = 0; o < f_.outputs.size(); ++o) {
      const Constant& c = vals_[f_.outputs[o]];
      int w = c.type.width;
      for (int k = 0; k < w; ++k) l_.outputs[o][i * w + k] = c.bits[static_cast<size_t>(k)];
    }
    return true;
  }

 private:
  Constant read(const Operand& o) const {
    if (o.is_const()) return o.value;
    Constant c;
    c.type = o.type;
    for (int k = 0; k < o.width(); ++k) c.bits[static_cast<size_t>(k)] = vals_[o.var].bits[o.swizzle[static_cast<size_t>(k)]];
    return c;
  }

  // Runs b until it ends or a jump leaves it (flow_ then says which).
  void visit(const Block& b) override {
    for (const Stmt& st : b) {
      Visitor::visit(st);
      if (flow_ != Flow::Normal) return;
    }
  }
  void visit_assign(const Stmt& s) override { assign(s); }
  void visit_if(const Stmt& s) override { visit(read(s.cond).b(0) ? s.then_body : s.else_body); }
  void visit_jump(const Stmt& s) override {
    flow_ = s.kind == StmtKind::Break      ? Flow::Break
            : s.kind == StmtKind::Continue ? Flow::Continue
                                           : Flow::Discard;
  }
  void visit_loop(const Stmt& s) override {
    for (;;) {
      if (s.loop != LoopKind::DoUntil) {
        visit(s.cond_body);
        if (flow_ != Flow::Normal || !read(s.cond).b(0)) return;
      }
      visit(s.body);
      if (flow_ == Flow::Discard) return;
      const Flow body_flow = flow_;
      flow_ = Flow::Normal;  // break and continue end here
      if (body_flow == Flow::Break) return;
      if (body_flow == Flow::Continue && s.loop == LoopKind::While) continue;
      // For and do-until: continue still runs the step / the condition.
      visit(s.step);
      if (flow_ != Flow::Normal) return;
      if (s.loop == LoopKind::DoUntil) {
        visit(s.cond_body);
        if (flow_ != Flow::Normal || read(s.cond).b(0)) return;
      }
    }
  }

  void assign(const Stmt& s) {
    Constant& dst = vals_[s.dst];
    const int width = s.mask.full() ? dst.type.width : s.mask.count;
    Constant r;
    r.type = dst.type.with_width(width);
    if (s.op == Op::Gather) {
      const InterpreterArray& a = l_.arrays.at(static_cast<size_t>(s.array));
      const ArrayDecl& decl = f_.arrays[static_cast<size_t>(s.array)];
      // Linearized with x fastest; each index mapped into its dimension by the array's mode.
      bool inside = true;
      int64_t idx = 0, stride = 1;
      for (size_t d = 0; d < s.args.size(); ++d) {
        const int32_t i = read(s.args[d]).i(0);
        inside = inside && index_inside(i, a.shape[d]);
        idx += stride * boundary_index(decl.boundary, i, a.shape[d]);
        stride *= a.shape[d];
      }
      const int ew = decl.elem.width;
      for (int k = 0; k < width; ++k)
        r.bits[static_cast<size_t>(k)] = decl.boundary == Boundary::Constant && !inside
                                             ? decl.border.bits[static_cast<size_t>(k)]
                                             : a.data[idx * ew + k];
    } else if (op_info(s.op).cls == OpClass::Group) {
      // The interpreter runs one element at a time: a group of one (docs/programming-model.md).
      const Constant x = s.args.empty() ? Constant{} : read(s.args[0]);
      const uint32_t on = x.bits[0] != 0 ? 1u : 0u;
      if (s.op == Op::GroupSize)
        r.bits[0] = 1;
      else if (s.op == Op::LaneIndex)
        r.bits[0] = 0;
      else if (x.type.is_bool() && s.op != Op::GroupBroadcast)
        r.bits[0] = on;  // any, all, ballot (bit 0), count
      else
        r.bits[0] = x.bits[0];  // min, max, sum, broadcast: the element's own value
    } else if (s.op == Op::ElementIndex) {
      r.bits[0] = static_cast<uint32_t>(static_cast<int32_t>(i_));
    } else if (s.op == Op::ElementCoord) {
      r.bits[0] = static_cast<uint32_t>(static_cast<int32_t>(i_ % l_.width));
      r.bits[1] = static_cast<uint32_t>(static_cast<int32_t>(i_ / l_.width));
    } else {
      // One vector for every statement's arguments: a fresh one per statement was most of
      // the interpreter's time under AddressSanitizer (each allocation records a stack).
      args_.clear();
      for (const Operand& a : s.args) args_.push_back(read(a));
      auto folded = passes::fold(s.op, r.type, args_);
      if (!folded)
        throw Error(std::string("interpreter: cannot evaluate '") + op_name(s.op) +
                    "' exactly (lower transcendental operations first)");
      r = *folded;
    }
    for (int k = 0; k < width; ++k) {
      int c = s.mask.full() ? k : s.mask.comps[static_cast<size_t>(k)];
      dst.bits[static_cast<size_t>(c)] = r.bits[static_cast<size_t>(k)];
    }
  }

  const Function& f_;
  const InterpreterLaunch& l_;
  std::vector<Constant> vals_;
  std::vector<Constant> args_;  // the arguments of the statement being evaluated
  int64_t i_ = 0;
  Flow flow_ = Flow::Normal;
};

}  // namespace

int64_t interpret(const Function& f, const InterpreterLaunch& launch) {
  Machine m(f, launch);
  int64_t written = 0;
  for (int64_t i = 0; i < launch.count; ++i) written += m.element(i) ? 1 : 0;
  return written;
}

}  // namespace rill::ir
