// Walking and rewriting the IR.
//
// Visitor walks a block read-only, in program order, calling one hook per statement kind;
// Mutator rebuilds a block, letting each hook replace a statement by zero or more
// statements. Passes derive from them and override only what they care about.
#pragma once

#include "rill/ir/IR.h"

namespace rill::ir {

class Visitor {
 public:
  virtual ~Visitor() = default;
  virtual void visit(const Block& b) {
    for (const Stmt& s : b) visit(s);
  }
  virtual void visit(const Stmt& s) {
    switch (s.kind) {
      case StmtKind::Assign: visit_assign(s); break;
      case StmtKind::If: visit_if(s); break;
      case StmtKind::Loop: visit_loop(s); break;
      default: visit_jump(s); break;
    }
  }
  virtual void visit_assign(const Stmt&) {}
  virtual void visit_if(const Stmt& s) {
    visit(s.then_body);
    visit(s.else_body);
  }
  virtual void visit_loop(const Stmt& s) {
    visit(s.cond_body);
    visit(s.body);
    visit(s.step);
  }
  virtual void visit_jump(const Stmt&) {}  // Break, Continue, Discard
};

class Mutator {
 public:
  virtual ~Mutator() = default;
  // Rewrites b in place.
  virtual void mutate(Block& b) {
    Block out;
    out.reserve(b.size());
    for (Stmt& s : b) mutate(std::move(s), out);
    b = std::move(out);
  }
  // Appends the replacement of s to out (default: s with its blocks mutated).
  virtual void mutate(Stmt&& s, Block& out) {
    switch (s.kind) {
      case StmtKind::If:
        mutate(s.then_body);
        mutate(s.else_body);
        break;
      case StmtKind::Loop:
        mutate(s.cond_body);
        mutate(s.body);
        mutate(s.step);
        break;
      default:
        break;
    }
    out.push_back(std::move(s));
  }
};

// Calls f(const Operand&) / f(Operand&) for every operand a block reads, nested ones included.
template <class B, class F>
void for_each_operand(B& block, F&& f) {
  for (auto& s : block) {
    for (auto& a : s.args) f(a);
    if (s.kind == StmtKind::If) f(s.cond);
    if (s.kind == StmtKind::Loop) f(s.cond);
    for_each_operand(s.then_body, f);
    for_each_operand(s.else_body, f);
    for_each_operand(s.cond_body, f);
    for_each_operand(s.body, f);
    for_each_operand(s.step, f);
  }
}

// Calls f(stmt) for every statement, pre-order.
template <class B, class F>
void for_each_stmt(B& block, F&& f) {
  for (auto& s : block) {
    f(s);
    for_each_stmt(s.then_body, f);
    for_each_stmt(s.else_body, f);
    for_each_stmt(s.cond_body, f);
    for_each_stmt(s.body, f);
    for_each_stmt(s.step, f);
  }
}

}  // namespace rill::ir
