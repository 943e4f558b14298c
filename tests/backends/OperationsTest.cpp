// Every DSL operation against a C++ reference, over a seeded sweep of inputs that includes
// the hard values (signed zeros, denormals, infinities, NaN, extremes).
//
// Each operation runs as one kernel over 4-vectors with outputs at every width (scalar,
// Float2, Float3, Float4), broadcasts (vector op scalar, scalar op vector) and host-scalar
// operands, so one compile covers all the forms. Exactly specified operations compare bit
// for bit (any NaN matches any NaN); transcendental ones within a few ulp of a
// double-precision reference.
//
// The Constants* tests evaluate the operations on constant operands, once with constant
// folding (the optimizer computes them) and once without (the backend computes them from
// literals in its generated code): both must agree with the reference too.
#include "BackendTest.h"

namespace rill::testing {
namespace {

using F4 = glm::vec4;
using I4 = glm::ivec4;
using L = std::numeric_limits<float>;

// ---- references -----------------------------------------------------------------------------

float ref_min(float a, float b) {
  return b < a ? b : a;
}
float ref_max(float a, float b) {
  return a < b ? b : a;
}
float ref_sign(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}
float ref_abs(float x) {
  return float_of(bits_of(x) & 0x7fffffffu);
}
float ref_fract(float x) {
  float f = std::floor(x);
  return x - f;
}
float ref_mod(float a, float b) {
  float q = a / b;
  float f = std::floor(q);
  float m = b * f;
  return a - m;
}
// rsqrt is specified as 1 / sqrt(x), two correctly rounded operations (the optimizer folds
// it that way), so it is exact too.
float ref_rsqrt(float x) {
  float s = std::sqrt(x);
  return 1.0f / s;
}
float ref_select(float a, float b) {
  return a < b ? b - a : a * b;
}
int32_t wrap(int64_t v) {
  return static_cast<int32_t>(static_cast<uint32_t>(v));
}
int32_t ref_idiv(int32_t a, int32_t b) {
  if (b == 0) return 0;
  return wrap(int64_t{a} / b);
}
int32_t ref_irem(int32_t a, int32_t b) {
  if (b == 0) return 0;
  return static_cast<int32_t>(int64_t{a} % b);
}
int32_t ref_shl(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) << (b & 31));
}
int32_t ref_shr(int32_t a, int32_t b) {
  return a >> (b & 31);
}
int32_t ref_shr_logical(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) >> (b & 31));
}
int32_t ref_mul_hi_unsigned(int32_t a, int32_t b) {
  const uint64_t p = uint64_t{static_cast<uint32_t>(a)} * static_cast<uint32_t>(b);
  return static_cast<int32_t>(static_cast<uint32_t>(p >> 32));
}
float ref_unit_float(int32_t x) {
  return static_cast<float>(static_cast<uint32_t>(x) >> 8) / 16777216.0f;
}
int32_t ref_to_int(float x) {
  if (std::isnan(x)) return 0;
  if (x >= 2147483648.0f) return std::numeric_limits<int32_t>::max();
  if (x < -2147483648.0f) return std::numeric_limits<int32_t>::min();
  return static_cast<int32_t>(x);
}
// as_int with NaN mapped to one pattern: a backend may change a NaN's payload on the way in.
int32_t ref_as_int(float x) {
  return std::isnan(x) ? 0x7fc00000 : std::bit_cast<int32_t>(x);
}
template <class T>
int32_t ref_compare_bits(T a, T b) {
  return int32_t{a < b} | int32_t{a <= b} << 1 | int32_t{a > b} << 2 | int32_t{a >= b} << 3 |
         int32_t{a == b} << 4 | int32_t{a != b} << 5;
}

// Bool results travel through Int streams.
template <int N>
Value<int32_t, N> to01(const Value<bool, N>& b) {
  return select(b, Value<int32_t, N>(1), Value<int32_t, N>(0));
}

// A host operand as a DSL value (a DSL value as itself).
template <class A>
auto dsl(const A& a) {
  if constexpr (std::is_arithmetic_v<A>)
    return Value<A, 1>(a);
  else
    return Value<typename A::scalar_type, A::width>(a);
}

// ---- the operations, as generic lambdas (any width, host scalars where the DSL has them) ----

