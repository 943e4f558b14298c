// The operation cases: every DSL operation, on scalars and vectors, with a double-precision
// reference that mirrors the operation's documented definition (Operators.h, Math.h and the
// rill_* helpers of backends/codegen).
//
// Each case is one kernel: a group of operations sharing an input signature, each written
// to outputs in several forms (float4, float, vector op scalar). References are written in
// double; the fast-mode domain of an operation is where its contract holds (docs/accuracy.md).
#include <algorithm>
#include <cfloat>
#include <climits>
#include <numbers>

#include "Suite.h"

namespace rill::conformance {

namespace {

constexpr double kPi = std::numbers::pi;

// ---- references ---------------------------------------------------------------------------

double r_min(double a, double b) {
  return b < a ? b : a;
}
double r_max(double a, double b) {
  return a < b ? b : a;
}
double r_sign(double x) {
  return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0);
}
double r_mod(double a, double b) {
  return a - b * std::floor(a / b);
}
double r_fract(double x) {
  return x - std::floor(x);
}
double r_rsqrt(double x) {
  return 1.0 / std::sqrt(x);
}

int32_t wrap(int64_t v) {
  return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(v)));
}
int32_t i_div(int32_t a, int32_t b) {
  if (b == 0) return 0;
  return wrap(int64_t{a} / b);
}
int32_t i_rem(int32_t a, int32_t b) {
  if (b == 0) return 0;
  return static_cast<int32_t>(int64_t{a} % b);
}
int32_t i_shl(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) << (b & 31));
}
int32_t i_shr(int32_t a, int32_t b) {
  return a >> (b & 31);
}
int32_t f_to_i(double x) {
  if (std::isnan(x)) return 0;
  if (x >= 2147483648.0) return INT_MAX;
  if (x < -2147483648.0) return INT_MIN;
  return static_cast<int32_t>(x);
}

// ---- forms ----------------------------------------------------------------------------------

template <class T>
using V1 = Value<T, 1>;
template <class T>
using V4 = Value<T, 4>;

// Bool results travel through Int streams as 0 / 1.
template <int N>
Value<int32_t, N> to01(const Value<bool, N>& b) {
  return select(b, Value<int32_t, N>(1), Value<int32_t, N>(0));
}

// A componentwise operation on inputs of scalar kind In (float or int) with result kind Out,
// written with a generic lambda so that it exists at width 1 and 4.
template <class In, class Out>
struct Unary {
  std::string op;
  std::function<V4<Out>(const V4<In>&)> v4;
  std::function<V1<Out>(const V1<In>&)> s;
  std::function<double(const Elem&, int input, int c)> ref;  // reads input `input`, comp c
  std::function<bool(double)> domain;
  std::function<double(double)> scale;
};
template <class In, class Out>
struct Binary {
  std::string op;
  std::function<V4<Out>(const V4<In>&, const V4<In>&)> v4;
  std::function<V1<Out>(const V1<In>&, const V1<In>&)> s;
  std::function<V4<Out>(const V4<In>&, const V1<In>&)> vs;
  std::function<double(const Elem&, int ca, int cb)> ref;  // inputs 0 and 1, components
  std::function<bool(double, double)> domain;
  std::function<double(double, double)> scale;
};

template <class In, class Out, class F>
Unary<In, Out> unary(std::string op, F f, std::function<double(double)> ref,
                     std::function<bool(double)> domain = {}) {
  Unary<In, Out> u;
  u.op = std::move(op);
  u.v4 = [f](const V4<In>& x) { return V4<Out>(f(x)); };
  u.s = [f](const V1<In>& x) { return V1<Out>(f(x)); };
  u.ref = [ref](const Elem& e, int input, int c) { return ref(e.d(input, c)); };
  u.domain = std::move(domain);
  return u;
}

template <class In, class Out, class F>
Binary<In, Out> binary(std::string op, F f, std::function<double(double, double)> ref,
                       std::function<bool(double, double)> domain = {},
                       std::function<double(double, double)> scale = {}) {
  Binary<In, Out> b;
  b.op = std::move(op);
  b.v4 = [f](const V4<In>& x, const V4<In>& y) { return V4<Out>(f(x, y)); };
  b.s = [f](const V1<In>& x, const V1<In>& y) { return V1<Out>(f(x, y)); };
  b.vs = [f](const V4<In>& x, const V1<In>& y) { return V4<Out>(f(x, y)); };
  b.ref = [ref](const Elem& e, int ca, int cb) { return ref(e.d(0, ca), e.d(1, cb)); };
  b.domain = std::move(domain);
  b.scale = std::move(scale);
  return b;
}

template <class In, class Out>
Case unary_case(const std::string& name, const std::string& category,
                std::vector<Unary<In, Out>> ops, Domain dom) {
  Case k;
  k.name = name;
  k.category = category;
  k.domains = {dom};
  k.build = [name, ops] {
    return program(name, [&] {
      Input<V4<In>> a("a");
      V1<In> ax = a.x();
      for (const auto& u : ops) {
        Output<V4<Out>> o4(u.op + "_v4");
        o4 = u.v4(a);
        Output<V1<Out>> o1(u.op + "_s");
        o1 = u.s(ax);
      }
    });
  };
  int out = 0;
  for (const auto& u : ops) {
    auto dom_fn = [d = u.domain](int comp) {
      return [d, comp](const Elem& e, int c) { return !d || d(e.d(0, comp < 0 ? c : comp)); };
    };
    auto scale_fn = [s = u.scale](int comp) -> std::function<double(const Elem&, int)> {
      if (!s) return {};
      return [s, comp](const Elem& e, int c) { return s(e.d(0, comp < 0 ? c : comp)); };
    };
    Check c4{u.op,
             category,
             "4-vector",
             out++,
             [r = u.ref](const Elem& e, int c) { return r(e, 0, c); },
             dom_fn(-1),
             scale_fn(-1)};
    Check c1{u.op,
             category,
             "scalar",
             out++,
             [r = u.ref](const Elem& e, int) { return r(e, 0, 0); },
             dom_fn(0),
             scale_fn(0)};
    k.checks.push_back(c4);
    k.checks.push_back(c1);
  }
  return k;
}

