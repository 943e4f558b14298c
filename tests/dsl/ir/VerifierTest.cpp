// ir/Verifier.h: accepts every captured program, rejects hand-built malformed IR.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Constant;
using ir::Op;
using ir::Operand;
using ir::Stmt;
using ir::StmtKind;

// in float x, in int n, out float y, a float3 local v, a uniform u; body: y = copy(x).
struct Fixture {
  ir::Function f;
  ir::VarId x, n, y, v, u;
  Fixture() {
    f.name = "hand";
    x = f.add_var(ir::float_type(1), ir::VarRole::Input, "x");
    n = f.add_var(ir::int_type(1), ir::VarRole::Input, "n");
    y = f.add_var(ir::float_type(1), ir::VarRole::Output, "y");
    v = f.add_var(ir::float_type(3), ir::VarRole::Local, "v");
    u = f.add_var(ir::float_type(1), ir::VarRole::Uniform, "u");
    f.inputs = {x, n};
    f.outputs = {y};
    f.uniforms = {u};
    f.body.push_back(Stmt::assign(y, Op::Copy, {X()}));
  }
  Operand X() const { return Operand::of_var(x, ir::float_type(1)); }
  Operand N() const { return Operand::of_var(n, ir::int_type(1)); }
  Operand V() const { return Operand::of_var(v, ir::float_type(3)); }
  static Operand F(float c) { return Operand::of_const(Constant::of_float(c)); }
  static Operand I(int32_t c) { return Operand::of_const(Constant::of_int(c)); }
  static Operand B(bool c) { return Operand::of_const(Constant::of_bool(c)); }
  ir::VarId temp(ir::Type t) { return f.add_var(t); }
  std::string problems() const { return test::problems(f); }
};

TEST(Verifier, AcceptsTheFixture) {
  Fixture fx;
  EXPECT_EQ(fx.problems(), "");
}

TEST(Verifier, AcceptsCapturedPrograms) {
  Uniform<Float3> tint(glm::vec3(1.0f), "tint");
  Array<Float> table(std::vector<float>{1.0f, 2.0f}, "table");
  Program p = program("big", [&] {
    Input<Float3> v("v");
    Input<Int> n("n");
    Output<Float3> y("y");
    Output<Int> k("k");
    y = v * tint;
    k = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF(table[i] > 1.0f) {
        RILL_CONTINUE;
      }
      RILL_ELSE_IF(i == 7) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      y(0, 2) = y(2, 0) * 0.5f;
      k = k + (i ^ 3);
    }
    RILL_ENDFOR;
    RILL_DO {
      y = normalize(cross(y, v));
    }
    RILL_UNTIL(any(y < 0.0f));
    RILL_IF(dot(y, y) > 2.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(test::problems(p.ir()), "");
  EXPECT_NO_THROW(ir::verify_or_throw(p.ir(), "test"));
}

TEST(Verifier, OperandKindsMustAgree) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(1));
  fx.f.body.push_back(Stmt::assign(t, Op::Add, {fx.X(), Fixture::I(1)}));
  EXPECT_HAS(fx.problems(), "operand kinds differ (float vs int)");
}

TEST(Verifier, ResultMustMatchTheDestination) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(1));
  fx.f.body.push_back(Stmt::assign(t, Op::Add, {fx.V(), fx.X()}));  // float3 into a float
  EXPECT_HAS(fx.problems(), "add yields float3 but writes 1 component(s) of float t5");

  Fixture g;
  ir::VarId b = g.temp(ir::float_type(1));
  g.f.body.push_back(Stmt::assign(b, Op::Lt, {g.X(), Fixture::F(1.0f)}));  // bool into a float
  EXPECT_HAS(g.problems(), "lt yields bool");
}

TEST(Verifier, OperandTypeMustMatchItsVariable) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::int_type(1));
  Operand wrong = fx.X();
  wrong.type = ir::int_type(1);
  fx.f.body.push_back(Stmt::assign(t, Op::Copy, {wrong}));
  EXPECT_HAS(fx.problems(), "has type int but its variable is float");
}

