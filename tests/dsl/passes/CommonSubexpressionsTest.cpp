// passes::eliminate_common_subexpressions: a pure op recomputed where an identical one
// dominates it becomes a copy; never for operands that may have changed in between.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Op;
using test::count_ops;

ir::Function cse(const Program& p, bool expect_change = true) {
  return test::after(p, [&](ir::Function& f) {
    EXPECT_EQ(passes::eliminate_common_subexpressions(f), expect_change);
  });
}

TEST(CommonSubexpressions, RepeatedExpressionBecomesACopy) {
  Program p = program("repeat", [] {
    Input<Float> x("x");
    Input<Float> z("z");
    Output<Float> y("y");
    Float a = x * z;
    Float b = x * z;
    Float c = z * x;  // commutative: the same
    Float d = x - z;
    Float e = z - x;  // not commutative: different
    y = a + b + c + d + e;
  });
  ir::Function f = cse(p);
  EXPECT_EQ(count_ops(f, Op::Mul), 1) << ir::print(f);
  EXPECT_EQ(count_ops(f, Op::Sub), 2);
  EXPECT_EQ(test::statements(f), test::statements(p.ir()));  // replaced by copies
  EXPECT_EQ(count_ops(f, Op::Copy), count_ops(p.ir(), Op::Copy) + 2);
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Mul), 1);
  std::string text = test::normalized(ir::print(o));
  EXPECT_LINE(text, "t# = add(t#, t#)");
}

// min and max pick by order: min(NaN, 1) is NaN but min(1, NaN) is 1, and min(-0, +0) is -0
// but min(+0, -0) is +0. So swapped operands are a different expression.
TEST(CommonSubexpressions, MinAndMaxOperandsAreNotSwapped) {
  Program p = program("minmax", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> z("z");
    y = min(x, 1.0f) + max(x, 1.0f);
    z = min(1.0f, x) + max(1.0f, x);
  });
  ir::Function f = cse(p, false);
  EXPECT_EQ(count_ops(f, Op::Min), 2) << ir::print(f);
  EXPECT_EQ(count_ops(f, Op::Max), 2) << ir::print(f);
}

TEST(CommonSubexpressionsCpu, MinAndMaxOfNaNAndSignedZerosKeepTheirOrder) {
  Program p = program("minmax_nan", [] {
    Input<Float> x("x");
    Input<Float> w("w");
    Output<Float4> y("y");
    y = Float4(min(x, w), min(w, x), max(x, w), max(w, x));
  });
  const float nan = std::numeric_limits<float>::quiet_NaN();
  test::expect_passes_preserve_results<Float4, Float, Float>(
      p, std::vector<float>{nan, 1.0f, -0.0f, 0.0f, nan},
      std::vector<float>{1.0f, nan, 0.0f, -0.0f, nan});
}

TEST(CommonSubexpressions, OperandsMustMatchExactly) {
  Program p = program("exact", [] {
    Input<Float3> v("v");
    Output<Float> y("y");
    Float a = v.x() * v.y();
    Float b = v.x() * v.z();  // another component
    Float c = v.x() * v.y();  // the same as a (through equal single-component reads)
    y = a + b + c;
  });
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Mul), 2) << ir::print(o);
  Program q = program("kinds", [] {
    Input<Int> n("n");
    Output<Float> y("y");
    y = to_float(n + 1) + to_float(n + 2) + as_float(n + 1);
  });
  ir::Function oq = passes::optimize(q.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(oq, Op::Add), 4) << ir::print(oq);  // n + 1 once, n + 2, two float adds
  EXPECT_EQ(count_ops(oq, Op::IntToFloat), 2);
  EXPECT_EQ(count_ops(oq, Op::IntBitsToFloat), 1);
}

