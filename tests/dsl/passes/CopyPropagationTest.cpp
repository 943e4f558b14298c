// passes::copy_propagate: reads of single-assignment copies read the source instead.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Op;
using ir::Operand;
using ir::Stmt;
using test::count_ops;
using test::normalized;

ir::Function propagated(const Program& p, bool expect_change = true) {
  return test::after(p,
                     [&](ir::Function& f) { EXPECT_EQ(passes::copy_propagate(f), expect_change); });
}

TEST(CopyPropagation, ChainsOfCopiesReadTheSource) {
  Program p = program("chain", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float a = x;
    Float b = a;
    Float c = b;
    y = c * c;
  });
  ir::Function f = propagated(p);
  std::string text = normalized(ir::print(f));
  EXPECT_LINE(text, "t# = mul(x_0, x_0)");
  // The copies themselves stay (dead now) until eliminate_dead_code.
  EXPECT_EQ(test::statements(f), test::statements(p.ir()));
  passes::eliminate_dead_code(f);
  EXPECT_EQ(test::statements(f), 2) << ir::print(f);
  EXPECT_EQ(test::problems(f), "");
}

TEST(CopyPropagation, ConstantsPropagate) {
  Program p = program("consts", [] {
    Input<Float3> v("v");
    Output<Float3> y("y");
    Float3 k(1.0f, 2.0f, 3.0f);  // a variable initialized with a constant
    Float s = 0.5f;
    y = v * s + k;
  });
  ir::Function f = propagated(p);
  std::string text = normalized(ir::print(f));
  EXPECT_LINE(text, "t# = mul(v_0, 0.5)");
  EXPECT_LINE(text, "t# = add(t#, float3(1.0, 2.0, 3.0))");
}

// Hand-built, so that the swizzles are exactly those under test.
TEST(CopyPropagation, SwizzlesCompose) {
  ir::Function f;
  f.name = "swz";
  ir::VarId v = f.add_var(ir::float_type(3), ir::VarRole::Input, "v");
  ir::VarId y = f.add_var(ir::float_type(2), ir::VarRole::Output, "y");
  ir::VarId z = f.add_var(ir::float_type(4), ir::VarRole::Output, "z");
  ir::VarId t = f.add_var(ir::float_type(3));
  ir::VarId k = f.add_var(ir::float_type(3));
  f.inputs = {v};
  f.outputs = {y, z};
  // t = v.zxy; y = t.yz (= v.xy); k = (1, 2, 3); z = construct(k.zx, t.xx) (= 3, 1, v.zz)
  f.body.push_back(
      Stmt::assign(t, Op::Copy, {Operand::of_var(v, ir::ScalarKind::Float, {2, 0, 1})}));
  f.body.push_back(Stmt::assign(y, Op::Copy, {Operand::of_var(t, ir::ScalarKind::Float, {1, 2})}));
  ir::Constant c;
  c.type = ir::float_type(3);
  c.bits = {std::bit_cast<uint32_t>(1.0f), std::bit_cast<uint32_t>(2.0f),
            std::bit_cast<uint32_t>(3.0f), 0};
  f.body.push_back(Stmt::assign(k, Op::Copy, {Operand::of_const(c)}));
  f.body.push_back(Stmt::assign(z, Op::Construct,
                                {Operand::of_var(k, ir::ScalarKind::Float, {2, 0}),
                                 Operand::of_var(t, ir::ScalarKind::Float, {0, 0})}));
  ASSERT_EQ(test::problems(f), "");
  EXPECT_TRUE(passes::copy_propagate(f));
  EXPECT_EQ(test::problems(f), "");
  std::string text = ir::print(f);
  EXPECT_LINE(text, "y_1 = copy(v_0.xy)");
  EXPECT_LINE(text, "z_2 = construct(float2(3.0, 1.0), v_0.zz)");
}

TEST(CopyPropagation, NotWhenTheCopyIsAssignedAgain) {
  Program p = program("reassigned", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float a = x;
    a = a * 2.0f;
    y = a + x;
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::copy_propagate(g); });
  std::string text = normalized(ir::print(f));
  EXPECT_LINE(text, "t# = add(t#, x_0)");  // still reads a, not x
  EXPECT_EQ(test::count_lines(text, "t# = add(x_0, x_0)"), 0);
}

TEST(CopyPropagation, NotWhenTheSourceIsAssignedAgain) {
  Program p = program("source_changes", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float s = x * 3.0f;
    Float t = s;  // t keeps the old value of s
    s = s + 1.0f;
    y = t * s;
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::copy_propagate(g); });
  const ir::Stmt& mul = f.body[f.body.size() - 2];
  ASSERT_EQ(mul.op, Op::Mul) << ir::print(f);
  EXPECT_NE(mul.args[0].var, mul.args[1].var) << ir::print(f);
}

TEST(CopyPropagation, NotIntoOutputsOrThroughMasks) {
  Program p = program("outputs", [] {
    Input<Float3> v("v");
    Output<Float3> y("y");
    Output<Float3> z("z");
    y = v;
    Float3 m = v;
    m(1) = 5.0f;  // m is assigned twice: not a plain copy any more
    z = m + y;    // y is an output: its value is not v everywhere
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::copy_propagate(g); });
  std::string text = normalized(ir::print(f));
  EXPECT_LINE(text, "y_1 = copy(v_0)");
  EXPECT_LINE(text, "t# = add(t#, y_1)");
}

TEST(CopyPropagation, LoopCarriedVariablesAreNotPropagated) {
  Program p = program("loop", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = x;
    RILL_FOR(Int i = 0, i < 3, i += 1) {
      Float prev = acc;  // copy of a variable assigned in the loop
      acc = acc * 2.0f;
      acc = acc + prev;
    }
    RILL_ENDFOR;
    y = acc;
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::copy_propagate(g); });
  // prev must still be read by the add (acc changed in between).
  int adds_reading_acc_twice = 0;
  ir::for_each_stmt(f.body, [&](const ir::Stmt& s) {
    if (s.kind == ir::StmtKind::Assign && s.op == Op::Add && s.args[0].is_var() &&
        s.args[1].is_var() && s.args[0].var == s.args[1].var)
      ++adds_reading_acc_twice;
  });
  EXPECT_EQ(adds_reading_acc_twice, 0) << ir::print(f);
}

TEST(CopyPropagation, NothingToDoReportsNoChange) {
  Program p = program("nothing", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * x;
  });
  propagated(p, false);
}

TEST(CopyPropagationCpu, PreservesResults) {
  Program p = program("copies", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Float3 v(x, x * 2.0f, x * 3.0f);
    Float3 w = v;
    Float3 u = w;
    u(0) = w.z();
    Float s = u.x() + w.y();
    Float t = s;
    s = s * 0.5f;
    Int k = n;
    Int j = k & 7;
    RILL_WHILE(j > 0) {
      Float old = t;
      t = t + s;
      s = old;
      j -= 1;
    }
    RILL_ENDWHILE;
    y = t - s + to_float(k) + u.z();
  });
  auto xs = test::random_floats(3000, 21);
  auto ns = test::random_ints(3000, 22);
  test::expect_passes_preserve_results<Float, Float, Int>(p, xs, ns);
}

}  // namespace
}  // namespace rill
