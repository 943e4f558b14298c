// passes::constant_fold and passes::fold: exact binary32 folding, integer wrap-around,
// identities, constant branches; ConstantFoldCpu checks every folded result against what
// the CPU backend computes at run time, bit for bit.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Constant;
using ir::Op;
using test::count_ops;
using test::normalized;

const float kInf = std::numeric_limits<float>::infinity();
const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kDenorm = std::numeric_limits<float>::denorm_min();
const int32_t kMax = std::numeric_limits<int32_t>::max();
const int32_t kMin = std::numeric_limits<int32_t>::min();

uint32_t fbits(float f) {
  return std::bit_cast<uint32_t>(f);
}

// Folds op on scalar constants; the result must exist.
Constant fold1(Op op, ir::Type result, std::vector<Constant> args) {
  auto r = passes::fold(op, result, args);
  EXPECT_TRUE(r.has_value()) << ir::op_name(op);
  return r.value_or(Constant{});
}
uint32_t ffold(Op op, float a, float b = 0.0f) {
  int arity = ir::op_info(op).arity;
  std::vector<Constant> args{Constant::of_float(a)};
  if (arity == 2) args.push_back(Constant::of_float(b));
  return fold1(op, ir::float_type(1), args).bits[0];
}
int32_t ifold(Op op, int32_t a, int32_t b = 0) {
  int arity = ir::op_info(op).arity;
  std::vector<Constant> args{Constant::of_int(a)};
  if (arity == 2) args.push_back(Constant::of_int(b));
  return fold1(op, ir::int_type(1), args).i(0);
}

// ---- fold() on its own -----------------------------------------------------------------------

TEST(ConstantFold, FloatArithmeticIsBinary32) {
  EXPECT_EQ(ffold(Op::Add, 0.1f, 0.2f), fbits(0.3f));
  EXPECT_EQ(ffold(Op::Add, 0.1f, 0.2f), 0x3e99999au);
  EXPECT_EQ(ffold(Op::Div, 1.0f, 3.0f), 0x3eaaaaabu);
  EXPECT_EQ(ffold(Op::Sqrt, 2.0f), 0x3fb504f3u);
  EXPECT_EQ(ffold(Op::Add, 1e8f, 1.0f), fbits(1e8f));  // 1 is below half an ulp of 1e8
  EXPECT_EQ(ffold(Op::Add, 16777216.0f, 1.0f), fbits(16777216.0f));  // ties to even
  EXPECT_EQ(ffold(Op::Add, 16777216.0f, 3.0f), fbits(16777220.0f));
  EXPECT_EQ(ffold(Op::Mul, 3.0f, 1.0f / 3.0f), fbits(1.0f));
  EXPECT_EQ(ffold(Op::Sub, 1.0f, 0.9f), fbits(1.0f - 0.9f));
  EXPECT_EQ(ffold(Op::Rsqrt, 4.0f), fbits(0.5f));
  EXPECT_EQ(ffold(Op::Mod, 5.5f, 2.0f), fbits(1.5f));
  EXPECT_EQ(ffold(Op::Mod, -5.5f, 2.0f), fbits(0.5f));  // x - y * floor(x / y)
  EXPECT_EQ(ffold(Op::Fract, -0.25f), fbits(0.75f));
  EXPECT_EQ(ffold(Op::Floor, -0.5f), fbits(-1.0f));
  EXPECT_EQ(ffold(Op::Ceil, -0.5f), fbits(-0.0f));
  EXPECT_EQ(ffold(Op::Min, 1.0f, 2.0f), fbits(1.0f));
  EXPECT_EQ(ffold(Op::Max, 1.0f, 2.0f), fbits(2.0f));
}

TEST(ConstantFold, DenormalsAreNotFlushed) {
  EXPECT_EQ(ffold(Op::Mul, 1e-38f, 1e-3f), fbits(1e-41f));
  EXPECT_NE(ffold(Op::Mul, 1e-38f, 1e-3f), 0u);
  EXPECT_EQ(ffold(Op::Add, kDenorm, kDenorm), 2u);
  EXPECT_EQ(ffold(Op::Mul, kDenorm, 0.5f), 0u);  // rounds to even: zero
  EXPECT_EQ(ffold(Op::Mul, kDenorm, 1.5f), 2u);
  EXPECT_EQ(ffold(Op::Div, std::numeric_limits<float>::min(), 4.0f), 0x00200000u);
  EXPECT_EQ(ffold(Op::Sqrt, kDenorm), fbits(std::sqrt(kDenorm)));
}