constexpr auto op_add = [](const auto& a, const auto& b) { return a + b; };
constexpr auto op_sub = [](const auto& a, const auto& b) { return a - b; };
constexpr auto op_mul = [](const auto& a, const auto& b) { return a * b; };
constexpr auto op_div = [](const auto& a, const auto& b) { return a / b; };
constexpr auto op_rem = [](const auto& a, const auto& b) { return a % b; };
constexpr auto op_min = [](const auto& a, const auto& b) { return min(a, b); };
constexpr auto op_max = [](const auto& a, const auto& b) { return max(a, b); };
constexpr auto op_mod = [](const auto& a, const auto& b) { return mod(a, b); };
constexpr auto op_pow = [](const auto& a, const auto& b) { return pow(a, b); };
constexpr auto op_atan2 = [](const auto& a, const auto& b) { return atan2(a, b); };
constexpr auto op_and = [](const auto& a, const auto& b) { return a & b; };
constexpr auto op_or = [](const auto& a, const auto& b) { return a | b; };
constexpr auto op_xor = [](const auto& a, const auto& b) { return a ^ b; };
constexpr auto op_shl = [](const auto& a, const auto& b) { return a << b; };
constexpr auto op_shr = [](const auto& a, const auto& b) { return a >> b; };
constexpr auto op_shr_logical = [](const auto& a, const auto& b) { return shr_logical(a, b); };
constexpr auto op_mul_hi_unsigned = [](const auto& a, const auto& b) {
  return mul_hi_unsigned(a, b);
};
constexpr auto op_select = [](const auto& a, const auto& b) { return select(a < b, b - a, a * b); };
// All six comparisons in one result: bit k is comparison k.
constexpr auto op_compare = [](const auto& a, const auto& b) {
  return to01(a < b) | (to01(a <= b) << 1) | (to01(a > b) << 2) | (to01(a >= b) << 3) |
         (to01(a == b) << 4) | (to01(a != b) << 5);
};
constexpr auto op_neg = [](const auto& x) { return -x; };
constexpr auto op_plus = [](const auto& x) { return +x; };
constexpr auto op_abs = [](const auto& x) { return abs(x); };
constexpr auto op_sign = [](const auto& x) { return sign(x); };
constexpr auto op_floor = [](const auto& x) { return floor(x); };
constexpr auto op_trunc = [](const auto& x) { return trunc(x); };
constexpr auto op_ceil = [](const auto& x) { return ceil(x); };
constexpr auto op_fract = [](const auto& x) { return fract(x); };
constexpr auto op_sqrt = [](const auto& x) { return sqrt(x); };
constexpr auto op_rsqrt = [](const auto& x) { return rsqrt(x); };
constexpr auto op_exp = [](const auto& x) { return exp(x); };
constexpr auto op_exp2 = [](const auto& x) { return exp2(x); };
constexpr auto op_log = [](const auto& x) { return log(x); };
constexpr auto op_log2 = [](const auto& x) { return log2(x); };
constexpr auto op_sin = [](const auto& x) { return sin(x); };
constexpr auto op_cos = [](const auto& x) { return cos(x); };
constexpr auto op_tan = [](const auto& x) { return tan(x); };
constexpr auto op_atan = [](const auto& x) { return atan(x); };
constexpr auto op_bitnot = [](const auto& x) { return ~x; };
constexpr auto op_to_int = [](const auto& x) { return to_int(x); };
constexpr auto op_to_float = [](const auto& x) { return to_float(x); };
constexpr auto op_as_float = [](const auto& x) { return as_float(x); };
constexpr auto op_unit_float = [](const auto& x) { return unit_float(x); };
constexpr auto op_as_int = [](const auto& x) {
  using I = Value<int32_t, std::remove_cvref_t<decltype(x)>::width>;
  return select(x != x, I(0x7fc00000), as_int(x));
};

// ---- the checker ----------------------------------------------------------------------------

// How results compare: bit for bit (ulps == 0), or within `ulps` of a double reference.
struct Tolerance {
  int64_t ulps = 0;
};

template <class R, class E>
::testing::AssertionResult compare(const std::vector<R>& got, const std::vector<E>& want,
                                   Tolerance tol, const Describe& d, int width) {
  if constexpr (std::is_same_v<E, double>) {
    return within_ulps(got, want, tol.ulps, d, width);
  } else {
    return bits_equal(got, want, d, width);
  }
}

// Which forms a kernel exercises: all of them, or (for operations that expand to long
// routines) only scalars and 4-vectors, which still see every input.
enum class Forms { All, Light };

class OperationsTest : public BackendTest {
 protected:
  // A componentwise unary operation on T over the sweep `xs`, at every vector width.
  // (Swizzles keep components in order here; VectorTest covers reordering reads.)
  template <class T, class Op, class Ref>
  void check_unary(const std::string& name, Op op, Ref ref, const std::vector<T>& xs,
                   Tolerance tol = {}, Forms forms = Forms::All) {
    HostFlushScope flush_like_backend(flushes_denormals());  // references follow the backend's rule
    using V4 = Value<T, 4>;
    using RS = typename decltype(op(std::declval<const V4&>()))::scalar_type;
    using E = decltype(ref(T{}));
    auto xv = as_vec4(xs);
    Program p = program(name, [&] {
      Input<V4> x("x");
      Output<Value<RS, 1>> o1("o1");
      Output<Value<RS, 2>> o2("o2");
      Output<Value<RS, 3>> o3("o3");
      Output<Value<RS, 4>> o4("o4");
      o1 = op(x.w());
      o4 = op(x);
      if (forms == Forms::All) {
        o2 = op(x(1, 2));
        o3 = op(x(0, 2, 3));
      } else {
        o2 = Value<RS, 2>(RS{});
        o3 = Value<RS, 3>(RS{});
      }
    });
    auto [r1, r2, r3, r4] = run<Value<RS, 1>, Value<RS, 2>, Value<RS, 3>, Value<RS, 4>>(p, xv);
    std::vector<E> e1, e2, e3, e4;
    for (const auto& v : xv) {
      e1.push_back(ref(v.w));
      for (int c : {1, 2}) e2.push_back(ref(v[c]));
      for (int c : {0, 2, 3}) e3.push_back(ref(v[c]));
      for (int c = 0; c < 4; ++c) e4.push_back(ref(v[c]));
    }
    Describe d = describe_inputs(xv);
    EXPECT_TRUE(compare(flatten(r1), e1, tol, d, 1)) << name << ": scalar (x.w)";
    EXPECT_TRUE(compare(flatten(r4), e4, tol, d, 4)) << name << ": 4-vector";
    if (forms == Forms::Light) return;
    EXPECT_TRUE(compare(flatten(r2), e2, tol, d, 2)) << name << ": 2-vector (x.yz)";
    EXPECT_TRUE(compare(flatten(r3), e3, tol, d, 3)) << name << ": 3-vector (x.xzw)";
  }

