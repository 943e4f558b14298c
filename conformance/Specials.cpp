// The hard-input table: what every operation gives for the values where languages and
// drivers disagree (division by zero, NaN, signed zeros, overflow, INT_MIN / -1, shift counts
// of 32 and more, float-to-int of NaN and huge values, normalize of a zero vector, ...).
//
// The results are Rill's documented semantics (docs/conformance.md): the suite checks that the
// reference interpreter and every backend give exactly these bits in the strict mode (any NaN
// matches any NaN; denormal results may be flushed by a backend that flushes), and in the
// double mode except where an entry says strict only.
#include <cfloat>
#include <climits>
#include <cmath>

#include "Suite.h"

namespace rill::conformance {

namespace {

constexpr uint32_t kNaN = 0x7fc00000u;  // "any NaN" in expectations
constexpr uint32_t kInf = 0x7f800000u, kNegInf = 0xff800000u;
constexpr uint32_t kNegZero = 0x80000000u;

uint32_t fb(float f) {
  return bits_of(f);
}
uint32_t ib(int32_t i) {
  return static_cast<uint32_t>(i);
}

using Eval = std::function<void(const Float&, const Float&, const Float&, const Int&, const Int&,
                                Float4&, Int&)>;

// Float results of f(x) / f(x, y).
template <class F>
Eval f1(F f) {
  return [f](const Float& x, const Float&, const Float&, const Int&, const Int&, Float4& rf, Int&) {
    rf.x() = f(x);
  };
}
template <class F>
Eval f2(F f) {
  return [f](const Float& x, const Float& y, const Float&, const Int&, const Int&, Float4& rf,
             Int&) { rf.x() = f(x, y); };
}
// Int results of f(i, j), of f(x, y) (comparisons, conversions).
template <class F>
Eval i2(F f) {
  return [f](const Float&, const Float&, const Float&, const Int& i, const Int& j, Float4&,
             Int& ri) { ri = f(i, j); };
}
template <class F>
Eval fi(F f) {
  return [f](const Float& x, const Float& y, const Float&, const Int&, const Int&, Float4&,
             Int& ri) { ri = f(x, y); };
}
// 3-vector results of f(v), v = (x, y, z).
template <class F>
Eval v3(F f) {
  return [f](const Float& x, const Float& y, const Float& z, const Int&, const Int&, Float4& rf,
             Int&) { rf(0, 1, 2) = f(Float3(x, y, z)); };
}

Int to01(const Bool& b) {
  return select(b, Int(1), Int(0));
}

std::vector<Special> make_specials() {
  std::vector<Special> s;
  auto F = [&](std::string label, Eval e, float x, float y, uint32_t want, std::string text) {
    Special sp;
    sp.label = std::move(label);
    sp.category = "float";
    sp.eval = std::move(e);
    sp.x = x;
    sp.y = y;
    sp.expected = {want};
    sp.expected_text = std::move(text);
    s.push_back(sp);
  };
  auto I = [&](std::string label, Eval e, int32_t i, int32_t j, int32_t want, std::string text,
               const char* cat = "int") {
    Special sp;
    sp.label = std::move(label);
    sp.category = cat;
    sp.eval = std::move(e);
    sp.i = i;
    sp.j = j;
    sp.int_result = true;
    sp.expected = {ib(want)};
    sp.expected_text = std::move(text);
    s.push_back(sp);
  };
  auto X = [&](std::string label, Eval e, float x, float y, int32_t want, std::string text) {
    I(std::move(label), std::move(e), 0, 0, want, std::move(text), "compare/convert");
    s.back().x = x;
    s.back().y = y;
  };
  auto V = [&](std::string label, Eval e, float x, float y, float z, std::vector<uint32_t> want,
               std::string text, bool strict_only = false) {
    Special sp;
    sp.label = std::move(label);
    sp.category = "vector";
    sp.eval = std::move(e);
    sp.x = x;
    sp.y = y;
    sp.z = z;
    sp.width = 3;
    sp.expected = std::move(want);
    sp.expected_text = std::move(text);
    sp.strict_only = strict_only;
    s.push_back(sp);
  };
  const float inf = INFINITY, nan = NAN;
  auto div = [](const Float& a, const Float& b) { return a / b; };
  auto sub = [](const Float& a, const Float& b) { return a - b; };
  auto add = [](const Float& a, const Float& b) { return a + b; };
  auto mul = [](const Float& a, const Float& b) { return a * b; };

  // ---- float arithmetic
  F("1 / +0", f2(div), 1, 0.0f, kInf, "+inf");
  F("1 / -0", f2(div), 1, -0.0f, kNegInf, "-inf");
  F("0 / 0", f2(div), 0, 0, kNaN, "NaN");
  F("inf / inf", f2(div), inf, inf, kNaN, "NaN");
  F("inf - inf", f2(sub), inf, inf, kNaN, "NaN");
  F("inf * 0", f2(mul), inf, 0, kNaN, "NaN");
  F("FLT_MAX * 2", f2(mul), FLT_MAX, 2, kInf, "+inf (overflow)");
  F("-FLT_MAX - FLT_MAX", f2(sub), -FLT_MAX, FLT_MAX, kNegInf, "-inf");
  F("FLT_MIN * 0.5", f2(mul), FLT_MIN, 0.5f, 0x00400000u, "2^-127 (denormal; +0 where flushed)");
  F("1e-45 + 0", f2(add), 1e-45f, 0, 0x00000001u, "1e-45 (denormal; +0 where flushed)");
  F("-0 + 0", f2(add), -0.0f, 0, 0u, "+0");
  F("-0 - 0", f2(sub), -0.0f, 0, kNegZero, "-0");
  F("-0 * 5", f2(mul), -0.0f, 5, kNegZero, "-0");
  F("-(+0)", f1([](const Float& a) { return -a; }), 0, 0, kNegZero, "-0");
  // ---- square roots
  F("sqrt(-1)", f1([](const Float& a) { return sqrt(a); }), -1, 0, kNaN, "NaN");
  F("sqrt(-0)", f1([](const Float& a) { return sqrt(a); }), -0.0f, 0, kNegZero, "-0");
  F("sqrt(+inf)", f1([](const Float& a) { return sqrt(a); }), inf, 0, kInf, "+inf");
  F("sqrt(-inf)", f1([](const Float& a) { return sqrt(a); }), -inf, 0, kNaN, "NaN");
  F("rsqrt(+0)", f1([](const Float& a) { return rsqrt(a); }), 0, 0, kInf, "+inf");
  F("rsqrt(-0)", f1([](const Float& a) { return rsqrt(a); }), -0.0f, 0, kNegInf,
    "-inf (1 / sqrt(-0))");
  F("rsqrt(-1)", f1([](const Float& a) { return rsqrt(a); }), -1, 0, kNaN, "NaN");
  F("rsqrt(+inf)", f1([](const Float& a) { return rsqrt(a); }), inf, 0, 0u, "+0");
  // ---- exponentials and logarithms
  auto lg = [](const Float& a) { return log(a); };
  auto lg2 = [](const Float& a) { return log2(a); };
  auto ex = [](const Float& a) { return exp(a); };
  auto ex2 = [](const Float& a) { return exp2(a); };
  F("log(-1)", f1(lg), -1, 0, kNaN, "NaN");
  F("log(+0)", f1(lg), 0, 0, kNegInf, "-inf");
  F("log(-0)", f1(lg), -0.0f, 0, kNegInf, "-inf");
  F("log(+inf)", f1(lg), inf, 0, kInf, "+inf");
  F("log(-inf)", f1(lg), -inf, 0, kNaN, "NaN");
  F("log(NaN)", f1(lg), nan, 0, kNaN, "NaN");
  F("log(1)", f1(lg), 1, 0, 0u, "+0");
  F("log2(1)", f1(lg2), 1, 0, 0u, "+0");
  F("log2(8)", f1(lg2), 8, 0, fb(3), "3");
  F("log2(-0)", f1(lg2), -0.0f, 0, kNegInf, "-inf");
  F("log2(-1e-45)", f1(lg2), -1e-45f, 0, kNaN, "NaN");
  F("exp(-inf)", f1(ex), -inf, 0, 0u, "+0");
  F("exp(+inf)", f1(ex), inf, 0, kInf, "+inf");
  F("exp(NaN)", f1(ex), nan, 0, kNaN, "NaN");
  F("exp(100)", f1(ex), 100, 0, kInf, "+inf (overflow)");
  F("exp(-200)", f1(ex), -200, 0, 0u, "+0 (underflow)");
  F("exp(0)", f1(ex), 0, 0, fb(1), "1");
  F("exp(-0)", f1(ex), -0.0f, 0, fb(1), "1");
  F("exp2(128)", f1(ex2), 128, 0, kInf, "+inf");
  F("exp2(-150)", f1(ex2), -150, 0, 0u, "+0 (2^-150 rounds to even)");
  F("exp2(-149)", f1(ex2), -149, 0, 0x00000001u, "2^-149 (denormal; +0 where flushed)");
  F("exp2(10)", f1(ex2), 10, 0, fb(1024), "1024");
  F("exp2(-inf)", f1(ex2), -inf, 0, 0u, "+0");
  // ---- pow (C99 Annex F)
  auto pw = [](const Float& a, const Float& b) { return pow(a, b); };
  F("pow(+0, -1)", f2(pw), 0, -1, kInf, "+inf");
  F("pow(-0, -1)", f2(pw), -0.0f, -1, kNegInf, "-inf (odd integer exponent keeps the sign)");
  F("pow(-0, -2)", f2(pw), -0.0f, -2, kInf, "+inf");
  F("pow(+0, 3)", f2(pw), 0, 3, 0u, "+0");
  F("pow(-8, 1/3)", f2(pw), -8, 1.0f / 3, kNaN, "NaN (negative base, non-integer exponent)");
  F("pow(-2, 3)", f2(pw), -2, 3, fb(-8), "-8");
  F("pow(-2, 2)", f2(pw), -2, 2, fb(4), "4");
  F("pow(2, 10)", f2(pw), 2, 10, fb(1024), "1024");
  F("pow(NaN, 0)", f2(pw), nan, 0, fb(1), "1");
  F("pow(1, NaN)", f2(pw), 1, nan, fb(1), "1");
  F("pow(NaN, 1)", f2(pw), nan, 1, kNaN, "NaN");
  F("pow(-1, +inf)", f2(pw), -1, inf, fb(1), "1");
  F("pow(0, 0)", f2(pw), 0, 0, fb(1), "1");
  F("pow(+inf, -1)", f2(pw), inf, -1, 0u, "+0");
  F("pow(+inf, 0.5)", f2(pw), inf, 0.5f, kInf, "+inf");
  F("pow(0.5, -inf)", f2(pw), 0.5f, -inf, kInf, "+inf");
  F("pow(0.5, +inf)", f2(pw), 0.5f, inf, 0u, "+0");
  F("pow(2, 200)", f2(pw), 2, 200, kInf, "+inf (overflow)");
  // ---- trigonometry
  auto sn = [](const Float& a) { return sin(a); };
  auto cs = [](const Float& a) { return cos(a); };
  auto tn = [](const Float& a) { return tan(a); };
  auto at = [](const Float& a) { return atan(a); };
  auto at2 = [](const Float& a, const Float& b) { return atan2(a, b); };
  F("sin(+inf)", f1(sn), inf, 0, kNaN, "NaN");
  F("sin(NaN)", f1(sn), nan, 0, kNaN, "NaN");
  F("sin(-0)", f1(sn), -0.0f, 0, kNegZero, "-0");
  F("cos(-inf)", f1(cs), -inf, 0, kNaN, "NaN");
  F("cos(0)", f1(cs), 0, 0, fb(1), "1");
  F("tan(-0)", f1(tn), -0.0f, 0, kNegZero, "-0");
  F("tan(inf)", f1(tn), inf, 0, kNaN, "NaN");
  F("atan(+inf)", f1(at), inf, 0, 0x3fc90fdbu, "pi/2 (1.57079637)");
  F("atan(-inf)", f1(at), -inf, 0, 0xbfc90fdbu, "-pi/2");
  F("atan(-0)", f1(at), -0.0f, 0, kNegZero, "-0");
  F("atan(NaN)", f1(at), nan, 0, kNaN, "NaN");
  F("atan2(+0, -0)", f2(at2), 0, -0.0f, 0x40490fdbu, "pi (3.14159274)");
  F("atan2(-0, -0)", f2(at2), -0.0f, -0.0f, 0xc0490fdbu, "-pi");
  F("atan2(+0, +0)", f2(at2), 0, 0, 0u, "+0");
  F("atan2(-0, +0)", f2(at2), -0.0f, 0, kNegZero, "-0");
  F("atan2(+inf, +inf)", f2(at2), inf, inf, 0x3f490fdbu, "pi/4");
  F("atan2(-inf, -inf)", f2(at2), -inf, -inf, 0xc016cbe4u, "-3pi/4");
  F("atan2(1, 0)", f2(at2), 1, 0, 0x3fc90fdbu, "pi/2");
  F("atan2(-1, -inf)", f2(at2), -1, -inf, 0xc0490fdbu, "-pi");
  F("atan2(NaN, 1)", f2(at2), nan, 1, kNaN, "NaN");
  // ---- min, max, sign, abs: min(a, b) = b < a ? b : a, max(a, b) = a < b ? b : a
  auto mn = [](const Float& a, const Float& b) { return min(a, b); };
  auto mx = [](const Float& a, const Float& b) { return max(a, b); };
  F("min(NaN, 1)", f2(mn), nan, 1, kNaN, "NaN (the first operand)");
  F("min(1, NaN)", f2(mn), 1, nan, fb(1), "1 (the first operand)");
  F("max(NaN, 1)", f2(mx), nan, 1, kNaN, "NaN");
  F("max(1, NaN)", f2(mx), 1, nan, fb(1), "1");
  F("min(-0, +0)", f2(mn), -0.0f, 0, kNegZero, "-0 (the first operand)");
  F("min(+0, -0)", f2(mn), 0, -0.0f, 0u, "+0");
  F("max(-0, +0)", f2(mx), -0.0f, 0, kNegZero, "-0");
  F("sign(-0)", f1([](const Float& a) { return sign(a); }), -0.0f, 0, 0u, "+0");
  F("sign(NaN)", f1([](const Float& a) { return sign(a); }), nan, 0, 0u, "+0");
  F("sign(-inf)", f1([](const Float& a) { return sign(a); }), -inf, 0, fb(-1), "-1");
  F("abs(-0)", f1([](const Float& a) { return abs(a); }), -0.0f, 0, 0u, "+0");
  F("abs(-inf)", f1([](const Float& a) { return abs(a); }), -inf, 0, kInf, "+inf");
  // ---- rounding
  F("floor(-0.5)", f1([](const Float& a) { return floor(a); }), -0.5f, 0, fb(-1), "-1");
  F("floor(-0)", f1([](const Float& a) { return floor(a); }), -0.0f, 0, kNegZero, "-0");
  F("ceil(-0.5)", f1([](const Float& a) { return ceil(a); }), -0.5f, 0, kNegZero, "-0");
  F("floor(+inf)", f1([](const Float& a) { return floor(a); }), inf, 0, kInf, "+inf");
  F("fract(-0.25)", f1([](const Float& a) { return fract(a); }), -0.25f, 0, fb(0.75f), "0.75");
  F("fract(-1e-30)", f1([](const Float& a) { return fract(a); }), -1e-30f, 0, fb(1),
    "1 (x - floor(x) rounds up to 1)");
  F("fract(+inf)", f1([](const Float& a) { return fract(a); }), inf, 0, kNaN, "NaN");
  F("mod(5, 0)", f2([](const Float& a, const Float& b) { return mod(a, b); }), 5, 0, kNaN, "NaN");
  F("mod(-1, 3)", f2([](const Float& a, const Float& b) { return mod(a, b); }), -1, 3, fb(2), "2");
  F("mod(5.5, -2)", f2([](const Float& a, const Float& b) { return mod(a, b); }), 5.5f, -2,
    fb(-0.5f), "-0.5");
  F("mod(1, +inf)", f2([](const Float& a, const Float& b) { return mod(a, b); }), 1, inf, kNaN,
    "NaN (x - y * floor(x / y) = 1 - inf * 0)");
  F("clamp(NaN, 0, 1)", f1([](const Float& a) { return clamp(a, 0.0f, 1.0f); }), nan, 0, kNaN,
    "NaN");
  F("lerp(inf, 1, 0)", f2([](const Float& a, const Float& b) { return lerp(a, b, 0.0f); }), inf, 1,
    kNaN, "NaN (a + (b - a) * t)");

  // ---- comparisons (1 true, 0 false) and conversions
  auto lt = [](const Float& a, const Float& b) { return to01(a < b); };
  auto eq = [](const Float& a, const Float& b) { return to01(a == b); };
  auto ne = [](const Float& a, const Float& b) { return to01(a != b); };
  auto ge = [](const Float& a, const Float& b) { return to01(a >= b); };
  X("NaN == NaN", fi(eq), nan, nan, 0, "false");
  X("NaN != NaN", fi(ne), nan, nan, 1, "true");
  X("NaN < 1", fi(lt), nan, 1, 0, "false");
  X("NaN >= 1", fi(ge), nan, 1, 0, "false");
  X("-0 == +0", fi(eq), -0.0f, 0, 1, "true");
  X("-0 < +0", fi(lt), -0.0f, 0, 0, "false");
  X("-inf < FLT_MAX", fi(lt), -inf, FLT_MAX, 1, "true");
  auto ti = [](const Float& a, const Float&) { return to_int(a); };
  auto ai = [](const Float& a, const Float&) { return as_int(a); };
  X("to_int(NaN)", fi(ti), nan, 0, 0, "0");
  X("to_int(+inf)", fi(ti), inf, 0, INT_MAX, "INT_MAX");
  X("to_int(-inf)", fi(ti), -inf, 0, INT_MIN, "INT_MIN");
  X("to_int(1e10)", fi(ti), 1e10f, 0, INT_MAX, "INT_MAX (saturates)");
  X("to_int(-1e10)", fi(ti), -1e10f, 0, INT_MIN, "INT_MIN (saturates)");
  X("to_int(2147483520)", fi(ti), 2147483520.0f, 0, 2147483520, "2147483520");
  X("to_int(2^31)", fi(ti), 2147483648.0f, 0, INT_MAX, "INT_MAX");
  X("to_int(-2^31)", fi(ti), -2147483648.0f, 0, INT_MIN, "INT_MIN");
  X("to_int(-1.5)", fi(ti), -1.5f, 0, -1, "-1 (toward zero)");
  X("to_int(2.5)", fi(ti), 2.5f, 0, 2, "2");
  X("to_int(-0.99999994)", fi(ti), -0.99999994f, 0, 0, "0");
  X("as_int(-0)", fi(ai), -0.0f, 0, INT_MIN, "INT_MIN (0x80000000)");
  X("as_int(-inf)", fi(ai), -inf, 0, static_cast<int32_t>(0xff800000u), "0xff800000");
  auto tf = [](const Float&, const Float&, const Float&, const Int& i, const Int&, Float4& rf,
               Int&) { rf.x() = to_float(i); };
  auto af = [](const Float&, const Float&, const Float&, const Int& i, const Int&, Float4& rf,
               Int&) { rf.x() = as_float(i); };
  auto FI = [&](std::string label, Eval e, int32_t i, uint32_t want, std::string text) {
    F(std::move(label), std::move(e), 0, 0, want, std::move(text));
    s.back().i = i;
    s.back().category = "compare/convert";
  };
  FI("to_float(INT_MAX)", tf, INT_MAX, 0x4f000000u, "2147483648 (rounded to nearest)");
  FI("to_float(INT_MIN)", tf, INT_MIN, 0xcf000000u, "-2147483648");
  FI("to_float(16777217)", tf, 16777217, 0x4b800000u, "16777216 (ties to even)");
  FI("as_float(0x7f800000)", af, 0x7f800000, kInf, "+inf");
  FI("as_float(1)", af, 1, 0x00000001u, "1e-45 (denormal; +0 where flushed)");

  // ---- integers: wrap around; x / 0 = 0, x % 0 = 0; shifts use the low 5 bits of the count
  auto idv = [](const Int& a, const Int& b) { return a / b; };
  auto irm = [](const Int& a, const Int& b) { return a % b; };
  auto ishl = [](const Int& a, const Int& b) { return a << b; };
  auto ishr = [](const Int& a, const Int& b) { return a >> b; };
  I("INT_MIN / -1", i2(idv), INT_MIN, -1, INT_MIN, "INT_MIN (wraps)");
  I("INT_MIN % -1", i2(irm), INT_MIN, -1, 0, "0");
  I("7 / 0", i2(idv), 7, 0, 0, "0");
  I("7 % 0", i2(irm), 7, 0, 0, "0");
  I("0 / 0", i2(idv), 0, 0, 0, "0");
  I("INT_MIN / 0", i2(idv), INT_MIN, 0, 0, "0");
  I("-7 / 2", i2(idv), -7, 2, -3, "-3 (toward zero)");
  I("-7 % 2", i2(irm), -7, 2, -1, "-1 (sign of the dividend)");
  I("7 % -2", i2(irm), 7, -2, 1, "1");
  I("INT_MIN / 2", i2(idv), INT_MIN, 2, -1073741824, "-1073741824");
  I("INT_MAX + 1", i2([](const Int& a, const Int& b) { return a + b; }), INT_MAX, 1, INT_MIN,
    "INT_MIN (wraps)");
  I("INT_MIN - 1", i2([](const Int& a, const Int& b) { return a - b; }), INT_MIN, 1, INT_MAX,
    "INT_MAX (wraps)");
  I("INT_MAX * 2", i2([](const Int& a, const Int& b) { return a * b; }), INT_MAX, 2, -2,
    "-2 (wraps)");
  I("65536 * 65536", i2([](const Int& a, const Int& b) { return a * b; }), 65536, 65536, 0,
    "0 (wraps)");
  I("-INT_MIN", i2([](const Int& a, const Int&) { return -a; }), INT_MIN, 0, INT_MIN, "INT_MIN");
  I("abs(INT_MIN)", i2([](const Int& a, const Int&) { return abs(a); }), INT_MIN, 0, INT_MIN,
    "INT_MIN");
  I("sign(INT_MIN)", i2([](const Int& a, const Int&) { return sign(a); }), INT_MIN, 0, -1, "-1");
  I("1 << 31", i2(ishl), 1, 31, INT_MIN, "INT_MIN");
  I("1 << 32", i2(ishl), 1, 32, 1, "1 (count 32 & 31 = 0)");
  I("1 << 33", i2(ishl), 1, 33, 2, "2");
  I("1 << -1", i2(ishl), 1, -1, INT_MIN, "INT_MIN (count -1 & 31 = 31)");
  I("-8 >> 1", i2(ishr), -8, 1, -4, "-4 (arithmetic)");
  I("-1 >> 40", i2(ishr), -1, 40, -1, "-1");
  I("INT_MIN >> 31", i2(ishr), INT_MIN, 31, -1, "-1");
  I("INT_MIN >> 32", i2(ishr), INT_MIN, 32, INT_MIN, "INT_MIN (count 0)");
  I("256 >> 36", i2(ishr), 256, 36, 16, "16 (count 4)");
  I("min(INT_MIN, INT_MAX)", i2([](const Int& a, const Int& b) { return min(a, b); }), INT_MIN,
    INT_MAX, INT_MIN, "INT_MIN");

  // ---- vectors
  auto nz = [](const Float3& v) { return normalize(v); };
  V("normalize(0, 0, 0)", v3(nz), 0, 0, 0, {kNaN, kNaN, kNaN}, "(NaN, NaN, NaN)");
  V("normalize(-0, 0, -0)", v3(nz), -0.0f, 0, -0.0f, {kNaN, kNaN, kNaN}, "(NaN, NaN, NaN)");
  V("normalize(1e-30, 0, 0)", v3(nz), 1e-30f, 0, 0, {kInf, kNaN, kNaN},
    "(+inf, NaN, NaN): the squared length underflows to 0 (double mode: (1, 0, 0))", true);
  V("normalize(FLT_MAX, 0, 0)", v3(nz), FLT_MAX, 0, 0, {0u, 0u, 0u},
    "(0, 0, 0): the squared length overflows to inf (double mode: (1, 0, 0))", true);
  V("normalize(0, 3, 4)", v3(nz), 0, 3, 4, {0u, fb(0.6f), fb(0.8f)}, "(0, 0.6, 0.8)");
  V("length(3e38, 3e38, 0)", v3([](const Float3& v) { return Float3(length(v), 0.0f, 0.0f); }),
    3e38f, 3e38f, 0, {kInf, 0u, 0u}, "+inf (overflow)");
  V("dot((inf, 0, 1), (0, 1, 1))",
    v3([](const Float3& v) { return Float3(dot(v, Float3(0.0f, 1.0f, 1.0f)), 0.0f, 0.0f); }), inf,
    0, 1, {kNaN, 0u, 0u}, "NaN (inf * 0)");
  V("cross((1, 0, 0), (0, 1, 0))",
    v3([](const Float3& v) { return cross(v, Float3(0.0f, 1.0f, 0.0f)); }), 1, 0, 0,
    {0u, 0u, fb(1)}, "(0, 0, 1)");
  V("reflect((1, -1, 0), (0, 1, 0))",
    v3([](const Float3& v) { return reflect(v, Float3(0.0f, 1.0f, 0.0f)); }), 1, -1, 0,
    {fb(1), fb(1), 0u}, "(1, 1, 0)");
  V("refract((0.8, -0.6, 0), (0, 1, 0), 1.5)",
    v3([](const Float3& v) { return refract(v, Float3(0.0f, 1.0f, 0.0f), Float(1.5f)); }), 0.8f,
    -0.6f, 0, {0u, 0u, 0u}, "(0, 0, 0): total internal reflection");
  return s;
}

}  // namespace

const std::vector<Special>& specials() {
  static const std::vector<Special> s = make_specials();
  return s;
}

// One kernel: element k evaluates entry k (chosen with RILL_IF on element_index(), its
// operands read from input streams so that nothing is folded on the host).
Case specials_case() {
  Case c;
  c.name = "specials";
  c.category = "special";
  c.elements = static_cast<int64_t>(specials().size());
  c.build = [] {
    return program("specials", [] {
      Input<Float> x("x");
      Input<Float> y("y");
      Input<Float> z("z");
      Input<Int> i("i");
      Input<Int> j("j");
      Output<Float4> rf("rf");
      Output<Int> ri("ri");
      Int k = element_index();
      Float4 f(0.0f);
      Int r = 0;
      const auto& all = specials();
      for (size_t e = 0; e < all.size(); ++e) {
        RILL_IF(k == static_cast<int32_t>(e)) {
          all[e].eval(x, y, z, i, j, f, r);
        }
        RILL_ENDIF;
      }
      rf = f;
      ri = r;
    });
  };
  c.generate = [](Rng&, int64_t n, const std::vector<ir::Type>& types, std::vector<Words>& out) {
    out.assign(types.size(), Words{});
    for (auto& w : out) w.assign(static_cast<size_t>(n), 0u);
    const auto& all = specials();
    for (size_t e = 0; e < all.size() && static_cast<int64_t>(e) < n; ++e) {
      out[0][e] = bits_of(all[e].x);
      out[1][e] = bits_of(all[e].y);
      out[2][e] = bits_of(all[e].z);
      out[3][e] = static_cast<uint32_t>(all[e].i);
      out[4][e] = static_cast<uint32_t>(all[e].j);
    }
  };
  return c;
}

}  // namespace rill::conformance