TEST(ConstantFold, SignedZerosInfinitiesAndNaN) {
  EXPECT_EQ(ffold(Op::Add, -0.0f, 0.0f), fbits(0.0f));
  EXPECT_EQ(ffold(Op::Add, -0.0f, -0.0f), fbits(-0.0f));
  EXPECT_EQ(ffold(Op::Mul, -0.0f, 5.0f), fbits(-0.0f));
  EXPECT_EQ(ffold(Op::Neg, 0.0f), fbits(-0.0f));
  EXPECT_EQ(ffold(Op::Abs, -0.0f), fbits(0.0f));
  EXPECT_EQ(ffold(Op::Sign, -0.0f), fbits(0.0f));  // sign(-0) = 0
  EXPECT_EQ(ffold(Op::Sign, kNaN), fbits(0.0f));   // sign(NaN) = 0
  EXPECT_EQ(ffold(Op::Sign, -3.0f), fbits(-1.0f));
  EXPECT_EQ(ffold(Op::Sqrt, -0.0f), fbits(-0.0f));
  EXPECT_EQ(ffold(Op::Div, 1.0f, 0.0f), fbits(kInf));
  EXPECT_EQ(ffold(Op::Div, 1.0f, -0.0f), fbits(-kInf));
  EXPECT_EQ(ffold(Op::Add, 3e38f, 3e38f), fbits(kInf));
  EXPECT_EQ(ffold(Op::Min, -0.0f, 0.0f), fbits(-0.0f));  // min(a, b) = b < a ? b : a
  EXPECT_EQ(ffold(Op::Min, 0.0f, -0.0f), fbits(0.0f));
  EXPECT_EQ(ffold(Op::Min, kNaN, 1.0f), fbits(kNaN));  // NaN first: NaN
  EXPECT_EQ(ffold(Op::Min, 1.0f, kNaN), fbits(1.0f));  // NaN second: the first operand
  EXPECT_EQ(ffold(Op::Max, 1.0f, kNaN), fbits(1.0f));
  for (auto [op, a, b] : {std::tuple{Op::Div, 0.0f, 0.0f},
                          {Op::Add, kInf, -kInf},
                          {Op::Mul, 0.0f, kInf},
                          {Op::Sqrt, -1.0f, 0.0f},
                          {Op::Mod, 1.0f, 0.0f}})
    EXPECT_TRUE(std::isnan(std::bit_cast<float>(ffold(op, a, b)))) << ir::op_name(op);
  // A NaN operand's payload is kept (as binary32 hardware does).
  uint32_t payload = 0x7fc12345u;
  EXPECT_EQ(ffold(Op::Add, std::bit_cast<float>(payload), 1.0f), payload);
  EXPECT_EQ(ffold(Op::Abs, std::bit_cast<float>(payload | 0x80000000u)), payload);
  EXPECT_EQ(ffold(Op::Neg, std::bit_cast<float>(payload)), payload | 0x80000000u);
}

TEST(ConstantFold, IntegerArithmeticWraps) {
  EXPECT_EQ(ifold(Op::Add, kMax, 1), kMin);
  EXPECT_EQ(ifold(Op::Sub, kMin, 1), kMax);
  EXPECT_EQ(ifold(Op::Mul, 65536, 65536), 0);
  EXPECT_EQ(ifold(Op::Mul, kMin, -1), kMin);
  EXPECT_EQ(ifold(Op::Neg, kMin), kMin);
  EXPECT_EQ(ifold(Op::Abs, kMin), kMin);
  EXPECT_EQ(ifold(Op::Div, kMin, -1), kMin);
  EXPECT_EQ(ifold(Op::Mod, kMin, -1), 0);
  EXPECT_EQ(ifold(Op::Div, 7, -2), -3);  // truncation
  EXPECT_EQ(ifold(Op::Div, -7, 2), -3);
  EXPECT_EQ(ifold(Op::Mod, -7, 3), -1);  // sign of the dividend
  EXPECT_EQ(ifold(Op::Mod, 7, -3), 1);
  EXPECT_EQ(ifold(Op::Shl, 1, 31), kMin);
  EXPECT_EQ(ifold(Op::Shl, 1, 32), 1);  // low 5 bits of the count
  EXPECT_EQ(ifold(Op::Shl, 1, 33), 2);
  EXPECT_EQ(ifold(Op::Shr, -8, 1), -4);  // arithmetic
  EXPECT_EQ(ifold(Op::Shr, -1, 31), -1);
  EXPECT_EQ(ifold(Op::Shr, 256, -1), 0);  // count 31
  EXPECT_EQ(ifold(Op::BitNot, 0), -1);
  EXPECT_EQ(ifold(Op::Sign, -9), -1);
}

TEST(ConstantFold, IntegerDivisionByZeroGivesZero) {
  EXPECT_EQ(ifold(Op::Div, 7, 0), 0);
  EXPECT_EQ(ifold(Op::Div, kMin, 0), 0);
  EXPECT_EQ(ifold(Op::Mod, 7, 0), 0);
  EXPECT_EQ(ifold(Op::Mod, -7, 0), 0);
}