  // A componentwise binary operation on T over the sweep pairs (as, bs) at every width, with
  // broadcasts; hl and hr are host scalars used as left and right operands.
  template <class T, class Op, class Ref>
  void check_binary(const std::string& name, Op op, Ref ref, const std::vector<T>& as,
                    const std::vector<T>& bs, T hl, T hr, Tolerance tol = {},
                    Forms forms = Forms::All) {
    HostFlushScope flush_like_backend(flushes_denormals());  // references follow the backend's rule
    using V4 = Value<T, 4>;
    using RS =
        typename decltype(op(std::declval<const V4&>(), std::declval<const V4&>()))::scalar_type;
    using R4 = Value<RS, 4>;
    using E = decltype(ref(T{}, T{}));
    auto av = as_vec4(as), bv = as_vec4(bs);
    Program p = program(name, [&] {
      Input<V4> a("a");
      Input<V4> b("b");
      Output<Value<RS, 1>> o1("scalar");
      Output<Value<RS, 2>> o2("vec2");
      Output<Value<RS, 3>> o3("vec3");
      Output<R4> o4("vec4");
      Output<R4> o5("vec_scalar");
      Output<R4> o6("scalar_vec");
      Output<R4> o7("vec_host");
      Output<R4> o8("host_vec");
      o1 = op(a.x(), b.x());
      o4 = op(a, b);
      if (forms == Forms::All) {
        o2 = op(a(1, 2), b(2, 3));
        o3 = op(a(0, 1, 2), b(0, 1, 2));
        o5 = op(a, b.w());
        o6 = op(a.w(), b);
        o7 = op(a, hr);
        o8 = op(hl, b);
      } else {
        o2 = Value<RS, 2>(RS{});
        o3 = Value<RS, 3>(RS{});
        o5 = o6 = o7 = o8 = R4(RS{});
      }
    });
    auto [r1, r2, r3, r4, r5, r6, r7, r8] =
        run<Value<RS, 1>, Value<RS, 2>, Value<RS, 3>, R4, R4, R4, R4, R4>(p, av, bv);
    std::vector<E> e1, e2, e3, e4, e5, e6, e7, e8;
    for (size_t i = 0; i < av.size(); ++i) {
      const auto &x = av[i], &y = bv[i];
      e1.push_back(ref(x.x, y.x));
      e2.push_back(ref(x.y, y.z));
      e2.push_back(ref(x.z, y.w));
      for (int c = 0; c < 3; ++c) e3.push_back(ref(x[c], y[c]));
      for (int c = 0; c < 4; ++c) {
        e4.push_back(ref(x[c], y[c]));
        e5.push_back(ref(x[c], y.w));
        e6.push_back(ref(x.w, y[c]));
        e7.push_back(ref(x[c], hr));
        e8.push_back(ref(hl, y[c]));
      }
    }
    Describe d = describe_inputs(av, bv);
    EXPECT_TRUE(compare(flatten(r1), e1, tol, d, 1)) << name << ": scalar op scalar (a.x, b.x)";
    EXPECT_TRUE(compare(flatten(r4), e4, tol, d, 4)) << name << ": 4-vectors";
    if (forms == Forms::Light) return;
    EXPECT_TRUE(compare(flatten(r2), e2, tol, d, 2)) << name << ": 2-vectors (a.yz, b.zw)";
    EXPECT_TRUE(compare(flatten(r3), e3, tol, d, 3)) << name << ": 3-vectors";
    EXPECT_TRUE(compare(flatten(r5), e5, tol, d, 4)) << name << ": vector op scalar (a, b.w)";
    EXPECT_TRUE(compare(flatten(r6), e6, tol, d, 4)) << name << ": scalar op vector (a.w, b)";
    EXPECT_TRUE(compare(flatten(r7), e7, tol, d, 4)) << name << ": vector op host " << show(hr);
    EXPECT_TRUE(compare(flatten(r8), e8, tol, d, 4))
        << name << ": host " << show(hl) << " op vector";
  }

  void float_unary(const std::string& name, auto op, auto ref, Tolerance tol = {},
                   Forms forms = Forms::All) {
    check_unary<float>(name, op, ref, sweep_floats(11, 4096), tol, forms);
  }
  void float_binary(const std::string& name, auto op, auto ref, Tolerance tol = {},
                    Forms forms = Forms::All) {
    auto [a, b] = sweep_float_pairs(23, 4096);
    check_binary<float>(name, op, ref, a, b, 0.75f, -2.5f, tol, forms);
  }
  void int_unary(const std::string& name, auto op, auto ref) {
    check_unary<int32_t>(name, op, ref, sweep_ints(31, 4096));
  }
  void int_binary(const std::string& name, auto op, auto ref, int32_t hl = -7, int32_t hr = 33) {
    auto [a, b] = sweep_int_pairs(47, 4096);
    check_binary<int32_t>(name, op, ref, a, b, hl, hr);
  }

  // sin, cos and tan are specified within a few ulp while |x| < 6000 (their argument
  // reduction is exact there); for larger arguments only the range of the result is checked:
  // sin and cos within [-1, 1], tan not NaN.
  void float_trig(const std::string& name, auto op, double (*ref)(double), Tolerance tol,
                  bool bounded) {
    std::vector<float> xs = sweep_floats(11, 8192);
    std::mt19937 rng(12);
    std::uniform_real_distribution<float> d(-6000.0f, 6000.0f);
    for (int i = 0; i < 4096; ++i) xs.push_back(d(rng));
    auto xv = as_vec4(xs);
    Program p = program(name, [&] {
      Input<Float4> x("x");
      Output<Float> o1("o1");
      Output<Float4> o4("o4");
      o1 = op(x.w());
      o4 = op(x);
    });
    auto [r1, r4] = run<Float, Float4>(p, xv);
    auto in_range = [](float x) { return !std::isfinite(x) || std::fabs(x) < 6000.0f; };
    std::vector<float> got, far_x, far_y;
    std::vector<double> want;
    for (size_t i = 0; i < xv.size(); ++i)
      for (int c = 0; c < 5; ++c) {
        float x = c < 4 ? xv[i][c] : xv[i].w;
        float y = c < 4 ? r4[i][c] : r1[i];
        if (in_range(x)) {
          got.push_back(y);
          want.push_back(ref(x));
        } else if (std::isnan(y) || (bounded && !(std::fabs(y) <= 1.0f))) {
          far_x.push_back(x);
          far_y.push_back(y);
        }
      }
    EXPECT_TRUE(within_ulps(got, want, tol.ulps)) << name << " for |x| < 6000";
    EXPECT_TRUE(far_x.empty()) << name << " is out of range for " << far_x.size()
                               << " large finite arguments, e.g. " << name << "("
                               << show(far_x.empty() ? 0.0f : far_x[0])
                               << ") = " << show(far_y.empty() ? 0.0f : far_y[0]);
  }
};