TEST(CommonSubexpressions, DominanceIsByBlock) {
  Program p = program("scopes", [] {
    Input<Float> x("x");
    Input<Float> z("z");
    Output<Float> y("y");
    Float before = x * z;
    y = before;
    RILL_IF(x > z) {
      y = y + x * z;  // dominated by `before`: reused
      y = y + x / z;
    }
    RILL_ELSE {
      y = y - x / z;  // the then-branch does not dominate the else-branch
    }
    RILL_ENDIF;
    y = y * (x / z);  // neither branch dominates what follows the if
  });
  ir::Function f = cse(p);
  EXPECT_EQ(count_ops(f, Op::Mul), 2) << ir::print(f);  // before, and y * (...)
  EXPECT_EQ(count_ops(f, Op::Div), 3) << ir::print(f);
}

TEST(CommonSubexpressions, NotAcrossAssignmentsToAnOperand) {
  Program p = program("changed", [] {
    Input<Float> x("x");
    Input<Float> z("z");
    Output<Float> y("y");
    Float a = x;
    Float p1 = a * z;
    a = a + 1.0f;
    Float p2 = a * z;  // a changed: not the same value as p1
    y = p1 + p2;
  });
  ir::Function f =
      test::after(p, [](ir::Function& g) { passes::eliminate_common_subexpressions(g); });
  EXPECT_EQ(count_ops(f, Op::Mul), 2) << ir::print(f);
}

TEST(CommonSubexpressions, NotForLoopCarriedVariables) {
  Program p = program("loop", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = x;
    RILL_FOR(Int i = 0, i < 4, i += 1) {
      Float u = acc * x;
      acc = acc + u;
      Float w = acc * x;  // the same text as u, another value
      acc = acc - w * 0.5f;
    }
    RILL_ENDFOR;
    y = acc * x;  // and again after the loop
  });
  ir::Function f =
      test::after(p, [](ir::Function& g) { passes::eliminate_common_subexpressions(g); });
  EXPECT_EQ(count_ops(f, Op::Mul), count_ops(p.ir(), Op::Mul)) << ir::print(f);
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Mul), 4) << ir::print(o);  // u, w, w * 0.5, and after the loop
}

TEST(CommonSubexpressions, InsideALoopBodyTemporariesAreReused) {
  Program p = program("loop_body", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Float acc = 0.0f;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      Float fi = to_float(i);
      acc = acc + fi * x + fi * x;  // fi is written once per iteration: one mul
    }
    RILL_ENDFOR;
    y = acc;
  });
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Mul), 1) << ir::print(o);
  EXPECT_EQ(count_ops(o, Op::IntToFloat), 1);
}

TEST(CommonSubexpressions, GathersAndElementIndexMerge) {
  Array<Float> table(std::vector<float>{1.0f, 2.0f, 3.0f}, "table");
  Program p = program("gathers", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = table[i] + table[i] + table[i + 1] + to_float(element_index() + element_index());
  });
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Gather), 2) << ir::print(o);
  EXPECT_EQ(count_ops(o, Op::ElementIndex), 1) << ir::print(o);
}

TEST(CommonSubexpressions, NothingToDoReportsNoChange) {
  Program p = program("nothing", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * x + x;
  });
  cse(p, false);
}

TEST(CommonSubexpressionsCpu, PreservesResults) {
  Array<Float> table(std::vector<float>{0.5f, -1.0f, 2.0f, 8.0f}, "table");
  Program p = program("cse_mix", [&] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Float a = x * x + table[n & 3];
    Float acc = a;
    Int m = n & 15;
    RILL_WHILE(m > 0) {
      Float u = acc * x;
      acc = acc + u;
      Float w = acc * x;
      RILL_IF(w > 100.0f) {
        acc = acc * 0.25f;
      }
      RILL_ELSE {
        acc = acc + x * x;
      }
      RILL_ENDIF;
      m -= 1;
    }
    RILL_ENDWHILE;
    y = acc + x * x + table[n & 3] + a;
  });
  auto xs = test::random_floats(3000, 31, -2.0f, 2.0f);
  auto ns = test::random_ints(3000, 32);
  test::expect_passes_preserve_results<Float, Float, Int>(p, xs, ns);
}

}  // namespace
}  // namespace rill