template <class In, class Out>
Case binary_case(const std::string& name, const std::string& category,
                 std::vector<Binary<In, Out>> ops, Domain da, Domain db) {
  Case k;
  k.name = name;
  k.category = category;
  k.domains = {da, db};
  k.build = [name, ops] {
    return program(name, [&] {
      Input<V4<In>> a("a");
      Input<V4<In>> b("b");
      V1<In> ax = a.x(), bx = b.x(), bw = b.w();
      for (const auto& o : ops) {
        Output<V4<Out>> o4(o.op + "_v4");
        o4 = o.v4(a, b);
        Output<V1<Out>> o1(o.op + "_s");
        o1 = o.s(ax, bx);
        Output<V4<Out>> ovs(o.op + "_vs");
        ovs = o.vs(a, bw);
      }
    });
  };
  int out = 0;
  for (const auto& o : ops) {
    // Which components of a and b component c of each form reads.
    auto make = [&](const char* form, int fa, int fb) {
      auto ca = [fa](int c) { return fa < 0 ? c : fa; };
      auto cb = [fb](int c) { return fb < 0 ? c : fb; };
      Check ch;
      ch.op = o.op;
      ch.category = category;
      ch.form = form;
      ch.output = out++;
      ch.ref = [r = o.ref, ca, cb](const Elem& e, int c) { return r(e, ca(c), cb(c)); };
      if (o.domain)
        ch.fast_domain = [d = o.domain, ca, cb](const Elem& e, int c) {
          return d(e.d(0, ca(c)), e.d(1, cb(c)));
        };
      if (o.scale)
        ch.scale = [s = o.scale, ca, cb](const Elem& e, int c) {
          return s(e.d(0, ca(c)), e.d(1, cb(c)));
        };
      k.checks.push_back(ch);
    };
    make("4-vector", -1, -1);
    make("scalar", 0, 0);
    make("vector op scalar", -1, 3);
  }
  return k;
}

// ---- float operations -------------------------------------------------------------------------

Case float_exact_unary() {
  using U = Unary<float, float>;
  std::vector<U> ops = {
      unary<float, float>(
          "neg", [](const auto& x) { return -x; }, [](double x) { return -x; }),
      unary<float, float>(
          "abs", [](const auto& x) { return abs(x); }, [](double x) { return std::fabs(x); }),
      unary<float, float>(
          "sign", [](const auto& x) { return sign(x); }, r_sign),
      unary<float, float>(
          "floor", [](const auto& x) { return floor(x); }, [](double x) { return std::floor(x); }),
      unary<float, float>(
          "ceil", [](const auto& x) { return ceil(x); }, [](double x) { return std::ceil(x); }),
      unary<float, float>(
          "trunc", [](const auto& x) { return trunc(x); }, [](double x) { return std::trunc(x); }),
      unary<float, float>(
          "fract", [](const auto& x) { return fract(x); }, r_fract),
      unary<float, float>(
          "sqrt", [](const auto& x) { return sqrt(x); }, [](double x) { return std::sqrt(x); }),
      unary<float, float>(
          "rsqrt", [](const auto& x) { return rsqrt(x); }, r_rsqrt),
  };
  return unary_case<float, float>("float_unary", "float", ops, Domain{-1000, 1000});
}

Case float_exact_binary() {
  auto q_ok = [](double a, double b) {  // mod: floor(a / b) is unambiguous in binary32
    double q = a / b;
    return std::fabs(a) <= 0x1p100 && std::fabs(b) <= 0x1p100 && std::fabs(q) < 1048576.0 &&
           std::fabs(q - std::round(q)) > 1e-5 * std::max(1.0, std::fabs(q));
  };
  std::vector<Binary<float, float>> ops = {
      binary<float, float>(
          "add", [](const auto& a, const auto& b) { return a + b; },
          [](double a, double b) { return a + b; }),
      binary<float, float>(
          "sub", [](const auto& a, const auto& b) { return a - b; },
          [](double a, double b) { return a - b; }),
      binary<float, float>(
          "mul", [](const auto& a, const auto& b) { return a * b; },
          [](double a, double b) { return a * b; }),
      binary<float, float>(
          "div", [](const auto& a, const auto& b) { return a / b; },
          [](double a, double b) { return a / b; },
          [](double a, double b) {  // OpenCL's relaxed-math domain of x / y
            return std::fabs(a) <= 0x1p62 && std::fabs(b) >= 0x1p-62 && std::fabs(b) <= 0x1p62;
          }),
      binary<float, float>(
          "mod", [](const auto& a, const auto& b) { return mod(a, b); }, r_mod, q_ok,
          [](double a, double b) { return std::fabs(a) + std::fabs(b); }),
      binary<float, float>(
          "min", [](const auto& a, const auto& b) { return min(a, b); }, r_min),
      binary<float, float>(
          "max", [](const auto& a, const auto& b) { return max(a, b); }, r_max),
  };
  return binary_case<float, float>("float_binary", "float", ops, Domain{-1000, 1000},
                                   Domain{-1000, 1000});
}

// Transcendental operations: one case each (in strict mode each becomes a long routine).
Case transcendental(const std::string& op, std::function<Float4(const Float4&)> v4,
                    std::function<Float(const Float&)> s, double (*ref)(double), Domain dom,
                    std::function<bool(double)> fast_domain,
                    std::function<double(double)> scale = {}) {
  Unary<float, float> u;
  u.op = op;
  u.v4 = std::move(v4);
  u.s = std::move(s);
  u.ref = [ref](const Elem& e, int input, int c) { return ref(e.d(input, c)); };
  u.domain = std::move(fast_domain);
  u.scale = std::move(scale);
  return unary_case<float, float>(op, "transcendental", {u}, dom);
}