// ---- float arithmetic (exact) ---------------------------------------------------------------

TEST_P(OperationsTest, FloatAdd) {
  float_binary("add", op_add, [](float a, float b) { return a + b; });
}
TEST_P(OperationsTest, FloatSub) {
  float_binary("sub", op_sub, [](float a, float b) { return a - b; });
}
TEST_P(OperationsTest, FloatMul) {
  float_binary("mul", op_mul, [](float a, float b) { return a * b; });
}
TEST_P(OperationsTest, FloatDiv) {
  float_binary("div", op_div, [](float a, float b) { return a / b; });
}
TEST_P(OperationsTest, FloatMin) {
  float_binary("min", op_min, ref_min);
}
TEST_P(OperationsTest, FloatMax) {
  float_binary("max", op_max, ref_max);
}
TEST_P(OperationsTest, FloatMod) {
  float_binary("mod", op_mod, ref_mod);
}
TEST_P(OperationsTest, FloatComparisons) {
  float_binary("fcmp", op_compare, ref_compare_bits<float>);
}
TEST_P(OperationsTest, FloatNeg) {
  float_unary("neg", op_neg, [](float x) { return -x; });
}
TEST_P(OperationsTest, FloatUnaryPlus) {
  float_unary("plus", op_plus, [](float x) { return x; });
}
TEST_P(OperationsTest, FloatAbs) {
  float_unary("abs", op_abs, ref_abs);
}
TEST_P(OperationsTest, FloatSign) {
  float_unary("sign", op_sign, ref_sign);
}
TEST_P(OperationsTest, Floor) {
  float_unary("floor", op_floor, [](float x) { return std::floor(x); });
}
TEST_P(OperationsTest, Trunc) {
  float_unary("trunc", op_trunc, [](float x) { return std::trunc(x); });
}
TEST_P(OperationsTest, Ceil) {
  float_unary("ceil", op_ceil, [](float x) { return std::ceil(x); });
}
TEST_P(OperationsTest, Fract) {
  float_unary("fract", op_fract, ref_fract);
}
TEST_P(OperationsTest, Sqrt) {
  float_unary("sqrt", op_sqrt, [](float x) { return std::sqrt(x); });
}
TEST_P(OperationsTest, Rsqrt) {
  float_unary("rsqrt", op_rsqrt, ref_rsqrt);
}

// ---- transcendental functions (within a few ulp of double precision) ------------------------

double d_exp(double x) {
  return std::exp(x);
}
double d_exp2(double x) {
  return std::exp2(x);
}
double d_log(double x) {
  return std::log(x);
}
double d_log2(double x) {
  return std::log2(x);
}
double d_sin(double x) {
  return std::sin(x);
}
double d_cos(double x) {
  return std::cos(x);
}
double d_tan(double x) {
  return std::tan(x);
}
double d_atan(double x) {
  return std::atan(x);
}
double d_pow(double x, double y) {
  return std::pow(x, y);
}
double d_atan2(double y, double x) {
  return std::atan2(y, x);
}

TEST_P(OperationsTest, Exp) {
  float_unary(
      "exp", op_exp, [](float x) { return d_exp(x); }, {3}, Forms::Light);
}
TEST_P(OperationsTest, Exp2) {
  float_unary(
      "exp2", op_exp2, [](float x) { return d_exp2(x); }, {3}, Forms::Light);
}
TEST_P(OperationsTest, Log) {
  float_unary(
      "log", op_log, [](float x) { return d_log(x); }, {4}, Forms::Light);
}
TEST_P(OperationsTest, Log2) {
  float_unary(
      "log2", op_log2, [](float x) { return d_log2(x); }, {4}, Forms::Light);
}
TEST_P(OperationsTest, Sin) {
  float_trig("sin", op_sin, d_sin, {4}, true);
}
TEST_P(OperationsTest, Cos) {
  float_trig("cos", op_cos, d_cos, {4}, true);
}
TEST_P(OperationsTest, Tan) {
  float_trig("tan", op_tan, d_tan, {5}, false);
}
TEST_P(OperationsTest, Atan) {
  float_unary(
      "atan", op_atan, [](float x) { return d_atan(x); }, {4}, Forms::Light);
}
TEST_P(OperationsTest, Pow) {
  float_binary(
      "pow", op_pow, [](float x, float y) { return d_pow(x, y); }, {4}, Forms::Light);
}
TEST_P(OperationsTest, Atan2) {
  float_binary(
      "atan2", op_atan2, [](float y, float x) { return d_atan2(y, x); }, {4}, Forms::Light);
}

// ---- integer arithmetic (wrap-around), comparisons, logic ------------------------------------

