// canonicalize: a kernel's statements and variables in an order that does not depend on the
// C++ compiler that built Rill.
//
// Capture records an operation when C++ evaluates it. C++ leaves the order of a call's
// arguments, and of the operands of `a * b + c * d`, to the compiler: GCC and clang record
// the two products in opposite orders, so the same kernel came out as different source
// (and missed the other build's kernel caches: PoCL's, the drivers', Rill's own). Values do
// not depend on that order, only the listing does, so this pass puts the listing in an order
// of its own:
//
//   - An operation's result (a temporary, or a local such as a by-value copy, written once
//     and read only in its block or blocks nested there) is computed just before the first
//     statement that needs it, its operands first, left to right (a depth-first walk from
//     the statements that stay).
//   - Everything else stays in the order it was recorded: variables written more than once,
//     outputs, ifs, loops, jumps. A temporary that reads a variable is computed before the
//     next write to that variable, as it was.
//   - A temporary that nothing reads stays where it was among the statements that stay:
//     the captured program keeps its dead code (dead_code removes it), and only there does
//     the listing still follow C++'s order. optimize() canonicalizes again at its end, so
//     the kernel source does not.
//   - Variables are numbered in the order the listing first mentions them (interface
//     first), so printed names (t12) follow the listing too.
//
// A temporary is only ever computed later than where it was recorded, never earlier: it
// does not move ahead of a jump or a write. Results are the same bits; the tests in
// tests/dsl/passes/CanonicalizeTest.cpp check both the order and the values.
#include <algorithm>
#include <functional>
#include <map>

#include "rill/ir/Visitor.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

using namespace ir;

namespace {

// Calls f(block, index) for every statement, pre-order.
template <class F>
void for_each_block_stmt(const Block& b, F&& f) {
  for (size_t i = 0; i < b.size(); ++i) {
    f(b, i);
    for (const Block* nested :
         {&b[i].then_body, &b[i].else_body, &b[i].cond_body, &b[i].body, &b[i].step})
      for_each_block_stmt(*nested, f);
  }
}

// Which variables may move: temporaries and locals (a copy of a DSL value passed by value is
// a local, made in argument order too) written once, by a whole-variable assignment, and
// read only after that in the same block or in blocks nested there. Not a lane-group op's
// result: moved past a branch that breaks or discards, it would see other lanes.
std::vector<bool> movable_values(const Function& f) {
  const std::vector<int> defs = count_definitions(f);
  std::vector<bool> movable(f.vars.size(), false);
  std::vector<const Block*> def_block(f.vars.size(), nullptr);
  std::vector<size_t> def_index(f.vars.size(), 0);
  struct Frame {
    const Block* block;
    size_t index;
  };
  // First the candidates and where they are written, then every read checked against that.
  for_each_block_stmt(f.body, [&](const Block& b, size_t i) {
    const Stmt& s = b[i];
    const VarRole role = s.kind == StmtKind::Assign ? f.var(s.dst).role : VarRole::Input;
    if (s.kind == StmtKind::Assign && s.mask.full() && defs[s.dst] == 1 &&
        (role == VarRole::Temp || role == VarRole::Local) && !reads_group(s.op)) {
      movable[s.dst] = true;
      def_block[s.dst] = &b;
      def_index[s.dst] = i;
    }
  });
  std::vector<Frame> stack;
  auto use = [&](const Operand& o) {
    if (!o.is_var() || !movable[o.var]) return;
    for (const Frame& fr : stack)
      if (fr.block == def_block[o.var] && fr.index > def_index[o.var]) return;
    movable[o.var] = false;  // read outside its block (or not after its assignment)
  };
  std::function<void(const Block&)> walk = [&](const Block& b) {
    stack.push_back({&b, 0});
    for (size_t i = 0; i < b.size(); ++i) {
      stack.back().index = i;
      const Stmt& s = b[i];
      for (const Operand& a : s.args) use(a);
      if (s.kind == StmtKind::If || s.kind == StmtKind::Loop) use(s.cond);
      walk(s.then_body);
      walk(s.else_body);
      walk(s.cond_body);
      walk(s.body);
      walk(s.step);
    }
    stack.pop_back();
  };
  walk(f.body);
  return movable;
}

// Every operand a statement reads, its nested blocks included, in listing order.
template <class F>
void for_each_read(const Stmt& s, F&& f) {
  for (const Operand& a : s.args) f(a);
  if (s.kind == StmtKind::If) {
    f(s.cond);
    for_each_operand(s.then_body, f);
    for_each_operand(s.else_body, f);
  } else if (s.kind == StmtKind::Loop) {
    for_each_operand(s.cond_body, f);
    f(s.cond);
    for_each_operand(s.body, f);
    for_each_operand(s.step, f);
  }
}

class Scheduler {
 public:
  explicit Scheduler(const Function& f) : movable_(movable_values(f)), at_(f.vars.size(), kNone) {}

