// Lane-group operations (rill/Group.h) through the passes: they are never folded or merged
// (the same operands give other results under other control flow), lockstep lowering hands
// each one the mask of the lanes running it, and the reference interpreter runs a group of
// one. The backend suite (tests/backends/GroupTest.cpp) checks what they compute.
#include "TestUtil.h"
#include "rill/Reference.h"

namespace rill {
namespace {

using ir::Op;
using test::count_ops;

// group_count(true) at the top and again inside a branch: the two count other lanes.
Program counts_program() {
  return program("group_counts", [] {
    Input<Int> v("v");
    Output<Int> top("top"), inner("inner");
    top = group_count(Bool(true));
    Int r = -1;
    RILL_IF(v > 0) {
      r = group_count(Bool(true));
    }
    RILL_ENDIF;
    inner = r;
  });
}

TEST(GroupOps, NeverFoldedOrMergedAcrossControlFlow) {
  ir::Function o = passes::optimize(counts_program().ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::GroupCount), 2) << ir::print(o);
  Program q = program("group_constants", [] {
    Output<Int> y("y");
    y = group_sum(Int(1)) + select(group_any(Bool(true)), Int(1), Int(0));
  });
  ir::Function oq = passes::optimize(q.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(oq, Op::GroupSum), 1) << ir::print(oq);
  EXPECT_EQ(count_ops(oq, Op::GroupAny), 1) << ir::print(oq);
}

// Canonicalize computes a temporary just before its first use; a group op's must stay ahead
// of a branch that discards, which would leave fewer lanes active.
TEST(GroupOps, StayAheadOfJumps) {
  Program p = program("group_before_discard", [] {
    Input<Int> v("v");
    Output<Int> y("y");
    Int n = group_count(v > 0);
    RILL_IF(v < -5) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    y = n;
  });
  for (const ir::Function& f :
       {p.ir(), passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict)}) {
    size_t count_at = f.body.size(), if_at = f.body.size();
    for (size_t i = 0; i < f.body.size(); ++i) {
      if (f.body[i].kind == ir::StmtKind::If) if_at = std::min(if_at, i);
      if (f.body[i].kind == ir::StmtKind::Assign && f.body[i].op == Op::GroupCount) count_at = i;
    }
    EXPECT_LT(count_at, if_at) << ir::print(f);
  }
}

TEST(GroupOps, LockstepLoweringAppendsTheRunningLanesMask) {
  ir::Function o = passes::optimize(counts_program().ir(), PassOptions{}, Accuracy::Strict);
  passes::LockstepFunction l = passes::lower_lockstep(o);
  ir::verify_or_throw(l.f, "lower_lockstep");
  int masked_by_var = 0, masked_by_true = 0;
  ir::for_each_stmt(l.f.body, [&](const ir::Stmt& s) {
    if (s.kind != ir::StmtKind::Assign || s.op != Op::GroupCount) return;
    ASSERT_EQ(s.args.size(), 2u);
    ASSERT_EQ(s.args[1].type, ir::bool_type(1));
    if (s.args[1].is_var())
      ++masked_by_var;  // the branch's lanes
    else if (s.args[1].value.b(0))
      ++masked_by_true;  // every lane, at the top
  });
  EXPECT_EQ(masked_by_var, 1) << ir::print(l.f);
  EXPECT_EQ(masked_by_true, 1) << ir::print(l.f);
}

TEST(GroupOps, TheInterpreterRunsAGroupOfOne) {
  Program p = program("group_of_one", [] {
    Input<Int> v("v");
    Output<Int4> a("a"), b("b");
    a = Int4(group_size(), lane_index(), group_count(v > 0), group_sum(v) + group_min(v));
    b = group_ballot(v > 0) + Int4(group_max(v), group_broadcast(v, Int(3)),
                                   select(group_all(v > 0), Int(10), Int(0)),
                                   select(group_any(v > 0), Int(20), Int(0)));
  });
  const std::vector<uint32_t> in = {5, static_cast<uint32_t>(-7), 0};
  std::vector<uint32_t> out_a(12, 0), out_b(12, 0);
  ir::InterpreterLaunch l = reference_launch(p);
  l.inputs = {in.data()};
  l.outputs = {out_a.data(), out_b.data()};
  l.count = 3;
  l.width = 3;
  ASSERT_EQ(ir::interpret(p.ir(), l), 3);
  for (size_t e = 0; e < 3; ++e) {
    const auto v = static_cast<int32_t>(in[e]);
    const int32_t on = v > 0 ? 1 : 0;
    const std::vector<int32_t> want_a = {1, 0, on, v + v};
    const std::vector<int32_t> want_b = {on + v, v, on * 10, on * 20};
    for (size_t c = 0; c < 4; ++c) {
      EXPECT_EQ(static_cast<int32_t>(out_a[e * 4 + c]), want_a[c]) << "a." << c << " of " << v;
      EXPECT_EQ(static_cast<int32_t>(out_b[e * 4 + c]), want_b[c]) << "b." << c << " of " << v;
    }
  }
}

}  // namespace
}  // namespace rill