TEST(ConstantFold, ConversionsAndComparisons) {
  auto to_int = [](float f) {
    return fold1(Op::FloatToInt, ir::int_type(1), {Constant::of_float(f)}).i(0);
  };
  EXPECT_EQ(to_int(-2.7f), -2);
  EXPECT_EQ(to_int(2.7f), 2);
  EXPECT_EQ(to_int(kNaN), 0);
  EXPECT_EQ(to_int(3e9f), kMax);
  EXPECT_EQ(to_int(-3e9f), kMin);
  EXPECT_EQ(to_int(kInf), kMax);
  EXPECT_EQ(to_int(-kInf), kMin);
  EXPECT_EQ(to_int(2147483520.0f), 2147483520);
  EXPECT_EQ(to_int(-2147483648.0f), kMin);
  auto to_float = [](int32_t i) {
    return fold1(Op::IntToFloat, ir::float_type(1), {Constant::of_int(i)}).bits[0];
  };
  EXPECT_EQ(to_float(16777217), fbits(16777216.0f));
  EXPECT_EQ(to_float(kMax), fbits(2147483648.0f));
  EXPECT_EQ(fold1(Op::FloatBitsToInt, ir::int_type(1), {Constant::of_float(-0.0f)}).i(0), kMin);
  EXPECT_EQ(fold1(Op::IntBitsToFloat, ir::float_type(1), {Constant::of_int(0x7fc12345)}).bits[0],
            0x7fc12345u);
  auto cmp = [](Op op, float a, float b) {
    return fold1(op, ir::bool_type(1), {Constant::of_float(a), Constant::of_float(b)}).b(0);
  };
  EXPECT_FALSE(cmp(Op::Lt, kNaN, 1.0f));
  EXPECT_FALSE(cmp(Op::Ge, kNaN, 1.0f));
  EXPECT_FALSE(cmp(Op::Eq, kNaN, kNaN));
  EXPECT_TRUE(cmp(Op::Ne, kNaN, kNaN));
  EXPECT_TRUE(cmp(Op::Eq, -0.0f, 0.0f));
  EXPECT_FALSE(cmp(Op::Lt, -0.0f, 0.0f));
  EXPECT_TRUE(cmp(Op::Le, -kInf, -3e38f));
}

TEST(ConstantFold, VectorsFoldComponentwiseAndBroadcast) {
  Constant v;
  v.type = ir::float_type(3);
  v.bits = {fbits(1.0f), fbits(2.0f), fbits(3.0f), 0};
  Constant r = fold1(Op::Mul, ir::float_type(3), {v, Constant::of_float(0.5f)});
  EXPECT_EQ(r.type, ir::float_type(3));
  EXPECT_EQ(r.f(0), 0.5f);
  EXPECT_EQ(r.f(2), 1.5f);
  Constant c;
  c.type = ir::bool_type(3);
  c.bits = {1, 0, 1, 0};
  Constant s = fold1(Op::Select, ir::float_type(3), {c, v, Constant::of_float(-1.0f)});
  EXPECT_EQ(s.f(0), 1.0f);
  EXPECT_EQ(s.f(1), -1.0f);
  EXPECT_EQ(s.f(2), 3.0f);
  // dot is the sum of products in component order, each rounded to binary32.
  Constant a, b;
  a.type = b.type = ir::float_type(3);
  a.bits = {fbits(1e8f), fbits(1.0f), fbits(-1e8f), 0};
  b.bits = {fbits(1.0f), fbits(1.0f), fbits(1.0f), 0};
  EXPECT_EQ(fold1(Op::Dot, ir::float_type(1), {a, b}).f(0), 0.0f);  // binary64 would say 1
  Constant e = fold1(Op::Construct, ir::float_type(4), {v, Constant::of_float(4.0f)});
  EXPECT_EQ(e.f(3), 4.0f);
  EXPECT_EQ(e.f(1), 2.0f);
}

