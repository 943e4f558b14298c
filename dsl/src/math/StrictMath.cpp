// Rill's portable math routines, written in the DSL (see StrictMath.h).
//
// Each routine reduces its argument to a small interval exactly or nearly so (splitting
// constants like ln 2 and pi/4 into parts whose products with small integers are exact),
// evaluates a Taylor polynomial in Horner form there (the intervals are small enough that
// Taylor's truncation error stays far below half an ulp), and reconstructs the result.
// Everything is branch-free: special inputs are handled by selects at the end, which keeps
// GPU lanes together and makes the code identical on every backend.
#include "rill/StrictMath.h"

#include <cstdint>
#include <initializer_list>
#include <limits>

namespace rill::strict {

namespace {

constexpr int32_t kSignMask = std::numeric_limits<int32_t>::min();  // 0x80000000
constexpr int32_t kAbsMask = 0x7fffffff;
constexpr int32_t kInfBits = 0x7f800000;

constexpr float kLog2e = 1.44269504088896340736f;
// ln 2 = kLn2Hi + kLn2Lo; kLn2Hi has 15 significant bits, so k * kLn2Hi is exact for |k| < 512.
constexpr float kLn2Hi = 0.693145751953125f;
constexpr float kLn2Lo = 1.42860682030941723212e-6f;
// pi/4 = kPio4A + kPio4B + kPio4C + kPio4D (to 4e-20): the first three have 11 significant
// bits, so j * part is exact for j < 2^13 (|x| < 6434); the last is a full float.
constexpr float kPio4A = 0x1.92p-1f;
constexpr float kPio4B = 0x1.fb4p-13f;
constexpr float kPio4C = 0x1.444p-25f;
constexpr float kPio4D = 0x1.68c234p-40f;
constexpr float kFourOverPi = 1.27323954473516268615f;
// pi/2 and pi/4 as a float plus its remainder, so that adding a small value rounds once.
constexpr float kPio2Hi = 1.57079637050628662109f;
constexpr float kPio2Lo = -4.37113900018624283e-8f;
constexpr float kPio4Hi = 0.785398185253143310547f;
constexpr float kPio4Lo = -2.18556950009312141e-8f;
constexpr float kPiHi = 3.14159274101257324219f;
constexpr float kPiLo = -8.74227800037248566e-8f;
constexpr float kTanPiOver8 = 0.414213562373095048802f;

// c[0] + x * (c[1] + x * (c[2] + ...)), in that order.
Float horner(const Float& x, std::initializer_list<float> c) {
  auto it = c.end();
  Float p = *--it;
  while (it != c.begin()) p = p * x + *--it;
  return p;
}

Float nan_value() {
  return Float(std::numeric_limits<float>::quiet_NaN());
}
Float inf_value() {
  return Float(std::numeric_limits<float>::infinity());
}

// atan on [0, 1]: reduce above tan(pi/8) with atan(t) = pi/4 + atan((t - 1) / (t + 1)).
Float atan_unit(const Float& t) {
  Bool upper = t > kTanPiOver8;
  Float u = select(upper, (t - 1.0f) / (t + 1.0f), t);
  Float z = u * u;
  // atan(u) = u - u^3/3 + u^5/5 - ... ; |u| <= 0.4143, so 9 terms leave < 0.1 ulp.
  Float p = u + u * z *
                    horner(z, {-1.0f / 3, 1.0f / 5, -1.0f / 7, 1.0f / 9, -1.0f / 11, 1.0f / 13,
                               -1.0f / 15, 1.0f / 17});
  return select(upper, (p + kPio4Lo) + kPio4Hi, p);
}

// sin and cos on [-pi/4, pi/4] (Taylor, |r| <= 0.786).
Float sin_poly(const Float& r, const Float& z) {
  return r + r * z * horner(z, {-1.0f / 6, 1.0f / 120, -1.0f / 5040, 1.0f / 362880});
}
Float cos_poly(const Float& z) {
  return (1.0f - 0.5f * z) +
         z * z * horner(z, {1.0f / 24, -1.0f / 720, 1.0f / 40320, -1.0f / 3628800});
}

// Argument reduction for sin, cos, tan: |x| = j * pi/4 + r with j even, |r| <= pi/4.
// Returns r and the quadrant (j / 2) mod 4.
struct Reduced {
  Float r;
  Int quadrant;
};
Reduced reduce_pi_over_4(const Float& ax) {
  // j stays a float (an integer value; converting to Int would saturate for huge |x|).
  Float j = floor(ax * kFourOverPi);
  j = 2.0f * floor((j + 1.0f) * 0.5f);  // the even neighbour
  Float r = (((ax - j * kPio4A) - j * kPio4B) - j * kPio4C) - j * kPio4D;
  // Beyond |x| ~ 2^23 floats are farther apart than the period and the reduction above is
  // meaningless; clamping keeps sin and cos in [-1, 1] and tan finite there.
  r = clamp(r, -0.9f, 0.9f);
  Float half = j * 0.5f;
  Float q = half - 4.0f * floor(half * 0.25f);  // (j / 2) mod 4, exact for integer j
  return {r, to_int(q)};
}

// ln(m) for m in [sqrt(1/2), sqrt(2)], via s = (m - 1) / (m + 1) and 2 atanh(s).
Float log_mantissa(const Float& m) {
  Float s = (m - 1.0f) / (m + 1.0f);
  Float z = s * s;
  return s * horner(z, {2.0f, 2.0f / 3, 2.0f / 5, 2.0f / 7, 2.0f / 9});
}

// Splits a positive finite x (denormals included) into m * 2^e, m in [sqrt(1/2), sqrt(2)).
struct Split {
  Float m;
  Float e;
};
Split split_exponent(const Float& x) {
  Bool denormal = as_int(x) < 0x00800000;
  Float xs = select(denormal, x * 8388608.0f, x);  // 2^23 makes it normal, exactly
  Int b = as_int(xs);
  Int e = ((b >> 23) & 255) - 127 - select(denormal, Int(23), Int(0));
  Float m = as_float((b & 0x007fffff) | 0x3f800000);
  Bool high = m > 1.41421356237309504880f;
  m = select(high, m * 0.5f, m);
  e = e + select(high, Int(1), Int(0));
  return {m, to_float(e)};
}

}  // namespace

Bool is_nan(const Float& x) {
  return (as_int(x) & kAbsMask) > kInfBits;
}
Bool is_inf(const Float& x) {
  return (as_int(x) & kAbsMask) == kInfBits;
}
Bool is_zero(const Float& x) {
  return (as_int(x) & kAbsMask) == 0;
}
Bool sign_bit(const Float& x) {
  return as_int(x) < 0;
}
Float copy_sign(const Float& magnitude, const Float& sign) {
  return as_float((as_int(magnitude) & kAbsMask) | (as_int(sign) & kSignMask));
}

Float scale_by_power_of_two(const Float& x, const Int& n) {
  // Two exact-or-once-rounded steps keep each factor a normal power of two.
  Int n1 = n >> 1;
  Int n2 = n - n1;
  Float s1 = as_float((n1 + 127) << 23);
  Float s2 = as_float((n2 + 127) << 23);
  return (x * s1) * s2;
}

Float exp2(const Float& x) {
  Float xc = clamp(x, -151.0f, 129.0f);  // beyond these the result is 0 or inf anyway
  Float n = floor(xc + 0.5f);
  Float f = xc - n;  // [-0.5, 0.5], exact
  // 2^f = e^(f ln 2), Taylor to degree 7 (truncation < 0.1 ulp on this interval).
  Float g = f * 0.693147180559945309417f;
  Float p =
      horner(g, {1.0f, 1.0f, 1.0f / 2, 1.0f / 6, 1.0f / 24, 1.0f / 120, 1.0f / 720, 1.0f / 5040});
  Float r = scale_by_power_of_two(p, to_int(n));
  return select(is_nan(x), x, r);
}

Float exp(const Float& x) {
  Float xc = clamp(x, -104.0f, 89.0f);
  Float k = floor(xc * kLog2e + 0.5f);
  Float r = (xc - k * kLn2Hi) - k * kLn2Lo;  // |r| <= 0.35
  Float p =
      horner(r, {1.0f, 1.0f, 1.0f / 2, 1.0f / 6, 1.0f / 24, 1.0f / 120, 1.0f / 720, 1.0f / 5040});
  Float res = scale_by_power_of_two(p, to_int(k));
  return select(is_nan(x), x, res);
}

namespace {
// log for the special inputs: NaN, negative -> NaN; +-0 -> -inf; +inf -> +inf.
Float log_specials(const Float& x, const Float& finite) {
  Float r = select(as_int(x) == kInfBits, inf_value(), finite);
  r = select(is_zero(x), -inf_value(), r);
  r = select(sign_bit(x) && !is_zero(x), nan_value(), r);
  return select(is_nan(x), x, r);
}
}  // namespace

Float log(const Float& x) {
  Split s = split_exponent(abs(x));
  Float lm = log_mantissa(s.m);
  Float r = (s.e * kLn2Lo + lm) + s.e * kLn2Hi;
  return log_specials(x, r);
}

Float log2(const Float& x) {
  Split s = split_exponent(abs(x));
  Float lm = log_mantissa(s.m);
  Float r = lm * kLog2e + s.e;
  return log_specials(x, r);
}

namespace {
// Error-free transformations (Dekker, Knuth) in plain binary32 arithmetic, no FMA needed:
// a value is carried as an unevaluated sum hi + lo of two floats.
struct Pair {
  Float hi, lo;
};
Pair two_sum(const Float& a, const Float& b) {
  Float s = a + b;
  Float bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
Pair split(const Float& a) {  // Veltkamp: a = hi + lo with 12 significant bits each
  Float c = a * 4097.0f;
  Float hi = c - (c - a);
  return {hi, a - hi};
}
Pair two_product(const Float& a, const Float& b) {
  Float p = a * b;
  Pair as = split(a), bs = split(b);
  Float err = (((as.hi * bs.hi - p) + as.hi * bs.lo) + as.lo * bs.hi) + as.lo * bs.lo;
  return {p, err};
}

// log2(x) for positive finite x, to about 2^-40 relative: pow needs it because the error
// of y * log2(x) is multiplied by |y log2 x| in the result.
Pair log2_extended(const Float& x) {
  Split sp = split_exponent(x);
  const Float& m = sp.m;
  Float u = m - 1.0f;  // exact
  Pair v = two_sum(m, Float(1.0f));
  Float s = u / v.hi;
  Pair sv = two_product(s, v.hi);
  Float s_lo = ((u - sv.hi) - sv.lo - s * v.lo) / v.hi;
  Float z = s * s;
  // Terms to s^17: |s| <= 0.1716, so the first one left out is below 2^-45 relative.
  Float tail = s * z *
               horner(z, {2.0f / 3, 2.0f / 5, 2.0f / 7, 2.0f / 9, 2.0f / 11, 2.0f / 13, 2.0f / 15,
                          2.0f / 17});
  Pair ln = two_sum(2.0f * s, tail + 2.0f * s_lo);
  // times log2(e) = kLog2Hi + kLog2Lo
  const float kLog2Hi = 1.44269502162933349609f, kLog2Lo = 1.92596299112661746887e-8f;
  Pair p = two_product(ln.hi, Float(kLog2Hi));
  Float p_lo = p.lo + (ln.hi * kLog2Lo + ln.lo * kLog2Hi);
  Pair l = two_sum(sp.e, p.hi);
  return {l.hi, l.lo + p_lo};
}
}  // namespace

namespace {
// y is an odd integer (no float of 2^24 or more is one).
Bool is_odd_integer(const Float& y) {
  return floor(y) == y && abs(y) < 16777216.0f && (to_int(y) & 1) == 1;
}
}  // namespace

Float pow(const Float& x, const Float& y) {
  Float ax = abs(x);
  // |y| beyond 2^60 overflows or underflows for every x != 1 just as well, and keeps the
  // splitting below finite.
  Float yc = clamp(y, -1.152921504606846976e18f, 1.152921504606846976e18f);
  Pair l = log2_extended(ax);
  Pair t = two_product(yc, l.hi);
  Float t_lo = t.lo + yc * l.lo;
  // 2^(t.hi + t_lo), with the reduction done on the pair.
  Float th = clamp(t.hi, -151.0f, 129.0f);
  Float n = floor(th + 0.5f);
  Float f = (th - n) + select(th == t.hi, t_lo, Float(0.0f));
  Float g = f * 0.693147180559945309417f;
  Float p =
      horner(g, {1.0f, 1.0f, 1.0f / 2, 1.0f / 6, 1.0f / 24, 1.0f / 120, 1.0f / 720, 1.0f / 5040});
  Float r = scale_by_power_of_two(p, to_int(n));
  // Zero and infinite bases: log2 is -inf or +inf there.
  Bool x_zero = is_zero(x);
  r = select(x_zero, select(y < 0.0f, inf_value(), Float(0.0f)), r);
  r = select(is_inf(x), select(y < 0.0f, Float(0.0f), inf_value()), r);
  // Negative bases: defined for integer y, odd ones keep the sign.
  Bool y_int = floor(y) == y;
  Bool y_odd = is_odd_integer(y);
  Bool x_neg = sign_bit(x);
  r = select(x_neg && y_odd, -r, r);
  r = select(x_neg && !y_int && !x_zero && !is_inf(x), nan_value(), r);
  // |x| = 1 with y = +-inf gives 1 (C99), so does x = 1 with any y and any x with y = 0.
  r = select(ax == 1.0f && is_inf(y), Float(1.0f), r);
  r = select(is_nan(x) || is_nan(y), x + y, r);
  r = select(x == 1.0f, Float(1.0f), r);
  r = select(y == 0.0f, Float(1.0f), r);
  return r;
}

// pow's rules above as they apply to a zero base: +-0 or +-inf by the sign of y, negative
// for -0 and an odd integer y; NaN for a NaN y; 1 for y = 0.
Float pow_of_zero(const Float& x, const Float& y) {
  Float r = select(y < 0.0f, inf_value(), Float(0.0f));
  r = select(sign_bit(x) && is_odd_integer(y), -r, r);
  r = select(is_nan(y), x + y, r);
  return select(y == 0.0f, Float(1.0f), r);
}

Bool pow_term_is_lost(const Float& c, const Float& s, const Float& x, const Float& y) {
  // log2(x) from above, for x = m 2^e normal: log2 lies below its tangents, here those at
  // m = 1, 1.25, 1.5 and 1.75 (within 0.02 of log2(m) on [1, 2)), each a m + b with a and
  // b rounded up (m > 0). The rounding of the operations (a few 2^-24 of the result) is far
  // inside the margin of 1 taken below.
  const Int bits = as_int(x);
  const Int field = (bits >> 23) & 255;
  const Float m = as_float((bits & 0x7fffff) | 0x3f800000);
  const Float log2_m = min(min(1.4427f * m - 1.4426f, 1.15416f * m - 1.1207f),
                           min(0.9618f * m - 0.8577f, 0.8244f * m - 0.6353f));
  const Float log2_up = to_float(field - 127) + log2_m;
  // pow(x, y) <= 2^(y log2_up) for y > 0, and u = 2^k with k >= y log2_up + 1 (truncation
  // moves a negative value up). Below, k is raised to -120, where 2^k is still a normal
  // float: a larger bound is still a bound. Above 2^100 there is no bound: pow may be
  // infinite, and s = 0 times infinity is NaN, not 0.
  const Float log2_pow_up = y * log2_up;
  const Int k = max(to_int(log2_pow_up), -122) + 2;
  const Float u = as_float((min(k, 120) + 127) << 23);
  return y > 0.0f && !sign_bit(x) && field >= 1 && field <= 254 && log2_pow_up <= 100.0f &&
         s >= 0.0f && !is_inf(s) && c + s * u == c;
}

Float sin(const Float& x) {
  Float ax = abs(x);
  Reduced red = reduce_pi_over_4(ax);
  Float z = red.r * red.r;
  Float s = sin_poly(red.r, z), c = cos_poly(z);
  Float v = select((red.quadrant & 1) == 1, c, s);
  v = select(red.quadrant >= 2, -v, v);
  v = select(sign_bit(x), -v, v);
  return select(is_nan(x) || is_inf(x), nan_value(), v);
}

Float cos(const Float& x) {
  Float ax = abs(x);
  Reduced red = reduce_pi_over_4(ax);
  Float z = red.r * red.r;
  Float s = sin_poly(red.r, z), c = cos_poly(z);
  Float v = select((red.quadrant & 1) == 1, s, c);
  v = select(red.quadrant == 1 || red.quadrant == 2, -v, v);
  return select(is_nan(x) || is_inf(x), nan_value(), v);
}

Float tan(const Float& x) {
  Float ax = abs(x);
  Reduced red = reduce_pi_over_4(ax);
  Float z = red.r * red.r;
  Float s = sin_poly(red.r, z), c = cos_poly(z);
  Float v = select((red.quadrant & 1) == 1, -c / s, s / c);
  v = select(sign_bit(x), -v, v);
  return select(is_nan(x) || is_inf(x), nan_value(), v);
}

Float atan(const Float& x) {
  Float a = abs(x);
  Bool inverse = a > 1.0f;
  Float t = select(inverse, 1.0f / a, a);
  Float p = atan_unit(t);
  p = select(inverse, (kPio2Lo - p) + kPio2Hi, p);
  return select(is_nan(x), x, copy_sign(p, x));
}

Float atan2(const Float& y, const Float& x) {
  Float ax = abs(x), ay = abs(y);
  Bool swap = ay > ax;
  Float t = select(swap, ax, ay) / select(swap, ay, ax);
  Float r = atan_unit(select(is_nan(t), Float(1.0f), t));  // both infinite: pi/4
  r = select(swap, (kPio2Lo - r) + kPio2Hi, r);
  r = select(ax == 0.0f && ay == 0.0f, Float(0.0f), r);
  r = select(sign_bit(x), (kPiLo - r) + kPiHi, r);
  r = copy_sign(r, y);
  return select(is_nan(x) || is_nan(y), x + y, r);
}

}  // namespace rill::strict