#define RILL_TRANSCENDENTAL(fn, lo, hi, ...)                                            \
  transcendental(                                                                       \
      #fn, [](const Float4& x) { return Float4(fn(x)); },                               \
      [](const Float& x) { return Float(fn(x)); }, [](double x) { return std::fn(x); }, \
      Domain{lo, hi}, __VA_ARGS__)

std::vector<Case> transcendental_cases() {
  auto in = [](double lo, double hi) { return [lo, hi](double x) { return x >= lo && x <= hi; }; };
  std::vector<Case> v;
  v.push_back(RILL_TRANSCENDENTAL(exp, -100, 100, in(-87.3, 88.7)));
  v.push_back(RILL_TRANSCENDENTAL(exp2, -150, 130, in(-126, 127.99)));
  // Near 1, where log is near 0, the error is absolute (in ulps of 1, as GLSL specifies it).
  auto near_one = [](double x) { return x >= 0.5 && x <= 2 ? 1.0 : 0.0; };
  v.push_back(RILL_TRANSCENDENTAL(log, 0, 1000, in(FLT_MIN, FLT_MAX), near_one));
  v.push_back(RILL_TRANSCENDENTAL(log2, 0, 1000, in(FLT_MIN, FLT_MAX), near_one));
  // sin and cos: absolute error on [-pi, pi] (in ulps of 1), as OpenCL's relaxed math and
  // Vulkan specify them: GPU built-ins (NVIDIA's sin.approx) have an absolute error there,
  // so near a zero of the function no relative bound holds.
  auto absolute = [](double) { return 1.0; };
  v.push_back(RILL_TRANSCENDENTAL(sin, -10, 10, in(-kPi, kPi), absolute));
  v.push_back(RILL_TRANSCENDENTAL(cos, -10, 10, in(-kPi, kPi), absolute));
  // tan: OpenCL's relaxed math derives it as sin(x) * (1 / cos(x)), so it inherits their
  // absolute error e amplified by the pole: |error| <= sqrt(2) e / cos^2(x). The measure is in
  // ulps of 1 / cos^2(x) (>= |tan x|), and the domain keeps |cos x| >= 2^-10, away from the
  // poles, where such an error can change the sign of cos(x) or give an infinity.
  v.push_back(RILL_TRANSCENDENTAL(
      tan, -10, 10,
      [](double x) { return x >= -kPi && x <= kPi && std::fabs(std::cos(x)) >= 0x1p-10; },
      [](double x) { return 1.0 / (std::cos(x) * std::cos(x)); }));
  v.push_back(RILL_TRANSCENDENTAL(atan, -100, 100, [](double) { return true; }));

  // pow: positive bases, results a binade away from overflow and underflow (pow is
  // exp2(y log2 x) on GPUs: its error grows with |y log2 x| up to the limits of the format).
  auto pow_domain = [](double x, double y) {
    return x > 0 && std::fabs(y) <= 1000 && std::fabs(y * std::log2(x)) <= 126;
  };
  std::vector<Binary<float, float>> pw = {binary<float, float>(
      "pow", [](const auto& a, const auto& b) { return pow(a, b); },
      [](double a, double b) { return std::pow(a, b); }, pow_domain)};
  v.push_back(
      binary_case<float, float>("pow", "transcendental", pw, Domain{0, 10}, Domain{-10, 10}));
  std::vector<Binary<float, float>> at = {binary<float, float>(
      "atan2", [](const auto& a, const auto& b) { return atan2(a, b); },
      [](double y, double x) { return std::atan2(y, x); },
      // OpenCL's relaxed math derives atan2 from atan(y / x): the operands are in the domain
      // of its division (magnitudes in [2^-62, 2^62]; no zeros, whose sign picks +-pi).
      [](double y, double x) {
        auto in_division_domain = [](double v) {
          return std::fabs(v) >= 0x1p-62 && std::fabs(v) <= 0x1p62;
        };
        return in_division_domain(y) && in_division_domain(x);
      })};
  v.push_back(
      binary_case<float, float>("atan2", "transcendental", at, Domain{-10, 10}, Domain{-10, 10}));
  return v;
}
#undef RILL_TRANSCENDENTAL

// ---- integers -----------------------------------------------------------------------------------

Case int_binary(const std::string& name, const std::vector<std::string>& which) {
  using B = Binary<int32_t, int32_t>;
  auto ii = [](int32_t (*f)(int32_t, int32_t)) {
    return [f](double a, double b) {
      return static_cast<double>(f(static_cast<int32_t>(a), static_cast<int32_t>(b)));
    };
  };
  std::vector<B> ops = {
      binary<int32_t, int32_t>(
          "int.add", [](const auto& a, const auto& b) { return a + b; },
          ii([](int32_t a, int32_t b) { return wrap(int64_t{a} + b); })),
      binary<int32_t, int32_t>(
          "int.sub", [](const auto& a, const auto& b) { return a - b; },
          ii([](int32_t a, int32_t b) { return wrap(int64_t{a} - b); })),
      binary<int32_t, int32_t>(
          "int.mul", [](const auto& a, const auto& b) { return a * b; },
          ii([](int32_t a, int32_t b) { return wrap(int64_t{a} * b); })),
      binary<int32_t, int32_t>(
          "int.div", [](const auto& a, const auto& b) { return a / b; }, ii(i_div)),
      binary<int32_t, int32_t>(
          "int.rem", [](const auto& a, const auto& b) { return a % b; }, ii(i_rem)),
      binary<int32_t, int32_t>(
          "int.min", [](const auto& a, const auto& b) { return min(a, b); },
          ii([](int32_t a, int32_t b) { return b < a ? b : a; })),
      binary<int32_t, int32_t>(
          "int.max", [](const auto& a, const auto& b) { return max(a, b); },
          ii([](int32_t a, int32_t b) { return a < b ? b : a; })),
      binary<int32_t, int32_t>(
          "int.and", [](const auto& a, const auto& b) { return a & b; },
          ii([](int32_t a, int32_t b) { return a & b; })),
      binary<int32_t, int32_t>(
          "int.or", [](const auto& a, const auto& b) { return a | b; },
          ii([](int32_t a, int32_t b) { return a | b; })),
      binary<int32_t, int32_t>(
          "int.xor", [](const auto& a, const auto& b) { return a ^ b; },
          ii([](int32_t a, int32_t b) { return a ^ b; })),
      binary<int32_t, int32_t>(
          "int.shl", [](const auto& a, const auto& b) { return a << b; }, ii(i_shl)),
      binary<int32_t, int32_t>(
          "int.shr", [](const auto& a, const auto& b) { return a >> b; }, ii(i_shr)),
      binary<int32_t, int32_t>(
          "int.shr_logical", [](const auto& a, const auto& b) { return shr_logical(a, b); },
          ii([](int32_t a, int32_t b) {
            return static_cast<int32_t>(static_cast<uint32_t>(a) >> (b & 31));
          })),
      binary<int32_t, int32_t>(
          "int.mul_hi_unsigned", [](const auto& a, const auto& b) { return mul_hi_unsigned(a, b); },
          ii([](int32_t a, int32_t b) {
            const uint64_t p = uint64_t{static_cast<uint32_t>(a)} * static_cast<uint32_t>(b);
            return static_cast<int32_t>(static_cast<uint32_t>(p >> 32));
          })),
  };
  std::vector<B> picked;
  for (const auto& o : ops)
    for (const auto& w : which)
      if (o.op == "int." + w) picked.push_back(o);
  return binary_case<int32_t, int32_t>(name, "int", picked, Domain{-1000, 1000, true},
                                       Domain{-40, 40, true});
}

