#include "Helpers.h"

namespace rill::codegen {

const std::string& c_family_helpers() {
  static const std::string text = R"(
/* Integer arithmetic wraps (two's complement); division and remainder by zero give 0. */
RILL_FN int32_t rill_add_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); }
RILL_FN int32_t rill_sub_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a - (uint32_t)b); }
RILL_FN int32_t rill_mul_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a * (uint32_t)b); }
RILL_FN int32_t rill_neg_i(int32_t a) { return (int32_t)(0u - (uint32_t)a); }
RILL_FN int32_t rill_div_i(int32_t a, int32_t b) {
  if (b == 0) return 0;
  if (b == -1) return rill_neg_i(a);
  return a / b;
}
RILL_FN int32_t rill_mod_i(int32_t a, int32_t b) {
  if (b == 0 || b == -1) return 0;
  return a % b;
}
RILL_FN int32_t rill_min_i(int32_t a, int32_t b) { return b < a ? b : a; }
RILL_FN int32_t rill_max_i(int32_t a, int32_t b) { return a < b ? b : a; }
RILL_FN int32_t rill_abs_i(int32_t a) { return a < 0 ? rill_neg_i(a) : a; }
RILL_FN int32_t rill_sign_i(int32_t a) { return a > 0 ? 1 : (a < 0 ? -1 : 0); }
RILL_FN int32_t rill_shl(int32_t a, int32_t b) { return (int32_t)((uint32_t)a << (b & 31)); }
RILL_FN int32_t rill_shr(int32_t a, int32_t b) { return a >> (b & 31); }

/* Float helpers with one meaning on every backend. */
RILL_FN rill_real rill_min_f(rill_real a, rill_real b) { return b < a ? b : a; }
RILL_FN rill_real rill_max_f(rill_real a, rill_real b) { return a < b ? b : a; }
RILL_FN rill_real rill_sign_f(rill_real x) { return x > 0 ? (rill_real)1 : (x < 0 ? (rill_real)-1 : (rill_real)0); }
RILL_FN rill_real rill_abs_f(rill_real x) { return RILL_M(fabs)(x); }
RILL_FN rill_real rill_floor(rill_real x) { return RILL_M(floor)(x); }
RILL_FN rill_real rill_ceil(rill_real x) { return RILL_M(ceil)(x); }
RILL_FN rill_real rill_trunc(rill_real x) { return RILL_M(trunc)(x); }
RILL_FN rill_real rill_fract(rill_real x) { rill_real f = RILL_M(floor)(x); return x - f; }
RILL_FN rill_real rill_mod_f(rill_real a, rill_real b) {
  rill_real q = a / b;
  rill_real f = RILL_M(floor)(q);
  rill_real m = b * f;
  return a - m;
}
RILL_FN rill_real rill_sqrt(rill_real x) { return RILL_M(sqrt)(x); }
RILL_FN rill_real rill_rsqrt(rill_real x) { rill_real s = RILL_M(sqrt)(x); return (rill_real)1 / s; }
RILL_FN rill_real rill_exp(rill_real x) { return RILL_M(exp)(x); }
RILL_FN rill_real rill_log(rill_real x) { return RILL_M(log)(x); }
RILL_FN rill_real rill_exp2(rill_real x) { return RILL_M(exp2)(x); }
RILL_FN rill_real rill_log2(rill_real x) { return RILL_M(log2)(x); }
RILL_FN rill_real rill_sin(rill_real x) { return RILL_M(sin)(x); }
RILL_FN rill_real rill_cos(rill_real x) { return RILL_M(cos)(x); }
RILL_FN rill_real rill_tan(rill_real x) { return RILL_M(tan)(x); }
RILL_FN rill_real rill_atan(rill_real x) { return RILL_M(atan)(x); }
RILL_FN rill_real rill_pow(rill_real x, rill_real y) { return RILL_M(pow)(x, y); }
RILL_FN rill_real rill_atan2(rill_real y, rill_real x) { return RILL_M(atan2)(y, x); }
RILL_FN rill_real rill_i2f(int32_t i) { return (rill_real)i; }
/* Truncation toward zero; NaN gives 0, out-of-range values saturate. */
RILL_FN int32_t rill_f2i(rill_real x) {
  if (x != x) return 0;
  if (x >= (rill_real)2147483648.0) return 2147483647;
  if (x < (rill_real)-2147483648.0) return (int32_t)(-2147483647 - 1);
  return (int32_t)x;
}
/* Array index in [0, n) under each boundary mode (ir::Boundary states them; ir::boundary_index
   is the reference). Wrap and mirror map a negative i through -1 - i, which never overflows,
   so no remainder of a negative number is taken. Computed in 64 bits. */
RILL_FN int64_t rill_clamp_index(int32_t i, int64_t n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); }
/* The same for one dimension in 32-bit arithmetic (64-bit compares cost GPUs two or more
   instructions each): n32 is n capped at 2^31, which no int32 index reaches, so the result is
   rill_clamp_index's for every n. */
RILL_FN uint32_t rill_count32(int64_t n) { return n < (int64_t)2147483648u ? (uint32_t)n : 2147483648u; }
RILL_FN int32_t rill_clamp_index32(int32_t i, uint32_t n32) {
  return i < 0 ? 0 : ((uint32_t)i >= n32 ? (int32_t)(n32 - 1u) : i);
}
RILL_FN int64_t rill_wrap_index(int32_t i, int64_t n) {
  const int64_t j = i >= 0 ? (int64_t)i : -1 - (int64_t)i;
  return i >= 0 ? j % n : n - 1 - j % n;
}
RILL_FN int64_t rill_mirror_index(int32_t i, int64_t n) {
  const int64_t j = i >= 0 ? (int64_t)i : -1 - (int64_t)i;
  const int64_t r = j % n;
  return (j / n) % 2 == 0 ? r : n - 1 - r;
}
RILL_FN int rill_index_inside(int32_t i, int64_t n) { return i >= 0 && i < n; }
)";
  return text;
}

std::string array_counts32(size_t arrays, const std::string& indent) {
  std::string src;
  for (size_t i = 0; i < arrays; ++i) {
    const std::string id = std::to_string(i);
    src += indent + "const uint32_t arr" + id + "_n32 = rill_count32(arr" + id + "_shape[0]);\n";
  }
  return src;
}

}  // namespace rill::codegen
