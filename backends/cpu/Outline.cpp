// Choosing the blocks the C emitter outlines, and their interfaces (Outline.h).
#include "Outline.h"

#include <algorithm>

#include "rill/ir/Visitor.h"

namespace rill::cpu {

using namespace ir;

namespace {

// Scalars are numbered var * 4 + component.
size_t scalar_key(VarId v, int c) {
  return static_cast<size_t>(v) * 4 + static_cast<size_t>(c);
}

template <class F>
void for_each_read(const Operand& o, F&& f) {
  if (!o.is_var()) return;
  for (int c = 0; c < o.width(); ++c) f(scalar_key(o.var, o.component(c)));
}

template <class F>
void for_each_write(const Function& fn, const Stmt& s, F&& f) {
  if (s.mask.full()) {
    for (int c = 0; c < fn.var(s.dst).type.width; ++c) f(scalar_key(s.dst, c));
  } else {
    for (int c = 0; c < s.mask.count; ++c)
      f(scalar_key(s.dst, s.mask.comps[static_cast<size_t>(c)]));
  }
}

// The blocks already outlined: analyses of an enclosing block see a call in their place,
// which reads the part's parameters and writes those passed by pointer.
struct Parts {
  const std::map<const Block*, size_t>& index;
  const std::vector<OutlinedPart>& parts;
  const OutlinedPart* called(const Block& b) const {
    auto it = index.find(&b);
    return it == index.end() ? nullptr : &parts[it->second];
  }
};

// How often each scalar is read or written in b, nested blocks included; with `parts`, an
// outlined nested block counts as its call.
void count_uses(const Function& fn, const Block& b, std::vector<uint32_t>& uses,
                const Parts* parts) {
  for (const Stmt& s : b) {
    for (const Operand& a : s.args) for_each_read(a, [&](size_t k) { ++uses[k]; });
    if (s.kind == StmtKind::Assign) for_each_write(fn, s, [&](size_t k) { ++uses[k]; });
    if (s.kind == StmtKind::If || s.kind == StmtKind::Loop)
      for_each_read(s.cond, [&](size_t k) { ++uses[k]; });
    for (const Block* inner : {&s.then_body, &s.else_body, &s.cond_body, &s.body, &s.step}) {
      if (const OutlinedPart* call = parts ? parts->called(*inner) : nullptr) {
        for (const ScalarRef& r : call->by_value) ++uses[scalar_key(r.var, r.comp)];
        for (const ScalarRef& r : call->by_pointer) ++uses[scalar_key(r.var, r.comp)];
      } else {
        count_uses(fn, *inner, uses, parts);
      }
    }
  }
}

// Marks in `written` the scalars b may write (an outlined nested block: those it takes by
// pointer).
void mark_written(const Function& fn, const Block& b, std::vector<char>& written,
                  const Parts& parts) {
  for (const Stmt& s : b) {
    if (s.kind == StmtKind::Assign) for_each_write(fn, s, [&](size_t k) { written[k] = 1; });
    for (const Block* inner : {&s.then_body, &s.else_body, &s.cond_body, &s.body, &s.step}) {
      if (const OutlinedPart* call = parts.called(*inner)) {
        for (const ScalarRef& r : call->by_pointer) written[scalar_key(r.var, r.comp)] = 1;
      } else {
        mark_written(fn, *inner, written, parts);
      }
    }
  }
}

// Marks in `exposed` the scalars b may read before writing them (their value at b's entry
// can matter); `defined` holds those certainly written so far on every path.
void upward_exposed(const Function& fn, const Block& b, std::vector<char>& defined,
                    std::vector<char>& exposed, const Parts& parts) {
  if (const OutlinedPart* call = parts.called(b)) {
    // The call reads every parameter (those by pointer are copied in) and writes back
    // those by pointer on every way out.
    for (const auto* list : {&call->by_value, &call->by_pointer})
      for (const ScalarRef& r : *list)
        if (!defined[scalar_key(r.var, r.comp)]) exposed[scalar_key(r.var, r.comp)] = 1;
    for (const ScalarRef& r : call->by_pointer) defined[scalar_key(r.var, r.comp)] = 1;
    return;
  }
  auto read = [&](const Operand& o) {
    for_each_read(o, [&](size_t k) {
      if (!defined[k]) exposed[k] = 1;
    });
  };
  for (const Stmt& s : b) {
    switch (s.kind) {
      case StmtKind::Assign:
        for (const Operand& a : s.args) read(a);
        for_each_write(fn, s, [&](size_t k) { defined[k] = 1; });
        break;
      case StmtKind::If: {
        read(s.cond);
        std::vector<char> other = defined;
        upward_exposed(fn, s.then_body, defined, exposed, parts);
        upward_exposed(fn, s.else_body, other, exposed, parts);
        for (size_t k = 0; k < defined.size(); ++k) defined[k] = defined[k] && other[k];
        break;
      }
      case StmtKind::Loop: {
        // What the loop writes is not counted as written after it (it may run no
        // iteration, or leave early): conservative.
        std::vector<char> inside = defined;
        upward_exposed(fn, s.cond_body, inside, exposed, parts);
        read(s.cond);
        upward_exposed(fn, s.body, inside, exposed, parts);
        upward_exposed(fn, s.step, inside, exposed, parts);
        break;
      }
      default:
        return;  // a jump: nothing after it in this block runs
    }
  }
}

// The jumps that leave b (loop_depth: loops of b around the statement), the arrays and the
// element position it reads.
void scan_part(const Block& b, int loop_depth, OutlinedPart& part) {
  for (const Stmt& s : b) {
    switch (s.kind) {
      case StmtKind::Assign:
        if (s.op == Op::Gather) part.arrays.push_back(s.array);
        if (s.op == Op::ElementIndex) part.element_index = true;
        if (s.op == Op::ElementCoord) part.element_coord = true;
        break;
      case StmtKind::Break:
        if (loop_depth == 0) part.exits[kBreak] = true;
        break;
      case StmtKind::Continue:
        if (loop_depth == 0) part.exits[kContinue] = true;
        break;
      case StmtKind::Discard:
        part.exits[kDiscard] = true;
        break;
      default:
        break;
    }
    scan_part(s.then_body, loop_depth, part);
    scan_part(s.else_body, loop_depth, part);
    scan_part(s.cond_body, loop_depth + 1, part);
    scan_part(s.body, loop_depth + 1, part);
    scan_part(s.step, loop_depth + 1, part);
  }
}

// Whether b runs a loop itself (an outlined nested block is a call: its loops are its own).
bool runs_loop(const Block& b, const Parts& parts) {
  for (const Stmt& s : b) {
    if (s.kind == StmtKind::Loop) return true;
    for (const Block* inner : {&s.then_body, &s.else_body})
      if (!parts.called(*inner) && runs_loop(*inner, parts)) return true;
  }
  return false;
}

class Planner {
 public:
  Planner(const Function& f, size_t min_cost) : f_(f), min_cost_(min_cost) {
    total_.assign(f.vars.size() * 4, 0);
    count_uses(f, f.body, total_, nullptr);
  }