TEST(ConstantFold, TranscendentalsAreNeverFolded) {
  for (Op op : {Op::Exp, Op::Log, Op::Exp2, Op::Log2, Op::Sin, Op::Cos, Op::Tan, Op::Atan}) {
    EXPECT_FALSE(passes::fold(op, ir::float_type(1), {Constant::of_float(0.5f)}).has_value())
        << ir::op_name(op);
  }
  for (Op op : {Op::Pow, Op::Atan2})
    EXPECT_FALSE(
        passes::fold(op, ir::float_type(1), {Constant::of_float(0.5f), Constant::of_float(2.0f)})
            .has_value())
        << ir::op_name(op);
  EXPECT_FALSE(passes::fold(Op::ElementIndex, ir::int_type(1), {}).has_value());

  Float k = 0.5f;  // made outside: an inline constant
  Program p = program("transcendental", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + exp(k) + log(k) + exp2(k) + log2(k) + sin(k) + cos(k) + tan(k) + atan(k) + pow(k, k) +
        atan2(k, k);
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::constant_fold(g); });
  for (Op op : {Op::Exp, Op::Log, Op::Exp2, Op::Log2, Op::Sin, Op::Cos, Op::Tan, Op::Atan, Op::Pow,
                Op::Atan2})
    EXPECT_EQ(count_ops(f, op), 1) << ir::op_name(op);
  // In fast mode they reach the backend as they are (strict mode replaces them by Rill's own
  // routines first, see OptimizerTest).
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Fast);
  EXPECT_EQ(count_ops(o, Op::Sin), 1);
  EXPECT_EQ(count_ops(o, Op::Pow), 1);
}

// ---- the pass on programs --------------------------------------------------------------------

TEST(ConstantFold, FoldsOperationsOnConstants) {
  // Made outside any program: inline constants, which constant_fold sees on its own.
  Float a = 0.1f, b = 0.2f, two = 2.0f;
  Int i = kMax, one = 1;
  Program p = program("fold", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float c = a + b;
    Int j = i + one;
    y = x * c + to_float(j) + sqrt(two);
  });
  ir::Function f = test::after(p, [](ir::Function& g) { EXPECT_TRUE(passes::constant_fold(g)); });
  std::string text = normalized(ir::print(f));
  EXPECT_LINE(text, "t# = copy(0.3)");
  EXPECT_LINE(text, "t# = copy(-2147483648)");
  EXPECT_LINE(text, "t# = copy(1.4142135)");
  EXPECT_EQ(count_ops(f, Op::Add), count_ops(p.ir(), Op::Add) - 2);  // a + b, i + 1
  EXPECT_EQ(test::statements(f), test::statements(p.ir()));          // folded in place, as copies
  // With the other passes the constants flow into their uses and fold further.
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  std::string opt = normalized(ir::print(o));
  EXPECT_LINE(opt, "t# = mul(x_0, 0.3)");
  EXPECT_LINE(opt, "t# = add(t#, -2147483648.0)");
  EXPECT_LINE(opt, "t# = add(t#, 1.4142135)");
  EXPECT_EQ(test::statements(o), 4) << opt;
}

TEST(ConstantFold, NothingToFoldReportsNoChange) {
  Program p = program("nothing", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * x;
  });
  ir::Function f = p.ir();
  EXPECT_FALSE(passes::constant_fold(f));
  EXPECT_EQ(ir::print(f), p.print());
}

TEST(ConstantFold, ExactIdentitiesForIntsAndBools) {
  Int zero = 0, one = 1;
  Bool yes = true, no = false;
  Program p = program("identities", [&] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> y("y");
    Bool b = n < m;
    Int r = (n + zero) * one + (zero + m) - zero;
    r = (r | zero) ^ zero;
    r = (r << zero) >> zero;
    r = one * r;
    Bool c = (b && yes) || no;
    Bool d = (b && no) || (b || yes);
    y = select(c, r, n) + select(d, one, zero) + select(yes, n, m);
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::constant_fold(g); });
  // What remains: add(t, t) in r, the outer or() in d (both operands are variables until
  // copy propagation), the two adds of y.
  const std::vector<std::pair<Op, int>> expected = {
      {Op::Add, 3}, {Op::Sub, 0}, {Op::Mul, 0}, {Op::BitOr, 0}, {Op::BitXor, 0},
      {Op::Shl, 0}, {Op::Shr, 0}, {Op::And, 0}, {Op::Or, 1},    {Op::Select, 2}};
  for (auto [op, n] : expected)
    EXPECT_EQ(count_ops(f, op), n) << ir::op_name(op) << "\n" << ir::print(f);
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(count_ops(o, Op::Or), 0) << ir::print(o);      // b || true is true
  EXPECT_EQ(count_ops(o, Op::Select), 1) << ir::print(o);  // select(true, 1, 0) is 1
}

TEST(ConstantFold, FloatIdentitiesThatAreNotExactStay) {
  Float zero = 0.0f, one = 1.0f;
  Program p = program("float_identities", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = (x + zero) * one - zero;  // x + 0 turns -0 into +0: not an identity
  });
  ir::Function f = test::after(p, [](ir::Function& g) { passes::constant_fold(g); });
  EXPECT_EQ(count_ops(f, Op::Add), 1);
  EXPECT_EQ(count_ops(f, Op::Mul), 1);
  EXPECT_EQ(count_ops(f, Op::Sub), 1);
}