Case int_unary() {
  auto i1 = [](int32_t (*f)(int32_t)) {
    return [f](double a) { return static_cast<double>(f(static_cast<int32_t>(a))); };
  };
  std::vector<Unary<int32_t, int32_t>> ops = {
      unary<int32_t, int32_t>(
          "int.neg", [](const auto& x) { return -x; },
          i1([](int32_t a) { return wrap(-int64_t{a}); })),
      unary<int32_t, int32_t>(
          "int.abs", [](const auto& x) { return abs(x); },
          i1([](int32_t a) { return wrap(a < 0 ? -int64_t{a} : a); })),
      unary<int32_t, int32_t>(
          "int.sign", [](const auto& x) { return sign(x); },
          i1([](int32_t a) { return a > 0 ? 1 : (a < 0 ? -1 : 0); })),
      unary<int32_t, int32_t>(
          "int.not", [](const auto& x) { return ~x; }, i1([](int32_t a) { return ~a; })),
  };
  return unary_case<int32_t, int32_t>("int_unary", "int", ops, Domain{-1000, 1000, true});
}

// ---- comparisons, booleans, select ---------------------------------------------------------

template <class T>
Case compare_case(const std::string& name, const std::string& prefix, Domain d) {
  using B = Binary<T, int32_t>;
  auto cmp = [](bool (*f)(double, double)) {
    return [f](double a, double b) { return f(a, b) ? 1.0 : 0.0; };
  };
  std::vector<B> ops = {
      binary<T, int32_t>(
          prefix + "lt", [](const auto& a, const auto& b) { return to01(a < b); },
          cmp([](double a, double b) { return a < b; })),
      binary<T, int32_t>(
          prefix + "le", [](const auto& a, const auto& b) { return to01(a <= b); },
          cmp([](double a, double b) { return a <= b; })),
      binary<T, int32_t>(
          prefix + "gt", [](const auto& a, const auto& b) { return to01(a > b); },
          cmp([](double a, double b) { return a > b; })),
      binary<T, int32_t>(
          prefix + "ge", [](const auto& a, const auto& b) { return to01(a >= b); },
          cmp([](double a, double b) { return a >= b; })),
      binary<T, int32_t>(
          prefix + "eq", [](const auto& a, const auto& b) { return to01(a == b); },
          cmp([](double a, double b) { return a == b; })),
      binary<T, int32_t>(
          prefix + "ne", [](const auto& a, const auto& b) { return to01(a != b); },
          cmp([](double a, double b) { return a != b; })),
  };
  return binary_case<T, int32_t>(name, "compare", ops, d, d);
}