TEST_P(OperationsTest, IntAdd) {
  int_binary("iadd", op_add, [](int32_t a, int32_t b) { return wrap(int64_t{a} + b); });
}
TEST_P(OperationsTest, IntSub) {
  int_binary("isub", op_sub, [](int32_t a, int32_t b) { return wrap(int64_t{a} - b); });
}
TEST_P(OperationsTest, IntMul) {
  int_binary("imul", op_mul, [](int32_t a, int32_t b) { return wrap(int64_t{a} * b); });
}
TEST_P(OperationsTest, IntDiv) {
  int_binary("idiv", op_div, ref_idiv, -7, 0);  // also divides by a host 0
}
TEST_P(OperationsTest, IntRem) {
  int_binary("irem", op_rem, ref_irem, -7, 0);
}
TEST_P(OperationsTest, IntMin) {
  int_binary("imin", op_min, [](int32_t a, int32_t b) { return b < a ? b : a; });
}
TEST_P(OperationsTest, IntMax) {
  int_binary("imax", op_max, [](int32_t a, int32_t b) { return a < b ? b : a; });
}
TEST_P(OperationsTest, BitAnd) {
  int_binary("and", op_and, [](int32_t a, int32_t b) { return a & b; });
}
TEST_P(OperationsTest, BitOr) {
  int_binary("or", op_or, [](int32_t a, int32_t b) { return a | b; });
}
TEST_P(OperationsTest, BitXor) {
  int_binary("xor", op_xor, [](int32_t a, int32_t b) { return a ^ b; });
}
TEST_P(OperationsTest, ShiftLeft) {
  int_binary("shl", op_shl, ref_shl);
}
TEST_P(OperationsTest, ShiftRight) {
  int_binary("shr", op_shr, ref_shr, -1024, -1);
}
TEST_P(OperationsTest, ShiftRightLogical) {
  int_binary("shr_logical", op_shr_logical, ref_shr_logical, -1024, -1);
}
TEST_P(OperationsTest, MulHiUnsigned) {
  int_binary("mul_hi_unsigned", op_mul_hi_unsigned, ref_mul_hi_unsigned, -1, -7);
}
TEST_P(OperationsTest, IntComparisons) {
  int_binary("icmp", op_compare, ref_compare_bits<int32_t>);
}
TEST_P(OperationsTest, IntNeg) {
  int_unary("ineg", op_neg, [](int32_t x) { return wrap(-int64_t{x}); });
}
TEST_P(OperationsTest, IntAbs) {
  int_unary("iabs", op_abs, [](int32_t x) { return wrap(x < 0 ? -int64_t{x} : x); });
}
TEST_P(OperationsTest, IntSign) {
  int_unary("isign", op_sign, [](int32_t x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); });
}
TEST_P(OperationsTest, BitNot) {
  int_unary("not", op_bitnot, [](int32_t x) { return ~x; });
}
TEST_P(OperationsTest, BoolLogic) {
  // Bools from bits of ints: and, or, not, ==, != on Bool vectors.
  int_binary(
      "logic",
      [](const auto& a, const auto& b) {
        auto p = (dsl(a) & 1) != 0;
        auto q = (dsl(b) & 2) != 0;
        return to01(p && q) | (to01(p || q) << 1) | (to01(!p) << 2) | (to01(p == q) << 3) |
               (to01(p != q) << 4) | (to01((p && !q) || (!p && q)) << 5);
      },
      [](int32_t a, int32_t b) {
        bool p = (a & 1) != 0, q = (b & 2) != 0;
        return int32_t{p && q} | int32_t{p || q} << 1 | int32_t{!p} << 2 | int32_t{p == q} << 3 |
               int32_t{p != q} << 4 | int32_t{p != q} << 5;
      });
}

// ---- conversions and select ----------------------------------------------------------------

TEST_P(OperationsTest, ToInt) {
  float_unary("to_int", op_to_int, ref_to_int);
}
TEST_P(OperationsTest, ToFloat) {
  int_unary("to_float", op_to_float, [](int32_t x) { return static_cast<float>(x); });
}
TEST_P(OperationsTest, AsFloat) {
  // NaN patterns only need to stay NaN (payloads are not specified).
  int_unary("as_float", op_as_float, [](int32_t x) { return std::bit_cast<float>(x); });
}
TEST_P(OperationsTest, UnitFloat) {
  int_unary("unit_float", op_unit_float, ref_unit_float);
}
TEST_P(OperationsTest, AsInt) {
  float_unary("as_int", op_as_int, ref_as_int);
}
TEST_P(OperationsTest, SelectComponentwise) {
  float_binary("select", op_select, ref_select);
}
TEST_P(OperationsTest, SelectScalarConditionAndHostOperands) {
  // A scalar condition chooses whole vectors; host scalars as either value.
  auto as = as_vec4(sweep_floats(5, 1024)), bs = as_vec4(sweep_floats(6, 1024));
  as.resize(std::min(as.size(), bs.size()));
  bs.resize(as.size());
  Program p = program("select_forms", [] {
    Input<Float4> a("a");
    Input<Float4> b("b");
    Output<Float4> o("o");
    Output<Float4> h("h");
    o = select(a.x() < b.y(), a, b);
    h = select(a < b, a, 4.0f) + cond(a >= b, -2.0f, b);
  });
  auto [o, h] = run<Float4, Float4>(p, as, bs);
  Describe d = describe_inputs(as, bs);
  EXPECT_TRUE(bits_equal(o, map(as, bs, [](F4 a, F4 b) { return a.x < b.y ? a : b; }), d));
  EXPECT_TRUE(bits_equal(h,
                         map(as, bs,
                             [](F4 a, F4 b) {
                               F4 r;
                               for (int c = 0; c < 4; ++c)
                                 r[c] = (a[c] < b[c] ? a[c] : 4.0f) + (a[c] >= b[c] ? -2.0f : b[c]);
                               return r;
                             }),
                         d));
}

// ---- constant operands: folded by the optimizer, and computed from literals ----------------