TEST(ConstantFold, ConstantBranchesAreResolved) {
  Program p = program("branches", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_IF(true) {
      y = y * x;
    }
    RILL_ENDIF;
    RILL_IF(false) {
      y = y + x;
    }
    RILL_ELSE {
      y = y - x;
    }
    RILL_ENDIF;
    RILL_IF(false) {
      y = y / x;
    }
    RILL_ENDIF;
    RILL_WHILE(false) {
      y = -y;
    }
    RILL_ENDWHILE;
    RILL_DO {
      y = y * 0.5f;
    }
    RILL_UNTIL(true);  // runs once: kept
  });
  ir::Function f = test::after(p, [](ir::Function& g) { EXPECT_TRUE(passes::constant_fold(g)); });
  EXPECT_EQ(test::count_kind(f, ir::StmtKind::If), 0) << ir::print(f);
  EXPECT_EQ(ir::count_loops(f.body), 1);
  EXPECT_EQ(count_ops(f, Op::Mul), 2);
  EXPECT_EQ(count_ops(f, Op::Add), 0);
  EXPECT_EQ(count_ops(f, Op::Sub), 1);
  EXPECT_EQ(count_ops(f, Op::Div), 0);
  EXPECT_EQ(count_ops(f, Op::Neg), 0);
}

TEST(ConstantFold, DoubleAccuracyDoesNotFoldFloatArithmetic) {
  Float a = 0.1f, b = 0.2f;
  Float3 u(1e8f, 1.0f, -1e8f), v(1.0f);
  Int i = 20, j = 22;
  Bool t = true;
  Program p = program("double", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> n("n");
    Float s = a + b;
    Float d = dot(u, v);
    Float c = to_float(i);
    n = i + j;
    y = x + s + d + c + select(t, a, b);
  });
  ir::Function dbl =
      test::after(p, [](ir::Function& g) { passes::constant_fold(g, Accuracy::Double); });
  EXPECT_EQ(count_ops(dbl, Op::Dot), 1);
  EXPECT_EQ(count_ops(dbl, Op::IntToFloat), 1);
  EXPECT_EQ(count_ops(dbl, Op::Add), count_ops(p.ir(), Op::Add) - 1);  // only i + j
  EXPECT_EQ(count_ops(dbl, Op::Select), 0);  // data movement is exact in any mode
  ir::Function strict = test::after(p, [](ir::Function& g) { passes::constant_fold(g); });
  EXPECT_EQ(count_ops(strict, Op::Dot), 0);
  EXPECT_EQ(count_ops(strict, Op::IntToFloat), 0);
  EXPECT_EQ(count_ops(strict, Op::Add), count_ops(p.ir(), Op::Add) - 2);
}

// ---- against the CPU backend -----------------------------------------------------------------

// Every pair of these, through every op.
const std::vector<float> kFloatCases = {0.0f,
                                        -0.0f,
                                        1.0f,
                                        -1.0f,
                                        0.1f,
                                        0.2f,
                                        1.0f / 3.0f,
                                        2.0f,
                                        -2.5f,
                                        5.5f,
                                        1e8f,
                                        16777216.0f,
                                        3e38f,
                                        -3e38f,
                                        1e-38f,
                                        1e-3f,
                                        kDenorm,
                                        -kDenorm,
                                        std::numeric_limits<float>::min(),
                                        kInf,
                                        -kInf,
                                        kNaN,
                                        std::bit_cast<float>(0x7fc12345u),
                                        std::bit_cast<float>(0xffc54321u)};

const std::vector<Op> kFloatOps = {Op::Add, Op::Sub,  Op::Mul,   Op::Div,   Op::Mod,  Op::Min,
                                   Op::Max, Op::Sqrt, Op::Rsqrt, Op::Floor, Op::Ceil, Op::Fract,
                                   Op::Abs, Op::Sign, Op::Neg,   Op::Trunc};

Float apply(Op op, const Float& a, const Float& b) {
  switch (op) {
    case Op::Add:
      return a + b;
    case Op::Sub:
      return a - b;
    case Op::Mul:
      return a * b;
    case Op::Div:
      return a / b;
    case Op::Mod:
      return mod(a, b);
    case Op::Min:
      return min(a, b);
    case Op::Max:
      return max(a, b);
    case Op::Sqrt:
      return sqrt(a);
    case Op::Rsqrt:
      return rsqrt(a);
    case Op::Floor:
      return floor(a);
    case Op::Ceil:
      return ceil(a);
    case Op::Trunc:
      return trunc(a);
    case Op::Fract:
      return fract(a);
    case Op::Abs:
      return abs(a);
    case Op::Sign:
      return sign(a);
    case Op::Neg:
      return -a;
    default:
      throw std::logic_error("op");
  }
}