// Booleans come from Int inputs (nonzero is true) and go back as 0 / 1.
Case bool_case() {
  Case k;
  k.name = "bool";
  k.category = "bool";
  k.domains = {Domain{-1, 1, true}, Domain{-1, 1, true}};
  k.build = [] {
    return program("bool", [] {
      Input<Int4> p("p");
      Input<Int4> q("q");
      Bool4 a = p != 0, b = q != 0;
      Bool ax = p.x() != 0, bx = q.x() != 0;
      Output<Int4> o_and("and_v4"), o_or("or_v4"), o_not("not_v4"), o_eq("eq_v4"), o_ne("ne_v4");
      Output<Int> s_and("and_s"), s_or("or_s"), s_not("not_s"), any4("any4"), all4("all4"),
          any2("any2"), all3("all3");
      o_and = to01(a && b);
      o_or = to01(a || b);
      o_not = to01(!a);
      o_eq = to01(a == b);
      o_ne = to01(a != b);
      s_and = to01(ax && bx);
      s_or = to01(ax || bx);
      s_not = to01(!ax);
      any4 = to01(any(a));
      all4 = to01(all(a));
      Bool2 a2 = p(0, 1) != 0;
      Bool3 a3 = p(0, 1, 2) != 0;
      any2 = to01(any(a2));
      all3 = to01(all(a3));
    });
  };
  auto t = [](const Elem& e, int in, int c) { return e.i(in, c) != 0; };
  auto add = [&](const char* op, const char* form, int out,
                 std::function<bool(const Elem&, int)> f) {
    Check c;
    c.op = op;
    c.category = "bool";
    c.form = form;
    c.output = out;
    c.ref = [f](const Elem& e, int comp) { return f(e, comp) ? 1.0 : 0.0; };
    k.checks.push_back(c);
  };
  add("bool.and", "4-vector", 0, [t](const Elem& e, int c) { return t(e, 0, c) && t(e, 1, c); });
  add("bool.or", "4-vector", 1, [t](const Elem& e, int c) { return t(e, 0, c) || t(e, 1, c); });
  add("bool.not", "4-vector", 2, [t](const Elem& e, int c) { return !t(e, 0, c); });
  add("bool.eq", "4-vector", 3, [t](const Elem& e, int c) { return t(e, 0, c) == t(e, 1, c); });
  add("bool.ne", "4-vector", 4, [t](const Elem& e, int c) { return t(e, 0, c) != t(e, 1, c); });
  add("bool.and", "scalar", 5, [t](const Elem& e, int) { return t(e, 0, 0) && t(e, 1, 0); });
  add("bool.or", "scalar", 6, [t](const Elem& e, int) { return t(e, 0, 0) || t(e, 1, 0); });
  add("bool.not", "scalar", 7, [t](const Elem& e, int) { return !t(e, 0, 0); });
  add("bool.any", "4-vector", 8,
      [t](const Elem& e, int) { return t(e, 0, 0) || t(e, 0, 1) || t(e, 0, 2) || t(e, 0, 3); });
  add("bool.all", "4-vector", 9,
      [t](const Elem& e, int) { return t(e, 0, 0) && t(e, 0, 1) && t(e, 0, 2) && t(e, 0, 3); });
  add("bool.any", "2-vector", 10, [t](const Elem& e, int) { return t(e, 0, 0) || t(e, 0, 1); });
  add("bool.all", "3-vector", 11,
      [t](const Elem& e, int) { return t(e, 0, 0) && t(e, 0, 1) && t(e, 0, 2); });
  return k;
}

Case select_case() {
  Case k;
  k.name = "select";
  k.category = "select";
  k.domains = {Domain{-1, 1, true}, Domain{}, Domain{}, Domain{-1000, 1000, true}};
  k.build = [] {
    return program("select", [] {
      Input<Int4> c("c");
      Input<Float4> a("a");
      Input<Float4> b("b");
      Input<Int4> i("i");
      Bool4 cv = c != 0;
      Bool cs = c.w() != 0;
      Output<Float4> f4("f_v4"), fs("f_scalar_cond");
      Output<Float> f1("f_s");
      Output<Int4> i4("i_v4");
      Output<Float4> fh("f_host");
      f4 = select(cv, a, b);
      fs = select(cs, a, b);
      f1 = select(Bool(c.x() != 0), Float(a.x()), Float(b.x()));
      i4 = select(cv, i, Int4(i(1, 2, 3, 0)));
      fh = select(cv, a, 0.5f);
    });
  };
  auto add = [&](const char* form, int out, std::function<double(const Elem&, int)> f) {
    Check ch;
    ch.op = "select";
    ch.category = "select";
    ch.form = form;
    ch.output = out;
    ch.ref = std::move(f);
    k.checks.push_back(ch);
  };
  add("4-vector", 0, [](const Elem& e, int c) { return e.i(0, c) ? e.d(1, c) : e.d(2, c); });
  add("scalar condition", 1,
      [](const Elem& e, int c) { return e.i(0, 3) ? e.d(1, c) : e.d(2, c); });
  add("scalar", 2, [](const Elem& e, int) { return e.i(0, 0) ? e.d(1, 0) : e.d(2, 0); });
  add("int 4-vector", 3,
      [](const Elem& e, int c) { return e.i(0, c) ? e.d(3, c) : e.d(3, (c + 1) % 4); });
  add("host operand", 4, [](const Elem& e, int c) { return e.i(0, c) ? e.d(1, c) : 0.5; });
  return k;
}

// ---- conversions -----------------------------------------------------------------------------

Case conversion_case() {
  Case k;
  k.name = "convert";
  k.category = "convert";
  k.domains = {Domain{-3e9, 3e9}, Domain{-100000000, 100000000, true}};
  k.build = [] {
    return program("convert", [] {
      Input<Float4> x("x");
      Input<Int4> i("i");
      Output<Int4> ti("to_int_v4"), ai("as_int_v4");
      Output<Float4> tf("to_float_v4"), af("as_float_v4");
      Output<Int> ti1("to_int_s");
      Output<Float> tf1("to_float_s");
      Output<Float4> uf("unit_float_v4");
      ti = to_int(x);
      ai = as_int(x);
      tf = to_float(i);
      af = as_float(i);
      ti1 = to_int(Float(x.x()));
      tf1 = to_float(Int(i.x()));
      uf = unit_float(i);
    });
  };
  auto add = [&](const char* op, const char* form, int out,
                 std::function<double(const Elem&, int)> f) {
    Check ch;
    ch.op = op;
    ch.category = "convert";
    ch.form = form;
    ch.output = out;
    ch.ref = std::move(f);
    k.checks.push_back(ch);
  };
  add("to_int", "4-vector", 0, [](const Elem& e, int c) { return f_to_i(e.d(0, c)); });
  // Bit reinterpretation reads the raw input bits (no flushing: it is not arithmetic).
  add("as_int", "4-vector", 1, [](const Elem& e, int c) {
    Elem raw = e;
    raw.daz = false;
    return static_cast<double>(raw.i(0, c));
  });
  add("to_float", "4-vector", 2, [](const Elem& e, int c) { return e.d(1, c); });
  add("as_float", "4-vector", 3,
      [](const Elem& e, int c) { return static_cast<double>(float_of(e.w(1, c))); });
  add("to_int", "scalar", 4, [](const Elem& e, int) { return f_to_i(e.d(0, 0)); });
  add("to_float", "scalar", 5, [](const Elem& e, int) { return e.d(1, 0); });
  // The high 24 bits as unsigned, times 2^-24: exact.
  add("unit_float", "4-vector", 6,
      [](const Elem& e, int c) { return static_cast<double>(e.w(1, c) >> 8) * 0x1p-24; });
  return k;
}