// Operations on scalar constants (a, b) -- unary ones ignore b -- and their references.
template <class T>
struct ConstantOps {
  using V = Value<T, 1>;
  struct FloatOp {
    std::string name;
    std::function<Float(const V&, const V&)> op;
    std::function<double(T, T)> ref;
    int64_t ulps;
  };
  struct IntOp {
    std::string name;
    std::function<Int(const V&, const V&)> op;
    std::function<int32_t(T, T)> ref;
  };
  std::vector<FloatOp> floats;
  std::vector<IntOp> ints;
};

class ConstantsTest : public BackendTest {
 protected:
  // Kernels of at most kChunk operand pairs each: one RILL_IF per pair unrolls every
  // operation per pair, and a single kernel for all 100 pairs grew past what NVIDIA's shader
  // assembler accepts once strict division is corrected there (docs/gpu.md).
  template <class T>
  void check(const std::string& name, const ConstantOps<T>& ops,
             const std::vector<std::pair<T, T>>& all_args) {
    constexpr size_t kChunk = 25;
    for (size_t first = 0; first < all_args.size(); first += kChunk) {
      auto begin = all_args.begin() + static_cast<std::ptrdiff_t>(first);
      auto end = all_args.begin() + static_cast<std::ptrdiff_t>(std::min(all_args.size(), first + kChunk));
      check_chunk(name + "_" + std::to_string(first / kChunk), ops, std::vector<std::pair<T, T>>(begin, end));
    }
  }

  // One kernel element per operand pair, computing every operation into 4-vector outputs.
  template <class T>
  void check_chunk(const std::string& name, const ConstantOps<T>& ops,
                   const std::vector<std::pair<T, T>>& all_args) {
    // The denormal rule: a flushing backend gets no denormal inputs (here: constants).
    std::vector<std::pair<T, T>> args;
    for (const auto& a : all_args) {
      if constexpr (std::is_same_v<T, float>)
        if (flushes_denormals() && (is_denormal(a.first) || is_denormal(a.second))) continue;
      args.push_back(a);
    }
    using V = Value<T, 1>;
    size_t nf = (ops.floats.size() + 3) / 4, ni = (ops.ints.size() + 3) / 4;
    Program p = program(name, [&] {
      std::vector<std::unique_ptr<Output<Float4>>> fo;
      std::vector<std::unique_ptr<Output<Int4>>> io;
      for (size_t j = 0; j < nf; ++j)
        fo.push_back(std::make_unique<Output<Float4>>("f" + std::to_string(j)));
      for (size_t j = 0; j < ni; ++j)
        io.push_back(std::make_unique<Output<Int4>>("i" + std::to_string(j)));
      Int idx = element_index();
      for (size_t k = 0; k < args.size(); ++k) {
        RILL_IF(idx == static_cast<int32_t>(k)) {
          V a(args[k].first), b(args[k].second);
          auto f = [&](size_t j) {
            return j < ops.floats.size() ? ops.floats[j].op(a, b) : Float(0.0f);
          };
          auto i = [&](size_t j) { return j < ops.ints.size() ? ops.ints[j].op(a, b) : Int(0); };
          for (size_t j = 0; j < nf; ++j)
            *fo[j] = Float4(f(4 * j), f(4 * j + 1), f(4 * j + 2), f(4 * j + 3));
          for (size_t j = 0; j < ni; ++j)
            *io[j] = Int4(i(4 * j), i(4 * j + 1), i(4 * j + 2), i(4 * j + 3));
        }
        RILL_ENDIF;
      }
    });
    for (bool fold : {true, false}) {
      PassOptions passes;
      passes.constant_folding = fold;
      const char* how = fold ? "folded" : "computed from literals";
      Kernel k;
      try {
        k = compile(p, Accuracy::Strict, passes);
      } catch (const rill::Error& e) {  // keep the report short: the message lists the source
        std::string what = e.what();
        size_t cut = 0;
        for (int line = 0; line < 8 && cut != std::string::npos; ++line)
          cut = what.find('\n', cut + 1);
        ADD_FAILURE() << name << " (" << how << ") does not compile: " << what.substr(0, cut);
        continue;
      }
      auto n = static_cast<int64_t>(args.size());
      std::vector<Stream<Float4>> fs;
      std::vector<Stream<Int4>> is;
      for (size_t j = 0; j < nf; ++j) fs.emplace_back(n);
      for (size_t j = 0; j < ni; ++j) is.emplace_back(n);
      for (size_t j = 0; j < nf; ++j) k.bind("f" + std::to_string(j), fs[j]);
      for (size_t j = 0; j < ni; ++j) k.bind("i" + std::to_string(j), is[j]);
      k.execute();
      for (size_t j = 0; j < ops.floats.size(); ++j) {
        auto r = fs[j / 4].download();
        std::vector<float> got;
        std::vector<double> want;
        for (size_t e = 0; e < args.size(); ++e) {
          // Documented deviation (docs/backends.md): llvmpipe's GLSL computes mod(x, +-0) on
          // uniform-held constants as x instead of NaN; that one case is left out there.
          if (backend_name() == "glsl" && ops.floats[j].name == std::string("mod") && args[e].second == 0.0f) continue;
          // Documented deviation (docs/backends.md): PoCL folds floor, ceil and trunc of a
          // NaN literal to 0 (NaN read from a stream is right); that one case is left out there.
          if (backend_name() == "opencl" && std::isnan(args[e].first) &&
              (ops.floats[j].name == std::string("floor") || ops.floats[j].name == std::string("ceil") ||
               ops.floats[j].name == std::string("trunc")))
            continue;
          got.push_back(r[e][static_cast<int>(j % 4)]);
          double plain = ops.floats[j].ref(args[e].first, args[e].second);
          if (flushes_denormals()) {
            // Denormal constants may or may not be flushed (llvmpipe flushes what it reads
            // from textures, not uniforms): either reading of the rule is accepted.
            HostFlushScope flush_like_backend(true);
            double flushed = ops.floats[j].ref(args[e].first, args[e].second);
            if (ulp_distance(got.back(), static_cast<float>(flushed)) <= ops.floats[j].ulps) plain = flushed;
          }
          want.push_back(plain);
        }
        EXPECT_TRUE(within_ulps(got, want, ops.floats[j].ulps, describe(args)))
            << ops.floats[j].name << " on constants, " << how;
      }
      for (size_t j = 0; j < ops.ints.size(); ++j) {
        auto r = is[j / 4].download();
        std::vector<int32_t> got, want;
        for (size_t e = 0; e < args.size(); ++e) {
          got.push_back(r[e][static_cast<int>(j % 4)]);
          want.push_back(ops.ints[j].ref(args[e].first, args[e].second));
        }
        EXPECT_TRUE(bits_equal(got, want, describe(args)))
            << ops.ints[j].name << " on constants, " << how;
      }
    }
  }

