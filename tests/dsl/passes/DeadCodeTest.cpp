// passes::eliminate_dead_code: unread assignments, empty ifs, code after a jump.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Op;
using ir::StmtKind;
using test::count_kind;
using test::count_ops;

ir::Function swept(const Program& p, bool expect_change = true) {
  return test::after(
      p, [&](ir::Function& f) { EXPECT_EQ(passes::eliminate_dead_code(f), expect_change); });
}

TEST(DeadCode, UnreadAssignmentsAndTheirOperandsGo) {
  Program p = program("unread", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float a = x * 3.0f;
    Float b = a + 1.0f;
    Float c = sqrt(b * b);  // nothing reads c: the whole chain is dead
    y = x;
  });
  ASSERT_GE(test::statements(p.ir()), 5) << p.print();
  ir::Function f = swept(p);
  EXPECT_EQ(test::statements(f), 1) << ir::print(f);
  EXPECT_LINE(ir::print(f), "y_1 = copy(x_0)");
}

TEST(DeadCode, OutputsAreAlwaysKept) {
  Program p = program("outputs", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> z("z");
    y = x;
    y = x * 2.0f;  // overwritten, but still an output assignment
    RILL_IF(x > 0.0f) {
      z = x;
    }
    RILL_ENDIF;
  });
  ir::Function f = swept(p, false);
  EXPECT_EQ(test::statements(f), test::statements(p.ir()));
}

TEST(DeadCode, CodeAfterAJumpGoes) {
  Program p = program("after_jump", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_IF(x > 1.0f) {
      RILL_DISCARD;
      y = x * 2.0f;  // never runs
    }
    RILL_ENDIF;
    RILL_WHILE(y < 10.0f) {
      y = y + 1.0f;
      RILL_IF(y > 5.0f) {
        RILL_BREAK;
        y = -y;
      }
      RILL_ENDIF;
      RILL_IF(y > 3.0f) {
        RILL_CONTINUE;
        y = y * 3.0f;
      }
      RILL_ENDIF;
    }
    RILL_ENDWHILE;
  });
  ir::Function f = swept(p);
  EXPECT_EQ(count_ops(f, Op::Neg), 0) << ir::print(f);
  EXPECT_EQ(count_ops(f, Op::Mul), 0) << ir::print(f);
  EXPECT_EQ(count_kind(f, StmtKind::Discard), 1);
  EXPECT_EQ(count_kind(f, StmtKind::Break), 1);
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 1);
}

TEST(DeadCode, EmptyIfsGo) {
  Program p = program("empty_if", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_IF(x > 0.0f) {
      Float t = x * 2.0f;  // dead: the if becomes empty, then its condition is dead
    }
    RILL_ELSE {
      Float u = x - 1.0f;
    }
    RILL_ENDIF;
  });
  ir::Function f = swept(p);
  EXPECT_EQ(count_kind(f, StmtKind::If), 0) << ir::print(f);
  EXPECT_EQ(test::statements(f), 1) << ir::print(f);
}

TEST(DeadCode, LoopsAndWhatTheyReadStay) {
  Program p = program("loops", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = n;
    Int i = 0;
    RILL_WHILE(i < n) {
      i += 1;
    }  // i is never used after: the loop still runs
    RILL_ENDWHILE;
  });
  ir::Function f = swept(p, false);
  EXPECT_EQ(ir::count_loops(f.body), 1);
  EXPECT_EQ(count_ops(f, Op::Add), 1);
}

TEST(DeadCode, UnreadLocalsInLoopsGo) {
  Program p = program("loop_dead", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_FOR(Int i = 0, i < 3, i += 1) {
      Float waste = to_float(i) * x;
      y = y + x;
    }
    RILL_ENDFOR;
  });
  ir::Function f = swept(p);
  EXPECT_EQ(count_ops(f, Op::Mul), 0) << ir::print(f);
  EXPECT_EQ(count_ops(f, Op::IntToFloat), 0) << ir::print(f);
  EXPECT_EQ(ir::count_loops(f.body), 1);
}

TEST(DeadCodeCpu, PreservesResults) {
  Program p = program("dead_mix", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    y = 0.0f;
    Float unused = x * x * x;
    RILL_IF(n < 0) {
      y = -x;
      RILL_DISCARD;
      y = x * 100.0f;
    }
    RILL_ENDIF;
    Int i = 0;
    RILL_WHILE(i < (n & 7)) {
      i += 1;
      Float t = to_float(i) * unused;
      RILL_IF(to_float(i) > x) {
        y = y + 1.0f;
        RILL_CONTINUE;
        y = y + t;
      }
      RILL_ENDIF;
      y = y + x;
    }
    RILL_ENDWHILE;
  });
  auto xs = test::random_floats(3000, 41, -5.0f, 5.0f);
  auto ns = test::random_ints(3000, 42, -100, 100);
  test::expect_passes_preserve_results<Float, Float, Int>(p, xs, ns);
}

}  // namespace
}  // namespace rill