// ---- geometry -----------------------------------------------------------------------------------

// Fast-mode domain of the geometric functions: every float input component is zero or of a
// magnitude in [2^-60, 2^60], so that no product or sum of four products overflows or
// underflows in binary32 (formulas are measured, not the range of the format).
bool moderate(const Elem& e) {
  for (size_t j = 0; j < e.types->size(); ++j) {
    const ir::Type& t = (*e.types)[j];
    if (!t.is_float()) continue;
    for (int c = 0; c < t.width; ++c) {
      double a = std::fabs(e.d(static_cast<int>(j), c));
      if (a != 0 && (a < 0x1p-60 || a > 0x1p60)) return false;
    }
  }
  return true;
}

double dot_d(const Elem& e, int a, int b, int n) {
  double s = 0;
  for (int c = 0; c < n; ++c) s = c == 0 ? e.d(a, c) * e.d(b, c) : s + e.d(a, c) * e.d(b, c);
  return s;
}
double dot_abs(const Elem& e, int a, int b, int n) {
  double s = 0;
  for (int c = 0; c < n; ++c) s += std::fabs(e.d(a, c) * e.d(b, c));
  return s;
}

// Unit vectors (normalized on the host in double, rounded to float) for half the elements
// of every Float3 / Float4 input, so reflect and refract see realistic inputs; the other
// half are hard and random values.
void unit_vectors(Rng& rng, int64_t n, const std::vector<ir::Type>& types, std::vector<Words>& out,
                  const std::vector<Domain>& domains) {
  generate_inputs(rng, n, types, domains, out);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int64_t e = n / 2; e < n; ++e)
    for (size_t j = 0; j < types.size(); ++j) {
      int w = types[j].width;
      if (!types[j].is_float() || w < 2) continue;
      double v[4], len = 0;
      for (int c = 0; c < w; ++c) {
        v[c] = g(rng);
        len += v[c] * v[c];
      }
      len = std::sqrt(len);
      for (int c = 0; c < w; ++c)
        out[j][static_cast<size_t>(e * w + c)] = bits_of(static_cast<float>(v[c] / len));
    }
}

// Whole-vector hard inputs: zero vectors, tiny and huge vectors, one infinite or NaN
// component. Written over the first elements of every float vector input.
void vector_specials(int64_t n, const std::vector<ir::Type>& types, std::vector<Words>& out) {
  const std::vector<std::array<float, 4>> vs = {{0, 0, 0, 0},
                                                {-0.0f, 0, -0.0f, 0},
                                                {1e-30f, 0, 0, 0},
                                                {1e-20f, 1e-20f, 0, 0},
                                                {FLT_MAX, 0, 0, 0},
                                                {3e38f, 3e38f, 0, 0},
                                                {1e19f, 1e19f, 1e19f, 1e19f},
                                                {INFINITY, 0, 0, 0},
                                                {NAN, 1, 0, 0},
                                                {1, 0, 0, 0},
                                                {0, 1, 0, 0},
                                                {0, 0, 1, 0},
                                                {0, 0, -1, 0},
                                                {1e-45f, 0, 0, 0},
                                                {-1, -1, -1, -1}};
  for (size_t j = 0; j < types.size(); ++j) {
    int w = types[j].width;
    if (!types[j].is_float() || w < 2) continue;
    for (size_t a = 0; a < vs.size(); ++a)
      for (size_t b = 0; b < vs.size(); ++b) {
        // element (a, b): input 0 gets vs[a], input 1 vs[b], others vs[(a + b) % size]
        int64_t e = static_cast<int64_t>(a * vs.size() + b);
        if (e >= n / 4) continue;
        size_t pick = j == 0 ? a : j == 1 ? b : (a + b) % vs.size();
        for (int c = 0; c < w; ++c)
          out[j][static_cast<size_t>(e * w + c)] = bits_of(vs[pick][static_cast<size_t>(c)]);
      }
  }
}