  template <class T>
  static Describe describe(const std::vector<std::pair<T, T>>& args) {
    return [&args](size_t e) { return "a=" + show(args[e].first) + ", b=" + show(args[e].second); };
  }
  template <class T>
  static std::vector<std::pair<T, T>> pairs(const std::vector<T>& as, const std::vector<T>& bs) {
    std::vector<std::pair<T, T>> out;
    for (T a : as)
      for (T b : bs) out.emplace_back(a, b);
    return out;
  }
};

// Exact float results compare with 0 ulps (bit for bit, NaN matching NaN).
template <class F>
std::function<double(float, float)> unary_ref(F f) {
  return [f](float a, float) { return static_cast<double>(f(a)); };
}

TEST_P(ConstantsTest, FloatUnary) {
  using V = Float;
  ConstantOps<float> ops;
  auto un = [](auto op) { return [op](const V& a, const V&) { return op(a); }; };
  ops.floats = {{"plus", un(op_plus), unary_ref([](float x) { return x; }), 0},
                {"abs", un(op_abs), unary_ref(ref_abs), 0},
                {"sign", un(op_sign), unary_ref(ref_sign), 0},
                {"floor", un(op_floor), unary_ref([](float x) { return std::floor(x); }), 0},
                {"ceil", un(op_ceil), unary_ref([](float x) { return std::ceil(x); }), 0},
                {"trunc", un(op_trunc), unary_ref([](float x) { return std::trunc(x); }), 0},
                {"fract", un(op_fract), unary_ref(ref_fract), 0},
                {"sqrt", un(op_sqrt), unary_ref([](float x) { return std::sqrt(x); }), 0},
                {"rsqrt", un(op_rsqrt), unary_ref(ref_rsqrt), 0}};
  ops.ints = {{"to_int", un(op_to_int), [](float a, float) { return ref_to_int(a); }},
              {"as_int", un(op_as_int), [](float a, float) { return ref_as_int(a); }}};
  std::vector<std::pair<float, float>> args;
  for (float x : hard_floats()) args.emplace_back(x, 0.0f);
  check("const_float_unary", ops, args);
}

// Negation of constants (apart from the other unary operations: the generated code must not
// print "--" for the negation of a negative literal).
TEST_P(ConstantsTest, Negation) {
  ConstantOps<float> ops;
  ops.floats = {{"neg", [](const Float& a, const Float&) { return -a; },
                 unary_ref([](float x) { return -x; }), 0}};
  std::vector<std::pair<float, float>> args;
  for (float x : hard_floats()) args.emplace_back(x, 0.0f);
  check("const_negation", ops, args);
}

TEST_P(ConstantsTest, FloatBinary) {
  ConstantOps<float> ops;
  auto exact = [](float (*f)(float, float)) {
    return [f](float a, float b) { return static_cast<double>(f(a, b)); };
  };
  ops.floats = {{"add", op_add, exact([](float a, float b) { return a + b; }), 0},
                {"sub", op_sub, exact([](float a, float b) { return a - b; }), 0},
                {"mul", op_mul, exact([](float a, float b) { return a * b; }), 0},
                {"div", op_div, exact([](float a, float b) { return a / b; }), 0},
                {"min", op_min, exact(ref_min), 0},
                {"max", op_max, exact(ref_max), 0},
                {"mod", op_mod, exact(ref_mod), 0},
                {"select", op_select, exact(ref_select), 0}};
  ops.ints = {{"compare", op_compare, ref_compare_bits<float>}};
  std::vector<float> v = {0.0f,  -0.0f,    L::denorm_min(), -1.0f,          1.5f,
                          -2.5f, L::max(), L::infinity(),   -L::infinity(), L::quiet_NaN()};
  check("const_float_binary", ops, pairs(v, v));
}