TEST(Verifier, SwizzleBeyondTheVariable) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(2));
  fx.f.body.push_back(
      Stmt::assign(t, Op::Copy, {Operand::of_var(fx.x, ir::ScalarKind::Float, {0, 2})}));
  EXPECT_HAS(fx.problems(), "swizzle of x_0 reads component 2 of a float");
}

TEST(Verifier, BadWriteMasks) {
  Fixture fx;
  Stmt s = Stmt::assign(fx.v, Op::Copy, {Fixture::F(1.0f)});
  s.mask.count = 1;
  s.mask.comps[0] = 3;  // v is a float3
  fx.f.body.push_back(s);
  EXPECT_HAS(fx.problems(), "write mask component out of range");

  Fixture g;
  Constant two;
  two.type = ir::float_type(2);
  Stmt r = Stmt::assign(g.v, Op::Copy, {Operand::of_const(two)});
  r.mask.count = 2;
  r.mask.comps = {1, 1, 0, 0};
  g.f.body.push_back(r);
  EXPECT_HAS(g.problems(), "write mask repeats a component");
}

TEST(Verifier, BreakAndContinueOutsideALoop) {
  Fixture fx;
  Stmt iff = Stmt::make_if(Fixture::B(true));
  iff.then_body.push_back(Stmt::make(StmtKind::Break));
  fx.f.body.push_back(iff);
  fx.f.body.push_back(Stmt::make(StmtKind::Continue));
  std::string p = fx.problems();
  EXPECT_HAS(p, "break outside a loop");
  EXPECT_HAS(p, "continue outside a loop");

  // Inside a loop's body (through an if) they are fine; so is discard anywhere.
  Fixture g;
  Stmt loop = Stmt::make_loop(ir::LoopKind::While);
  loop.cond = Fixture::B(true);
  Stmt inner = Stmt::make_if(Fixture::B(false));
  inner.then_body.push_back(Stmt::make(StmtKind::Break));
  inner.else_body.push_back(Stmt::make(StmtKind::Continue));
  loop.body.push_back(inner);
  g.f.body.push_back(loop);
  g.f.body.push_back(Stmt::make(StmtKind::Discard));
  EXPECT_EQ(g.problems(), "");
}

TEST(Verifier, ConditionsMustBeScalarBools) {
  Fixture fx;
  fx.f.body.push_back(Stmt::make_if(fx.X()));
  EXPECT_HAS(fx.problems(), "condition must be a scalar bool, got float");

  Fixture g;
  Stmt loop = Stmt::make_loop(ir::LoopKind::DoUntil);
  Constant b2;
  b2.type = ir::bool_type(2);
  loop.cond = Operand::of_const(b2);
  g.f.body.push_back(loop);
  EXPECT_HAS(g.problems(), "condition must be a scalar bool, got bool2");
}

TEST(Verifier, UnknownVariables) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(1));
  fx.f.body.push_back(Stmt::assign(t, Op::Copy, {Operand::of_var(99, ir::float_type(1))}));
  EXPECT_HAS(fx.problems(), "operand reads unknown variable t99");

  Fixture g;
  g.f.body.push_back(Stmt::assign(77, Op::Copy, {g.X()}));
  EXPECT_HAS(g.problems(), "assignment to unknown variable");

  Fixture h;
  h.f.body.push_back(Stmt::make_if(Operand::of_var(55, ir::bool_type(1))));
  EXPECT_HAS(h.problems(), "unknown variable t55");
}