  void schedule(Block& b) {
    for (Stmt& s : b) {
      schedule(s.then_body);
      schedule(s.else_body);
      schedule(s.cond_body);
      schedule(s.body);
      schedule(s.step);
    }
    std::vector<size_t> roots, temps;
    std::vector<VarId> temp_vars;
    for (size_t i = 0; i < b.size(); ++i) {
      if (b[i].kind == StmtKind::Assign && movable_[b[i].dst]) {
        at_[b[i].dst] = i;
        temps.push_back(i);
        temp_vars.push_back(b[i].dst);
      } else {
        roots.push_back(i);
      }
    }
    if (!temps.empty()) reorder(b, roots, temps);
    for (VarId v : temp_vars) at_[v] = kNone;
  }

 private:
  static constexpr size_t kNone = ~size_t{0};

  // Calls done(k) for start and the unvisited movable values it reads, operands first, left
  // to right. A loop with its own stack: a chain of values (a sum built term by term) can be
  // as long as the kernel.
  template <class F>
  void post_order(const Block& b, size_t start, std::vector<bool>& visited, F&& done) const {
    if (visited[start]) return;
    visited[start] = true;
    struct Frame {
      size_t at, next_arg;
    };
    std::vector<Frame> stack{{start, 0}};
    while (!stack.empty()) {
      Frame& fr = stack.back();
      const std::vector<Operand>& args = b[fr.at].args;
      if (fr.next_arg < args.size()) {
        const Operand& a = args[fr.next_arg++];
        if (a.is_var() && at_[a.var] != kNone && !visited[at_[a.var]]) {
          visited[at_[a.var]] = true;
          stack.push_back({at_[a.var], 0});
        }
        continue;
      }
      const size_t k = fr.at;
      stack.pop_back();
      done(k);
    }
  }

  void reorder(Block& b, const std::vector<size_t>& roots, const std::vector<size_t>& temps) {
    // The order a purely lazy schedule would compute the temporaries in (operands first,
    // depth first from each remaining statement in turn): the canonical order, also for
    // those that must be computed earlier to stay ahead of a write.
    std::vector<size_t> rank(b.size(), kNone);
    size_t next_rank = 0;
    std::vector<bool> ranked(b.size(), false);
    auto rank_temp = [&](VarId v) {
      if (at_[v] == kNone) return;
      post_order(b, at_[v], ranked, [&](size_t i) { rank[i] = next_rank++; });
    };
    for (size_t r : roots)
      for_each_read(b[r], [&](const Operand& o) {
        if (o.is_var()) rank_temp(o.var);
      });

    // Which temporaries read each variable that a statement of this block may write.
    std::map<VarId, std::vector<size_t>> readers;
    for (size_t i : temps)
      for (const Operand& a : b[i].args)
        if (a.is_var() && at_[a.var] == kNone) readers[a.var].push_back(i);

    Block out;
    out.reserve(b.size());
    std::vector<bool> placed(b.size(), false);
    auto place = [&](size_t i) {
      post_order(b, i, placed, [&](size_t k) { out.push_back(std::move(b[k])); });
    };
    size_t dead_from = 0;  // unread temporaries stay where they were
    for (size_t r : roots) {
      for (; dead_from < r; ++dead_from)
        if (!placed[dead_from] && rank[dead_from] == kNone) place(dead_from);
      // Reads of what r writes, recorded before r, must be computed before r.
      std::vector<size_t> early;
      auto writes = [&](VarId v) {
        auto it = readers.find(v);
        if (it == readers.end()) return;
        for (size_t i : it->second)
          if (i < r && !placed[i] && rank[i] != kNone) early.push_back(i);
      };
      if (b[r].kind == StmtKind::Assign) writes(b[r].dst);
      for_each_stmt(b[r].then_body, [&](const Stmt& s) {
        if (s.kind == StmtKind::Assign) writes(s.dst);
      });
      for_each_stmt(b[r].else_body, [&](const Stmt& s) {
        if (s.kind == StmtKind::Assign) writes(s.dst);
      });
      for (const Block* nested : {&b[r].cond_body, &b[r].body, &b[r].step})
        for_each_stmt(*nested, [&](const Stmt& s) {
          if (s.kind == StmtKind::Assign) writes(s.dst);
        });
      std::sort(early.begin(), early.end(), [&](size_t x, size_t y) { return rank[x] < rank[y]; });
      for (size_t i : early) place(i);
      for_each_read(b[r], [&](const Operand& o) {
        if (o.is_var() && at_[o.var] != kNone) place(at_[o.var]);
      });
      placed[r] = true;
      out.push_back(std::move(b[r]));
    }
    for (size_t i = 0; i < b.size(); ++i)
      if (!placed[i]) place(i);  // unread temporaries after the last statement that stays
    b = std::move(out);
  }