// y = op_k(a, b) where k is the element's op input; the kernel computes at run time.
template <class T, class Apply>
Program op_table(const char* name, const std::vector<Op>& ops, Apply&& apply_op) {
  return program(name, [&] {
    Input<Int> k("k");
    Input<Value<T, 1>> a("a");
    Input<Value<T, 1>> b("b");
    Output<Value<T, 1>> y("y");
    y = a;
    for (size_t i = 0; i < ops.size(); ++i) {
      RILL_IF(k == static_cast<int>(i)) {
        y = apply_op(ops[i], a, b);
      }
      RILL_ENDIF;
    }
  });
}

TEST(ConstantFoldCpu, FloatFoldingMatchesTheBackendBitForBit) {
  Program p = op_table<float>("float_ops", kFloatOps, apply);
  std::vector<int32_t> ks;
  std::vector<float> as, bs;
  for (size_t k = 0; k < kFloatOps.size(); ++k)
    for (float a : kFloatCases)
      for (float b : kFloatCases) {
        ks.push_back(static_cast<int32_t>(k));
        as.push_back(a);
        bs.push_back(b);
      }
  auto out = test::run_cpu<Float, Int, Float, Float>(p, {}, ks, as, bs);
  int mismatches = 0;
  for (size_t e = 0; e < out.size(); ++e) {
    Op op = kFloatOps[static_cast<size_t>(ks[e])];
    uint32_t folded = ffold(op, as[e], bs[e]);
    // Any NaN matches any NaN: a NaN's sign and payload are not specified, and the C
    // compiler decides them (clang may swap a commutative add's two NaN operands).
    const bool both_nan = std::isnan(std::bit_cast<float>(folded)) && std::isnan(out[e]);
    if (folded != fbits(out[e]) && !both_nan && ++mismatches <= 10)
      ADD_FAILURE() << ir::op_name(op) << "(" << std::hex << fbits(as[e]) << ", " << fbits(bs[e])
                    << "): folded 0x" << folded << ", backend 0x" << fbits(out[e]);
  }
  EXPECT_EQ(mismatches, 0);
}

const std::vector<int32_t> kIntCases = {0,  1,  -1,    2,       -2,   3,    -7,       31,
                                        32, 33, 65536, 1 << 30, kMax, kMin, kMax - 1, kMin + 1};
const std::vector<Op> kIntOps = {Op::Add,    Op::Sub,   Op::Mul,    Op::Div,   Op::Mod, Op::Min,
                                 Op::Max,    Op::Abs,   Op::Sign,   Op::Neg,   Op::Shl, Op::Shr,
                                 Op::BitAnd, Op::BitOr, Op::BitXor, Op::BitNot, Op::ShrU,
                                 Op::MulHiU};

Int apply_int(Op op, const Int& a, const Int& b) {
  switch (op) {
    case Op::Add:
      return a + b;
    case Op::Sub:
      return a - b;
    case Op::Mul:
      return a * b;
    case Op::Div:
      return a / b;
    case Op::Mod:
      return a % b;
    case Op::Min:
      return min(a, b);
    case Op::Max:
      return max(a, b);
    case Op::Abs:
      return abs(a);
    case Op::Sign:
      return sign(a);
    case Op::Neg:
      return -a;
    case Op::Shl:
      return a << b;
    case Op::Shr:
      return a >> b;
    case Op::BitAnd:
      return a & b;
    case Op::BitOr:
      return a | b;
    case Op::BitXor:
      return a ^ b;
    case Op::BitNot:
      return ~a;
    case Op::ShrU:
      return shr_logical(a, b);
    case Op::MulHiU:
      return mul_hi_unsigned(a, b);
    default:
      throw std::logic_error("op");
  }
}