  // The cost of b once its large nested blocks are outlined; outlines b too when it may be
  // (an if side or a loop body) and is large.
  size_t block(const Block& b, bool may_outline, bool in_loop, bool loop_body = false) {
    size_t cost = 0;
    for (const Stmt& s : b) {
      switch (s.kind) {
        case StmtKind::Assign:
          cost += static_cast<size_t>(s.mask.full() ? f_.var(s.dst).type.width : s.mask.count) +
                  (s.op == Op::Gather ? 4 : 0);
          break;
        case StmtKind::If:
          cost += 1 + block(s.then_body, true, in_loop) + block(s.else_body, true, in_loop);
          break;
        case StmtKind::Loop:
          cost += 1 + block(s.cond_body, false, true) + block(s.body, true, true, true) +
                  block(s.step, false, true);
          break;
        default:
          cost += 1;
          break;
      }
    }
    if (!may_outline || b.empty() || cost < min_cost_) return cost;
    outline(b, in_loop, loop_body, cost);
    return 2;  // the call
  }

  OutlinePlan plan;

 private:
  void outline(const Block& b, bool in_loop, bool loop_body, size_t cost) {
    OutlinedPart part;
    part.block = &b;
    part.id = static_cast<int>(plan.parts.size());
    part.cost = cost;
    // All uses of a scalar (nested parts included) inside b: b may own it. Its uses with
    // nested parts seen as calls: whether b's function mentions it at all.
    const Parts parts{plan.index, plan.parts};
    std::vector<uint32_t> inside(total_.size(), 0), uses(total_.size(), 0);
    count_uses(f_, b, inside, nullptr);
    count_uses(f_, b, uses, &parts);
    std::vector<char> written(total_.size(), 0);
    mark_written(f_, b, written, parts);
    std::vector<char> defined(total_.size(), 0), exposed(total_.size(), 0);
    upward_exposed(f_, b, defined, exposed, parts);
    for (size_t k = 0; k < uses.size(); ++k) {
      if (!uses[k]) continue;
      const ScalarRef r{static_cast<VarId>(k / 4), static_cast<int>(k % 4)};
      const VarRole role = f_.var(r.var).role;
      const bool interface =
          role == VarRole::Input || role == VarRole::Output || role == VarRole::Uniform;
      // A scalar no statement outside b touches is b's own, starting at zero as every
      // variable of the kernel does, unless b may read a value an earlier call left
      // (b in a loop, the scalar read before written).
      if (inside[k] == total_[k] && !interface && !(in_loop && exposed[k]))
        part.locals.push_back(r);
      else if (written[k])
        part.by_pointer.push_back(r);
      else
        part.by_value.push_back(r);
    }
    scan_part(b, 0, part);
    part.loops = loop_body || runs_loop(b, parts);
    std::sort(part.arrays.begin(), part.arrays.end());
    part.arrays.erase(std::unique(part.arrays.begin(), part.arrays.end()), part.arrays.end());
    plan.index[&b] = plan.parts.size();
    plan.parts.push_back(std::move(part));
  }

  const Function& f_;
  size_t min_cost_;
  std::vector<uint32_t> total_;  // uses of each scalar in the whole kernel
};

}  // namespace

OutlinePlan plan_outlining(const Function& f, size_t min_cost) {
  Planner p(f, min_cost);
  p.plan.root_cost = p.block(f.body, false, false);
  if (!p.plan.parts.empty()) {
    const Parts parts{p.plan.index, p.plan.parts};
    std::vector<uint32_t> uses(f.vars.size() * 4, 0);
    count_uses(f, f.body, uses, &parts);
    p.plan.root_scalars.resize(uses.size());
    for (size_t k = 0; k < uses.size(); ++k) p.plan.root_scalars[k] = uses[k] != 0;
  }
  return std::move(p.plan);
}

}  // namespace rill::cpu