  std::vector<bool> movable_;
  std::vector<size_t> at_;  // where a movable temporary of the block being ordered is written
};

void renumber_variables(Function& f) {
  std::vector<VarId> to(f.vars.size(), kNoVar);
  VarId next = 0;
  auto take = [&](VarId v) {
    if (v != kNoVar && to[v] == kNoVar) to[v] = next++;
  };
  for (VarId v : f.inputs) take(v);
  for (VarId v : f.outputs) take(v);
  for (VarId v : f.uniforms) take(v);
  // In the order a listing prints them: a loop's condition after the block computing it.
  std::function<void(const Block&)> walk = [&](const Block& b) {
    for (const Stmt& s : b) {
      for (const Operand& a : s.args)
        if (a.is_var()) take(a.var);
      if (s.kind == StmtKind::Assign) take(s.dst);
      if (s.kind == StmtKind::If && s.cond.is_var()) take(s.cond.var);
      walk(s.then_body);
      walk(s.else_body);
      walk(s.cond_body);
      if (s.kind == StmtKind::Loop && s.cond.is_var()) take(s.cond.var);
      walk(s.body);
      walk(s.step);
    }
  };
  walk(f.body);
  for (VarId v = 0; v < f.vars.size(); ++v) take(v);  // declared, never mentioned

  std::vector<Variable> vars(f.vars.size());
  for (VarId v = 0; v < f.vars.size(); ++v) vars[to[v]] = std::move(f.vars[v]);
  f.vars = std::move(vars);
  for (auto* list : {&f.inputs, &f.outputs, &f.uniforms})
    for (VarId& v : *list) v = to[v];
  for_each_stmt(f.body, [&](Stmt& s) {
    if (s.kind == StmtKind::Assign) s.dst = to[s.dst];
  });
  for_each_operand(f.body, [&](Operand& o) {
    if (o.is_var()) o.var = to[o.var];
  });
}

// Uniforms and arrays in the order the listing first reads them.
InterfaceOrder order_interface_by_first_use(Function& f) {
  InterfaceOrder order;
  std::vector<bool> uniform_seen(f.vars.size(), false), array_seen(f.arrays.size(), false);
  auto use = [&](const Operand& o) {
    if (o.is_var() && f.var(o.var).role == VarRole::Uniform && !uniform_seen[o.var]) {
      uniform_seen[o.var] = true;
      order.uniforms.push_back(static_cast<size_t>(f.var(o.var).slot));
    }
  };
  for_each_stmt(f.body, [&](const Stmt& s) {
    for (const Operand& a : s.args) use(a);
    if (s.kind == StmtKind::If || s.kind == StmtKind::Loop) use(s.cond);
    if (s.kind == StmtKind::Assign && s.op == Op::Gather && !array_seen[s.array]) {
      array_seen[s.array] = true;
      order.arrays.push_back(static_cast<size_t>(s.array));
    }
  });
  // Declared but never read (possible only for IR built by hand): last, as they were.
  for (size_t i = 0; i < f.uniforms.size(); ++i)
    if (!uniform_seen[f.uniforms[i]]) order.uniforms.push_back(i);
  for (size_t i = 0; i < f.arrays.size(); ++i)
    if (!array_seen[i]) order.arrays.push_back(i);

  std::vector<VarId> uniforms;
  for (size_t i = 0; i < order.uniforms.size(); ++i) {
    uniforms.push_back(f.uniforms[order.uniforms[i]]);
    f.vars[uniforms.back()].slot = static_cast<int>(i);
  }
  f.uniforms = std::move(uniforms);
  std::vector<ArrayDecl> arrays;
  std::vector<int> array_to(f.arrays.size());
  for (size_t i = 0; i < order.arrays.size(); ++i) {
    arrays.push_back(std::move(f.arrays[order.arrays[i]]));
    array_to[order.arrays[i]] = static_cast<int>(i);
  }
  f.arrays = std::move(arrays);
  for_each_stmt(f.body, [&](Stmt& s) {
    if (s.kind == StmtKind::Assign && s.op == Op::Gather) s.array = array_to[s.array];
  });
  return order;
}

}  // namespace

void canonicalize(Function& f, InterfaceOrder* interface) {
  Scheduler(f).schedule(f.body);
  if (interface) *interface = order_interface_by_first_use(f);
  renumber_variables(f);
}

}  // namespace rill::passes