TEST(Verifier, OpSignatures) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(1));
  fx.f.body.push_back(Stmt::assign(t, Op::Add, {fx.X()}));
  EXPECT_HAS(fx.problems(), "add: expects 2 operands, got 1");

  Fixture g;
  ir::VarId i = g.temp(ir::int_type(1));
  g.f.body.push_back(Stmt::assign(i, Op::BitAnd, {g.X(), g.X()}));
  EXPECT_HAS(g.problems(), "bitand: not defined on float");

  Fixture h;
  ir::VarId s = h.temp(ir::float_type(1));
  h.f.body.push_back(Stmt::assign(s, Op::Sin, {h.N()}));
  EXPECT_HAS(h.problems(), "sin: not defined on int");

  Fixture k;
  ir::VarId w = k.temp(ir::float_type(3));
  Constant two;
  two.type = ir::float_type(2);
  k.f.body.push_back(Stmt::assign(w, Op::Mul, {k.V(), Operand::of_const(two)}));
  EXPECT_HAS(k.problems(), "operand widths differ");

  Fixture c;
  ir::VarId cr = c.temp(ir::float_type(3));
  c.f.body.push_back(Stmt::assign(cr, Op::Cross, {c.V(), c.X()}));
  EXPECT_HAS(c.problems(), "cross: expects float3 operands");
}

TEST(Verifier, ConstructAndGather) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(3));
  fx.f.body.push_back(Stmt::assign(t, Op::Construct, {fx.X(), fx.N(), fx.X()}));
  EXPECT_HAS(fx.problems(), "construct mixes kinds");

  Fixture w;
  ir::VarId t4 = w.temp(ir::float_type(4));
  w.f.body.push_back(Stmt::assign(t4, Op::Construct, {w.X(), w.V(), w.X()}));  // 5 components
  EXPECT_HAS(w.problems(), "construct yields float5 but writes 4 component(s)");

  Fixture g;
  ir::VarId r = g.temp(ir::float_type(1));
  Stmt gather = Stmt::assign(r, Op::Gather, {g.N()});
  gather.array = 0;  // there are no arrays
  g.f.body.push_back(gather);
  EXPECT_HAS(g.problems(), "gather from unknown array");

  Fixture h;
  h.f.arrays.push_back(ir::ArrayDecl{"grid", ir::float_type(1), 2});
  ir::VarId q = h.temp(ir::float_type(1));
  Stmt g1 = Stmt::assign(q, Op::Gather, {h.N()});
  g1.array = 0;
  h.f.body.push_back(g1);
  Stmt g2 = Stmt::assign(q, Op::Gather, {h.N(), h.X()});
  g2.array = 0;
  h.f.body.push_back(g2);
  std::string p = h.problems();
  EXPECT_HAS(p, "gather index count differs from array dimensions");
  EXPECT_HAS(p, "gather index must be a scalar int");
}

TEST(Verifier, UniformsAreReadOnlyAndOutputsMustBeWritten) {
  Fixture fx;
  fx.f.body.clear();  // y is no longer written
  fx.f.body.push_back(Stmt::assign(fx.u, Op::Copy, {fx.X()}));
  std::string p = fx.problems();
  EXPECT_HAS(p, "assignment to uniform 'u'");
  EXPECT_HAS(p, "output 'y' is never written");
}

TEST(Verifier, InconsistentConstant) {
  Fixture fx;
  ir::VarId t = fx.temp(ir::float_type(1));
  Operand c = Fixture::F(1.0f);
  c.type = ir::float_type(2);
  fx.f.body.push_back(Stmt::assign(t, Op::Copy, {c}));
  EXPECT_HAS(fx.problems(), "constant operand has inconsistent type");
}

TEST(Verifier, MessagesNameTheSourceLocationAndVerifyOrThrowListsThem) {
  Fixture fx;
  int line = __LINE__;
  fx.f.body.push_back(Stmt::make(StmtKind::Break, RILL_HERE));
  fx.f.body.push_back(Stmt::make_if(fx.X()));
  auto all = ir::verify(fx.f);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_HAS(all[0], test::here(__FILE__, line + 1) + ": break outside a loop");
  std::string msg = test::error_of([&] { ir::verify_or_throw(fx.f, "my pass"); });
  EXPECT_HAS(msg, "my pass: kernel 'hand' is malformed:");
  EXPECT_HAS(msg, "break outside a loop");
  EXPECT_HAS(msg, "condition must be a scalar bool");
}

}  // namespace
}  // namespace rill