Case geometry_case() {
  Case k;
  k.name = "geometry";
  k.category = "geometry";
  k.domains = {Domain{-10, 10}, Domain{-10, 10}, Domain{-10, 10}};
  k.generate = [d = k.domains](Rng& rng, int64_t n, const std::vector<ir::Type>& t,
                               std::vector<Words>& out) {
    unit_vectors(rng, n, t, out, d);
    vector_specials(n, t, out);
  };
  k.build = [] {
    return program("geometry", [] {
      Input<Float4> a("a");
      Input<Float4> b("b");
      Input<Float4> t("t");
      Output<Float> dot4("dot4"), dot3("dot3"), dot2("dot2"), len4("len4"), len3("len3"),
          len2("len2"), dist3("dist3");
      Output<Float3> cross3("cross3"), norm3("norm3");
      Output<Float4> norm4("norm4");
      Output<Float2> norm2("norm2");
      Output<Float4> lerp4("lerp4"), lerps("lerp_scalar_t"), clamp4("clamp4"),
          clamps("clamp_scalar");
      Output<Float> lerp1("lerp1");
      Float3 a3 = a(0, 1, 2), b3 = b(0, 1, 2);
      Float2 a2 = a(0, 1), b2 = b(0, 1);
      dot4 = dot(a, b);
      dot3 = dot(a3, b3);
      dot2 = dot(a2, b2);
      len4 = length(a);
      len3 = length(a3);
      len2 = length(a2);
      dist3 = distance(a3, b3);
      cross3 = cross(a3, b3);
      norm3 = normalize(a3);
      norm4 = normalize(a);
      norm2 = normalize(a2);
      lerp4 = lerp(a, b, t);
      lerps = lerp(a, b, Float(t.x()));
      lerp1 = lerp(Float(a.x()), Float(b.x()), Float(t.x()));
      clamp4 = clamp(a, b, t);
      clamps = clamp(a, -1.0f, 1.0f);
    });
  };
  auto add = [&](const char* op, const char* form, int out,
                 std::function<double(const Elem&, int)> f,
                 std::function<double(const Elem&, int)> scale = {},
                 std::function<bool(const Elem&, int)> dom = {}) {
    Check ch;
    ch.op = op;
    ch.category = "geometry";
    ch.form = form;
    ch.output = out;
    ch.ref = std::move(f);
    ch.scale = std::move(scale);
    ch.fast_domain = [dom](const Elem& e, int c) { return moderate(e) && (!dom || dom(e, c)); };
    k.checks.push_back(ch);
  };
  for (int n : {4, 3, 2}) {
    const char* form = n == 4 ? "4-vector" : n == 3 ? "3-vector" : "2-vector";
    add(
        "dot", form,
        n == 4   ? 0
        : n == 3 ? 1
                 : 2,
        [n](const Elem& e, int) { return dot_d(e, 0, 1, n); },
        [n](const Elem& e, int) { return dot_abs(e, 0, 1, n); });
  }
  for (int n : {4, 3, 2}) {
    const char* form = n == 4 ? "4-vector" : n == 3 ? "3-vector" : "2-vector";
    add("length", form,
        n == 4   ? 3
        : n == 3 ? 4
                 : 5,
        [n](const Elem& e, int) { return std::sqrt(dot_d(e, 0, 0, n)); });
  }
  add("distance", "3-vector", 6, [](const Elem& e, int) {
    double s = 0;
    for (int c = 0; c < 3; ++c) {
      double d = e.d(0, c) - e.d(1, c);
      s = c == 0 ? d * d : s + d * d;
    }
    return std::sqrt(s);
  });
  add(
      "cross", "3-vector", 7,
      [](const Elem& e, int c) {
        int i = (c + 1) % 3, j = (c + 2) % 3;
        return e.d(0, i) * e.d(1, j) - e.d(0, j) * e.d(1, i);
      },
      [](const Elem& e, int c) {
        int i = (c + 1) % 3, j = (c + 2) % 3;
        return std::fabs(e.d(0, i) * e.d(1, j)) + std::fabs(e.d(0, j) * e.d(1, i));
      });
  for (int n : {3, 4, 2}) {
    const char* form = n == 4 ? "4-vector" : n == 3 ? "3-vector" : "2-vector";
    add(
        "normalize", form,
        n == 3   ? 8
        : n == 4 ? 9
                 : 10,
        [n](const Elem& e, int c) { return e.d(0, c) / std::sqrt(dot_d(e, 0, 0, n)); }, {},
        [n](const Elem& e, int) {  // the squared length neither overflows nor underflows
          double s = dot_d(e, 0, 0, n);
          return s >= static_cast<double>(FLT_MIN) && s <= static_cast<double>(FLT_MAX);
        });
  }
  auto lerp_ref = [](double a, double b, double t) { return a + (b - a) * t; };
  auto lerp_scale = [](double a, double b, double t) {
    return std::fabs(a) + (std::fabs(a) + std::fabs(b)) * std::fabs(t);
  };
  add(
      "lerp", "4-vector", 11,
      [=](const Elem& e, int c) { return lerp_ref(e.d(0, c), e.d(1, c), e.d(2, c)); },
      [=](const Elem& e, int c) { return lerp_scale(e.d(0, c), e.d(1, c), e.d(2, c)); });
  add(
      "lerp", "scalar t", 12,
      [=](const Elem& e, int c) { return lerp_ref(e.d(0, c), e.d(1, c), e.d(2, 0)); },
      [=](const Elem& e, int c) { return lerp_scale(e.d(0, c), e.d(1, c), e.d(2, 0)); });
  add("clamp", "4-vector", 13,
      [](const Elem& e, int c) { return r_min(r_max(e.d(0, c), e.d(1, c)), e.d(2, c)); });
  add("clamp", "host bounds", 14,
      [](const Elem& e, int c) { return r_min(r_max(e.d(0, c), -1.0), 1.0); });
  add(
      "lerp", "scalar", 15,
      [=](const Elem& e, int) { return lerp_ref(e.d(0, 0), e.d(1, 0), e.d(2, 0)); },
      [=](const Elem& e, int) { return lerp_scale(e.d(0, 0), e.d(1, 0), e.d(2, 0)); });
  return k;
}

// reflect and refract on 3-vectors, as in GLSL (Math.h).
Case optics_case() {
  Case k;
  k.name = "optics";
  k.category = "geometry";
  k.domains = {Domain{-10, 10}, Domain{-10, 10}, Domain{0.2, 3}};
  k.generate = [d = k.domains](Rng& rng, int64_t n, const std::vector<ir::Type>& t,
                               std::vector<Words>& out) {
    unit_vectors(rng, n, t, out, d);
    vector_specials(n, t, out);
  };
  k.build = [] {
    return program("optics", [] {
      Input<Float3> i("i");
      Input<Float3> nn("n");
      Input<Float> eta("eta");
      Output<Float3> refl("reflect3"), refr("refract3");
      Output<Float2> refl2("reflect2");
      refl = reflect(i, nn);
      refr = refract(i, nn, eta);
      refl2 = reflect(Float2(i(0, 1)), Float2(nn(0, 1)));
    });
  };
  auto reflect_ref = [](const Elem& e, int c, int w) {
    double d = dot_d(e, 1, 0, w);
    return e.d(0, c) - (2.0 * d) * e.d(1, c);
  };
  auto reflect_scale = [](const Elem& e, int c, int w) {
    return std::fabs(e.d(0, c)) + 2.0 * dot_abs(e, 1, 0, w) * std::fabs(e.d(1, c));
  };
  Check r3;
  r3.op = "reflect";
  r3.category = "geometry";
  r3.form = "3-vector";
  r3.output = 0;
  r3.ref = [=](const Elem& e, int c) { return reflect_ref(e, c, 3); };
  r3.scale = [=](const Elem& e, int c) { return reflect_scale(e, c, 3); };
  r3.fast_domain = [](const Elem& e, int) { return moderate(e); };
  Check r2 = r3;
  r2.form = "2-vector";
  r2.output = 2;
  r2.ref = [=](const Elem& e, int c) { return reflect_ref(e, c, 2); };
  r2.scale = [=](const Elem& e, int c) { return reflect_scale(e, c, 2); };
  Check rf;
  rf.op = "refract";
  rf.category = "geometry";
  rf.form = "3-vector";
  rf.output = 1;
  rf.ref = [](const Elem& e, int c) {
    double d = dot_d(e, 1, 0, 3), eta = e.d(2, 0);
    double kk = 1.0 - eta * eta * (1.0 - d * d);
    double r = eta * e.d(0, c) - (eta * d + std::sqrt(std::max(kk, 0.0))) * e.d(1, c);
    return kk < 0 ? 0.0 : r;
  };
  // The formula is well conditioned for unit vectors away from grazing refraction (|k| > 0.05;
  // near k = 0, sqrt(k) amplifies the rounding of k).
  rf.fast_domain = [](const Elem& e, int) {
    if (!moderate(e)) return false;
    double li = dot_d(e, 0, 0, 3), ln = dot_d(e, 1, 1, 3);
    double d = dot_d(e, 1, 0, 3), eta = e.d(2, 0);
    double kk = 1.0 - eta * eta * (1.0 - d * d);
    return std::fabs(li - 1) < 1e-6 && std::fabs(ln - 1) < 1e-6 && std::fabs(kk) > 0.05;
  };
  rf.scale = [](const Elem& e, int) {
    double eta = e.d(2, 0), d = dot_d(e, 1, 0, 3);
    return std::fabs(eta) * (1 + std::fabs(d)) + 1;
  };
  k.checks = {r3, rf, r2};
  return k;
}