TEST(ConstantFoldCpu, IntFoldingMatchesTheBackend) {
  Program p = op_table<int32_t>("int_ops", kIntOps, apply_int);
  std::vector<int32_t> ks, as, bs;
  for (size_t k = 0; k < kIntOps.size(); ++k)
    for (int32_t a : kIntCases)
      for (int32_t b : kIntCases) {
        ks.push_back(static_cast<int32_t>(k));
        as.push_back(a);
        bs.push_back(b);
      }
  auto out = test::run_cpu<Int, Int, Int, Int>(p, {}, ks, as, bs);
  int mismatches = 0;
  for (size_t e = 0; e < out.size(); ++e) {
    Op op = kIntOps[static_cast<size_t>(ks[e])];
    int32_t folded = ifold(op, as[e], bs[e]);
    if (folded != out[e] && ++mismatches <= 10)
      ADD_FAILURE() << ir::op_name(op) << "(" << as[e] << ", " << bs[e] << "): folded " << folded
                    << ", backend " << out[e];
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(ConstantFoldCpu, ConversionsAndComparisonsMatchTheBackend) {
  const std::vector<Op> ops = {
      Op::FloatToInt, Op::FloatBitsToInt, Op::Lt, Op::Le, Op::Gt, Op::Ge, Op::Eq, Op::Ne};
  Program p = program("convert", [&] {
    Input<Int> k("k");
    Input<Float> a("a");
    Input<Float> b("b");
    Output<Int> y("y");
    Int one = 1, zero = 0;
    y = -5;
    RILL_IF(k == 0) {
      y = to_int(a);
    }
    RILL_ELSE_IF(k == 1) {
      y = as_int(a);
    }
    RILL_ELSE_IF(k == 2) {
      y = select(a < b, one, zero);
    }
    RILL_ELSE_IF(k == 3) {
      y = select(a <= b, one, zero);
    }
    RILL_ELSE_IF(k == 4) {
      y = select(a > b, one, zero);
    }
    RILL_ELSE_IF(k == 5) {
      y = select(a >= b, one, zero);
    }
    RILL_ELSE_IF(k == 6) {
      y = select(a == b, one, zero);
    }
    RILL_ELSE {
      y = select(a != b, one, zero);
    }
    RILL_ENDIF;
  });
  std::vector<float> cases = kFloatCases;
  for (float f : {2.7f, -2.7f, 3e9f, -3e9f, 2147483520.0f, -2147483648.0f, 2147483648.0f})
    cases.push_back(f);
  std::vector<int32_t> ks;
  std::vector<float> as, bs;
  for (size_t k = 0; k < ops.size(); ++k)
    for (float a : cases)
      for (float b : cases) {
        ks.push_back(static_cast<int32_t>(k));
        as.push_back(a);
        bs.push_back(b);
      }
  auto out = test::run_cpu<Int, Int, Float, Float>(p, {}, ks, as, bs);
  int mismatches = 0;
  for (size_t e = 0; e < out.size(); ++e) {
    Op op = ops[static_cast<size_t>(ks[e])];
    bool compare = ks[e] >= 2;
    Constant r = compare ? fold1(op, ir::bool_type(1),
                                 {Constant::of_float(as[e]), Constant::of_float(bs[e])})
                         : fold1(op, ir::int_type(1), {Constant::of_float(as[e])});
    if (r.i(0) != out[e] && ++mismatches <= 10)
      ADD_FAILURE() << ir::op_name(op) << "(" << as[e] << ", " << bs[e] << "): folded " << r.i(0)
                    << ", backend " << out[e];
  }
  EXPECT_EQ(mismatches, 0);

  // And int -> float.
  Program q = program("to_float", [] {
    Input<Int> n("n");
    Output<Float> y("y");
    y = to_float(n);
  });
  std::vector<int32_t> ns = kIntCases;
  for (int32_t n : {16777217, -16777217, 16777219, 123456789}) ns.push_back(n);
  auto fl = test::run_cpu<Float, Int>(q, {}, ns);
  for (size_t e = 0; e < ns.size(); ++e)
    EXPECT_EQ(fold1(Op::IntToFloat, ir::float_type(1), {Constant::of_int(ns[e])}).bits[0],
              fbits(fl[e]))
        << ns[e];
}

TEST(ConstantFoldCpu, DotAndCrossMatchTheBackend) {
  Program p = program("geometry", [] {
    Input<Float3> a("a");
    Input<Float3> b("b");
    Output<Float4> y("y");
    y = Float4(cross(a, b), dot(a, b));
  });
  std::vector<glm::vec3> as{{1e8f, 1.0f, -1e8f}, {1.0f + 1.0f / 8192, 1.0f, 0.0f}, {1, 2, 3}},
      bs{{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f - 1.0f / 8192, 0.0f}, {0.1f, 0.2f, 0.3f}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> d(-1000.0f, 1000.0f);
  for (int k = 0; k < 500; ++k) {
    as.emplace_back(d(rng), d(rng), d(rng));
    bs.emplace_back(d(rng), d(rng), d(rng));
  }
  auto out = test::run_cpu<Float4, Float3, Float3>(p, {}, as, bs);
  auto c3 = [](const glm::vec3& v) {
    Constant c;
    c.type = ir::float_type(3);
    for (int i = 0; i < 3; ++i) c.bits[static_cast<size_t>(i)] = fbits(v[i]);
    return c;
  };
  for (size_t e = 0; e < as.size(); ++e) {
    Constant cr = fold1(Op::Cross, ir::float_type(3), {c3(as[e]), c3(bs[e])});
    Constant dt = fold1(Op::Dot, ir::float_type(1), {c3(as[e]), c3(bs[e])});
    for (int i = 0; i < 3; ++i)
      ASSERT_EQ(cr.bits[static_cast<size_t>(i)], fbits(out[e][i])) << "cross, case " << e;
    ASSERT_EQ(dt.bits[0], fbits(out[e][3])) << "dot, case " << e;
  }
  EXPECT_EQ(out[0][3], 0.0f);  // binary32 all the way: 1e8 + 1 - 1e8 = 0
}

// The same constant expressions, folded (all passes) and left to the backend (no folding):
// identical bits, NaNs included.
TEST(ConstantFoldCpu, FoldedProgramsComputeWhatUnfoldedOnesDo) {
  Float a = 0.1f, b = 0.2f, third = 3.0f, two = 2.0f, tiny = 1e-38f, milli = 1e-3f;
  Float zero = 0.0f, inf = kInf, minus_one = -1.0f;
  Float3 u(1e8f, 1.0f, -1e8f), v(1.0f);
  Int big = kMax, z = 0;
  Program p = program("consts", [&] {
    Input<Float> x("x");
    Output<Float4> y("y");
    Float s = (a + b) * x;
    Float q = 1.0f / third + sqrt(two) + tiny * milli + dot(u, v);
    Int i = (big + 1) / z + (big * 2) % z + (big + 7);
    Float n = as_float(as_int(zero / zero) + as_int(inf - inf) + as_int(sqrt(minus_one)));
    y = Float4(s, q, to_float(i) + n,
               fract(Float(-1e-30f)) + mod(Float(-5.5f), Float(2.0f)) + zero * inf);
  });
  CompileOptions fold_on, fold_off;
  fold_off.passes.constant_folding = false;
  std::vector<float> xs{1.0f, -0.0f, 3.0f};
  auto on = test::run_cpu<Float4, Float>(p, fold_on, xs);
  auto off = test::run_cpu<Float4, Float>(p, fold_off, xs);
  EXPECT_SAME_BITS(test::bits_of(on), test::bits_of(off));
  EXPECT_EQ(on[0][0], 0.3f);
  Kernel k = compile(p, "cpu", fold_on);
  EXPECT_EQ(test::count_occurrences(k.ir(), " = dot("), 0) << k.ir();
  EXPECT_EQ(test::count_occurrences(k.ir(), " = div("), 0) << k.ir();
}

// Accuracy::Double does not fold float arithmetic: the backend computes it in binary64.
TEST(ConstantFoldCpu, DoubleModeLeavesFloatConstantsToTheBackend) {
  Float3 u(1e8f, 1.0f, -1e8f), v(1.0f);
  Float a = 0.1f, b = 0.2f;
  Program p = program("double_consts", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> z("z");
    y = x + dot(u, v);
    z = x + (a + b);
  });
  CompileOptions dbl;
  dbl.accuracy = Accuracy::Double;
  Kernel k = compile(p, "cpu", dbl);
  EXPECT_EQ(test::count_occurrences(k.ir(), " = dot("), 1) << k.ir();
  EXPECT_EQ(test::count_occurrences(k.ir(), " = add(0.1, 0.2)"), 1) << k.ir();
  Stream<Float> x(std::vector<float>{0.0f});
  Stream<Float> y(1), z(1);
  k.inputs(x).outputs(y, z).execute();
  // 1e8 + 1 - 1e8 is 1 in binary64 (0 in binary32); 0.1 + 0.2 in binary64, then rounded.
  const std::string& src = k.source();
  EXPECT_EQ(y.download()[0], 1.0f) << src.substr(src.find("int64_t rill_run"));
  EXPECT_EQ(z.download()[0], static_cast<float>(static_cast<double>(0.1f) + 0.2f));
}

TEST(ConstantFoldCpu, PreservesResults) {
  Float k = 0.75f;
  Int m = 12;
  Program p = program("fold_mix", [&] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Float c = k * 4.0f - 1.0f;  // 2
    Int j = m / 4 + (m << 1);   // 27
    Float t = x * c + to_float(n % j) + floor(k) - ceil(-k) + abs(-k);
    RILL_IF(c > 1.0f) {
      t = t * 0.5f;
    }  // always taken
    RILL_ELSE {
      t = -t;
    }
    RILL_ENDIF;
    y = select(j > 20, t, x) + min(x, c) + max(k, x) + (x + 0.0f);
  });
  auto xs = test::random_floats(3000, 11);
  auto ns = test::random_ints(3000, 12);
  test::expect_passes_preserve_results<Float, Float, Int>(p, xs, ns);
  ir::Function o = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(test::count_kind(o, ir::StmtKind::If), 0) << ir::print(o);
}

}  // namespace
}  // namespace rill