TEST_P(ConstantsTest, Int) {
  using V = Int;
  ConstantOps<int32_t> ops;
  auto un = [](auto op) { return [op](const V& a, const V&) { return op(a); }; };
  ops.ints = {
      {"add", op_add, [](int32_t a, int32_t b) { return wrap(int64_t{a} + b); }},
      {"sub", op_sub, [](int32_t a, int32_t b) { return wrap(int64_t{a} - b); }},
      {"mul", op_mul, [](int32_t a, int32_t b) { return wrap(int64_t{a} * b); }},
      {"div", op_div, ref_idiv},
      {"rem", op_rem, ref_irem},
      {"min", op_min, [](int32_t a, int32_t b) { return b < a ? b : a; }},
      {"max", op_max, [](int32_t a, int32_t b) { return a < b ? b : a; }},
      {"and", op_and, [](int32_t a, int32_t b) { return a & b; }},
      {"or", op_or, [](int32_t a, int32_t b) { return a | b; }},
      {"xor", op_xor, [](int32_t a, int32_t b) { return a ^ b; }},
      {"shl", op_shl, ref_shl},
      {"shr", op_shr, ref_shr},
      {"shr_logical", op_shr_logical, ref_shr_logical},
      {"mul_hi_unsigned", op_mul_hi_unsigned, ref_mul_hi_unsigned},
      {"compare", op_compare, ref_compare_bits<int32_t>},
      {"neg", un(op_neg), [](int32_t a, int32_t) { return wrap(-int64_t{a}); }},
      {"abs", un(op_abs), [](int32_t a, int32_t) { return wrap(a < 0 ? -int64_t{a} : a); }},
      {"sign", un(op_sign), [](int32_t a, int32_t) { return a > 0 ? 1 : (a < 0 ? -1 : 0); }},
      {"not", un(op_bitnot), [](int32_t a, int32_t) { return ~a; }}};
  ops.floats = {{"to_float", un(op_to_float),
                 [](int32_t a, int32_t) { return double{static_cast<float>(a)}; }, 0},
                {"as_float", un(op_as_float),
                 [](int32_t a, int32_t) { return double{std::bit_cast<float>(a)}; }, 0},
                {"unit_float", un(op_unit_float),
                 [](int32_t a, int32_t) { return double{ref_unit_float(a)}; }, 0}};
  std::vector<int32_t> v = {0,
                            1,
                            -1,
                            2,
                            -7,
                            31,
                            33,
                            std::numeric_limits<int32_t>::max(),
                            std::numeric_limits<int32_t>::min()};
  check("const_int", ops, pairs(v, v));
}

TEST_P(ConstantsTest, TranscendentalUnary) {
  // Special values (C99 Annex F) and a few ordinary ones.
  using V = Float;
  auto un = [](auto op) { return [op](const V& a, const V&) { return op(a); }; };
  auto dref = [](double (*f)(double)) { return [f](float a, float) { return f(a); }; };
  ConstantOps<float> unary;
  unary.floats = {{"exp", un(op_exp), dref(d_exp), 3}, {"exp2", un(op_exp2), dref(d_exp2), 3},
                  {"log", un(op_log), dref(d_log), 4}, {"log2", un(op_log2), dref(d_log2), 4},
                  {"sin", un(op_sin), dref(d_sin), 4}, {"cos", un(op_cos), dref(d_cos), 4},
                  {"tan", un(op_tan), dref(d_tan), 5}, {"atan", un(op_atan), dref(d_atan), 4}};
  std::vector<std::pair<float, float>> args;
  for (float x :
       {0.0f, -0.0f, 1.0f, -1.0f, 0.5f, -2.5f, L::infinity(), -L::infinity(), L::quiet_NaN()})
    args.emplace_back(x, 0.0f);
  check("const_transcendental_unary", unary, args);
}

// Split from TranscendentalUnary: each compiles several kernels of software transcendentals,
// which on simd takes over a minute per test on 2 shared cores (compile cost: issue 17).
TEST_P(ConstantsTest, TranscendentalBinary) {
  ConstantOps<float> binary;
  binary.floats = {{"pow", op_pow, [](float a, float b) { return d_pow(a, b); }, 4},
                   {"atan2", op_atan2, [](float a, float b) { return d_atan2(a, b); }, 4}};
  std::vector<float> v = {0.0f, -0.0f, 2.0f, -1.5f, L::infinity(), L::quiet_NaN()};
  check("const_transcendental_binary", binary, pairs(v, v));
}

RILL_BACKEND_TEST_SUITE(OperationsTest);
RILL_BACKEND_TEST_SUITE(ConstantsTest);

}  // namespace
}  // namespace rill::testing

namespace rill::testing {
namespace {

// A float made from an int constant (int_to_float(0), as_float of a literal) is a constant
// to the driver's compiler too, which may fold it into the operations using it with rules
// that are wrong for zeros, infinities and NaN (Mesa: x * 0.0 -> 0.0). With the optimizer
// off the constants reach the backend unfolded; the results must still be IEEE's.
TEST_P(OperationsTest, FloatsMadeFromIntConstantsAreNotFoldedByTheDriver) {
  Program p = program("int_constants", [] {
    Output<Float3> o("o");
    Output<Float2> o2("o2");
    Output<Float> nan_out("nan_out");
    Float3 d = Float3(Float(o2.x()), Float(o2.y()), Float(o2.x())) / to_float(Int3(0));
    o = Float3(Float(o.y()), Float(o.x()), Float(o.z())) / d;
    nan_out = as_float(Int(0x7f800000)) * to_float(Int(0));  // inf * 0: NaN
    o2 = Float2(Float(o2.x()), Float(o2.y()));
  });
  Kernel k = compile(p, Accuracy::Strict, PassOptions{false, false, false, false});
  const float inf = std::numeric_limits<float>::infinity();
  Stream<Float3> o(std::vector<glm::vec3>(37, {3343711.5f, -103.9f, -inf}));
  Stream<Float2> o2(std::vector<glm::vec2>(37, {8.26980972f, -6.0f}));
  Stream<Float> nan_out(37);
  k.outputs(o, o2, nan_out);
  k.execute();
  const glm::vec3 r = o.download()[36];
  // (-103.9 / inf, 3343711.5 / -inf, -inf / inf) in the order x, y, z of the swizzle.
  EXPECT_EQ(bits_of(r.x), bits_of(-0.0f)) << show(r.x);
  EXPECT_EQ(bits_of(r.y), bits_of(-0.0f)) << show(r.y);
  EXPECT_TRUE(std::isnan(r.z)) << show(r.z);
  EXPECT_TRUE(std::isnan(nan_out.download()[36])) << show(nan_out.download()[36]);
}

}  // namespace
}  // namespace rill::testing