// Swizzles (reads in any order, repeated components, swizzles of swizzles and of temporaries)
// and write masks, on Float4 and Int4: exact data movement.
Case swizzle_case() {
  Case k;
  k.name = "swizzle";
  k.category = "swizzle";
  k.build = [] {
    return program("swizzle", [] {
      Input<Float4> a("a");
      Input<Int4> n("n");
      Output<Float3> s1("zxy");
      Output<Float2> s2("yx");
      Output<Float4> s3("wzyx");
      Output<Float4> s4("xxyy");
      Output<Float> s5("w");
      Output<Int4> s6("int_wyxz");
      Output<Float2> s7("wzyx_yx");
      Output<Float3> s8("neg_zxy");
      Output<Float4> m1("mask_zx");
      Output<Int4> m2("int_mask_wy");
      s1 = a(2, 0, 1);
      s2 = a(1, 0);
      s3 = a(3, 2, 1, 0);
      s4 = a(0, 0, 1, 1);
      s5 = a.w();
      s6 = n(3, 1, 0, 2);
      s7 = Float4(a(3, 2, 1, 0))(1, 0);
      s8 = Float4(-a)(2, 0, 1);
      Float4 v = a;
      v(2, 0) = a(0, 1);
      m1 = v;
      Int4 q = n;
      q(3, 1) = n(1, 3);
      m2 = q;
    });
  };
  auto add = [&](const char* op, const char* form, int out, std::vector<int> from, int input = 0,
                 bool negate = false) {
    Check ch;
    ch.op = op;
    ch.category = "swizzle";
    ch.form = form;
    ch.output = out;
    ch.ref = [from, input, negate](const Elem& e, int c) {
      double v = e.d(input, from[static_cast<size_t>(c)]);
      return negate ? -v : v;
    };
    k.checks.push_back(ch);
  };
  add("swizzle", "v(2, 0, 1)", 0, {2, 0, 1});
  add("swizzle", "v(1, 0)", 1, {1, 0});
  add("swizzle", "v(3, 2, 1, 0)", 2, {3, 2, 1, 0});
  add("swizzle", "v(0, 0, 1, 1)", 3, {0, 0, 1, 1});
  add("swizzle", "v.w()", 4, {3});
  add("swizzle", "int v(3, 1, 0, 2)", 5, {3, 1, 0, 2}, 1);
  add("swizzle", "v(3, 2, 1, 0)(1, 0)", 6, {2, 3});
  add("swizzle", "(-v)(2, 0, 1)", 7, {2, 0, 1}, 0, true);
  add("write mask", "v(2, 0) = a(0, 1)", 8, {1, 1, 0, 3});
  add("write mask", "int q(3, 1) = n(1, 3)", 9, {0, 3, 2, 1}, 1);
  return k;
}

}  // namespace

bool exact_reference(const std::string& op) {
  static const char* const kExact[] = {"neg",      "abs",   "sign",    "floor",     "ceil",  "trunc",
                                       "fract",    "sqrt",  "add",     "sub",       "mul",
                                       "div",      "min",   "max",     "select",    "to_float",
                                       "as_float", "clamp", "swizzle", "write mask"};
  for (const char* e : kExact)
    if (op == e) return true;
  return false;
}

std::vector<Case> operation_cases() {
  std::vector<Case> v;
  v.push_back(float_exact_unary());
  v.push_back(float_exact_binary());
  for (Case& c : transcendental_cases()) v.push_back(std::move(c));
  v.push_back(int_unary());
  // Two kernels: a GLSL context may not have the texture units for 36 outputs' previous values.
  v.push_back(int_binary("int_arith", {"add", "sub", "mul", "div", "rem", "min", "max"}));
  v.push_back(int_binary("int_bits", {"and", "or", "xor", "shl", "shr", "shr_logical"}));
  v.push_back(int_binary("int_unsigned", {"mul_hi_unsigned"}));
  v.push_back(compare_case<float>("compare_float", "", Domain{-4, 4}));
  v.push_back(compare_case<int32_t>("compare_int", "int.", Domain{-4, 4, true}));
  v.push_back(bool_case());
  v.push_back(select_case());
  v.push_back(swizzle_case());
  v.push_back(conversion_case());
  v.push_back(geometry_case());
  v.push_back(optics_case());
  return v;
}

}  // namespace rill::conformance
