// The rill_* helpers, each with its body in every dialect that has one (see Helpers.h).
//
// Adding an op with a HELPER form (Ops.def): an entry here, with a C body (which OpenCL C
// shares), a GLSL body and, where lane-by-lane is too slow, a lockstep C body; without one,
// lockstep C calls the C body lane by lane (LockstepEmitter.cpp). The order is the order of
// every prelude: a helper after the helpers it calls (GLSL has no forward use). A body
// carries the comments the generated code shows; the comment above an entry says why.
#include "Helpers.h"

#include <algorithm>
#include <string_view>

#include "codegen/LeanDivSqrt.h"  // generated from backends/glsl/lean/*.glsl
#include "rill/ir/Ops.h"

namespace rill::codegen {

namespace {

constexpr Language C = Language::C, OpenCL = Language::OpenCL, Glsl = Language::Glsl,
                   Lockstep = Language::Lockstep;

}  // namespace

const std::vector<Helper>& helper_table() {
  static const std::vector<Helper> table = {
      // Bit casts between float and int32 (the ops int_bits_to_float, float_bits_to_int):
      // C through memcpy, which compilers reduce to a move; the others have built-ins. GLSL
      // passes the int through RILL_ZERO_I so that the compiler cannot fold the constant
      // float it would make (see rill_i2f).
      {"ibits",
       {{C,
         R"(RILL_FN rill_real rill_ibits(int32_t i) { float f; memcpy(&f, &i, 4); return (rill_real)f; })"},
        {OpenCL, R"(RILL_FN rill_real rill_ibits(int32_t i) { return (rill_real)as_float(i); })"},
        {Glsl, R"(float rill_ibits(int i) { return intBitsToFloat(i ^ RILL_ZERO_I); })"},
        {Lockstep, R"(RILL_FN rill_vr rill_v_ibits(rill_vi a) { return (rill_vr)a; })"}}},
      {"fbits",
       {{C,
         R"(RILL_FN int32_t rill_fbits(rill_real x) { float f = (float)x; int32_t i; memcpy(&i, &f, 4); return i; })"},
        {OpenCL, R"(RILL_FN int32_t rill_fbits(rill_real x) { return as_int((float)x); })"},
        {Glsl, R"(int rill_fbits(float x) { return floatBitsToInt(x); })"},
        {Lockstep, R"(RILL_FN rill_vi rill_v_fbits(rill_vr a) { return (rill_vi)a; })"}}},
      // A uniform's float from its host word, and an output's binary32 from rill_real: the
      // C-family frames' uniforms and stores (GLSL reads words with uintBitsToFloat).
      {"word_f",
       {{C,
         R"(RILL_FN rill_real rill_word_f(uint32_t w) { float f; memcpy(&f, &w, 4); return (rill_real)f; })"},
        {OpenCL,
         R"(RILL_FN rill_real rill_word_f(uint32_t w) { return (rill_real)as_float(w); })"}}},
      // The same body; C's prelude has always had a blank line after it, kept so that C
      // sources (and so the kernel caches) stay as they were.
      {"store_f",
       {{C, "RILL_FN float rill_store_f(rill_real x) { return (float)x; }\n\n"},
        {OpenCL, R"(RILL_FN float rill_store_f(rill_real x) { return (float)x; })"}}},

      // Integer arithmetic wraps (two's complement): computed on unsigned values, since
      // signed overflow is undefined in C and OpenCL C.
      {"add_i",
       {{C, R"(
/* Integer arithmetic wraps (two's complement); division and remainder by zero give 0. */
RILL_FN int32_t rill_add_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); })"},
        {Glsl, R"(
int rill_add_i(int a, int b) { return int(uint(a) + uint(b)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_add_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a + (rill_vu)b); })"}}},
      {"sub_i",
       {{C,
         R"(RILL_FN int32_t rill_sub_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a - (uint32_t)b); })"},
        {Glsl, R"(int rill_sub_i(int a, int b) { return int(uint(a) - uint(b)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_sub_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a - (rill_vu)b); })"}}},
      {"mul_i",
       {{C,
         R"(RILL_FN int32_t rill_mul_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a * (uint32_t)b); })"},
        {Glsl, R"(int rill_mul_i(int a, int b) { return int(uint(a) * uint(b)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_mul_i(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a * (rill_vu)b); })"}}},
      {"neg_i",
       {{C, R"(RILL_FN int32_t rill_neg_i(int32_t a) { return (int32_t)(0u - (uint32_t)a); })"},
        {Glsl, R"(int rill_neg_i(int a) { return int(0u - uint(a)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_neg_i(rill_vi a) { return (rill_vi)((rill_vu){} - (rill_vu)a); })"}}},
      // Truncating division; by zero gives 0, and INT32_MIN / -1 wraps (C would trap).
      {"div_i",
       {{C, R"(RILL_FN int32_t rill_div_i(int32_t a, int32_t b) {
  if (b == 0) return 0;
  if (b == -1) return rill_neg_i(a);
  return a / b;
})"},
        {Glsl,
         R"(// Truncating division computed on magnitudes (GLSL leaves negative operands open).
int rill_div_i(int a, int b) {
  if (b == 0) return 0;
  uint q = (a < 0 ? 0u - uint(a) : uint(a)) / (b < 0 ? 0u - uint(b) : uint(b));
  return ((a < 0) != (b < 0)) ? int(0u - q) : int(q);
})"}}},
      // The remainder of truncating division, with the sign of a; by zero (and by -1, which
      // C may trap on for INT32_MIN) gives 0.
      {"mod_i",
       {{C, R"(RILL_FN int32_t rill_mod_i(int32_t a, int32_t b) {
  if (b == 0 || b == -1) return 0;
  return a % b;
})"},
        {Glsl, R"(int rill_mod_i(int a, int b) {
  if (b == 0) return 0;
  return rill_sub_i(a, rill_mul_i(b, rill_div_i(a, b)));
})"}}},
      {"min_i",
       {{C, R"(RILL_FN int32_t rill_min_i(int32_t a, int32_t b) { return b < a ? b : a; })"},
        {Glsl, R"(int rill_min_i(int a, int b) { return b < a ? b : a; })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_min_i(rill_vi a, rill_vi b) { return rill_sel_i(RILL_CMP(b < a), b, a); })"}}},
      {"max_i",
       {{C, R"(RILL_FN int32_t rill_max_i(int32_t a, int32_t b) { return a < b ? b : a; })"},
        {Glsl, R"(int rill_max_i(int a, int b) { return a < b ? b : a; })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_max_i(rill_vi a, rill_vi b) { return rill_sel_i(RILL_CMP(a < b), b, a); })"}}},
      // abs(INT32_MIN) wraps to INT32_MIN.
      {"abs_i",
       {{C, R"(RILL_FN int32_t rill_abs_i(int32_t a) { return a < 0 ? rill_neg_i(a) : a; })"},
        {Glsl, R"(int rill_abs_i(int a) { return a < 0 ? rill_neg_i(a) : a; })"}}},
      {"sign_i",
       {{C, R"(RILL_FN int32_t rill_sign_i(int32_t a) { return a > 0 ? 1 : (a < 0 ? -1 : 0); })"},
        {Glsl, R"(int rill_sign_i(int a) { return a > 0 ? 1 : (a < 0 ? -1 : 0); })"}}},
      // Shifts count modulo 32 (C leaves counts outside [0, 32) undefined); >> is arithmetic.
      {"shl",
       {{C,
         R"(RILL_FN int32_t rill_shl(int32_t a, int32_t b) { return (int32_t)((uint32_t)a << (b & 31)); })"},
        {Glsl, R"(int rill_shl(int a, int b) { return int(uint(a) << uint(b & 31)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_shl(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a << (rill_vu)(b & 31)); })"}}},
      {"shr",
       {{C, R"(RILL_FN int32_t rill_shr(int32_t a, int32_t b) { return a >> (b & 31); })"},
        {Glsl, R"(int rill_shr(int a, int b) { return a >> (b & 31); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_shr(rill_vi a, rill_vi b) { return a >> (b & 31); })"}}},

      // GLSL's float select and strict comparisons (the dialect's select() and compare()),
      // which shader compilers would otherwise rewrite as if there were no NaN.
      {"sel_f", {{Glsl, R"(
// Selections are made on bit patterns: shader compilers turn a float `a < b ? b : a` into
// their own max, whose NaN and signed-zero behaviour differs.
float rill_sel_f(bool c, float a, float b) { return intBitsToFloat(c ? floatBitsToInt(a) : floatBitsToInt(b)); })"}}},
      {"isnan",
       {{Glsl,
         R"(// Ordered comparisons on bit patterns: shader compilers may assume no NaN and rewrite
// comparisons (a > b into !(a <= b)). key() orders floats as integers, -0 equal to +0.
bool rill_isnan(float x) { return (floatBitsToInt(x) & 0x7fffffff) > 0x7f800000; })"}}},
      {"key",
       {{Glsl,
         R"(// Where the arithmetic flushes denormals (RILL_FLUSHES_DENORMALS: GPUs, llvmpipe's fragment
// shaders), they compare as zero too; elsewhere (llvmpipe's compute shaders) they order as
// IEEE says, as on the CPU.
int rill_key(float x) {
  int b = floatBitsToInt(x);
#if RILL_FLUSHES_DENORMALS
  if ((b & 0x7f800000) == 0) return 0;
#endif
  return b >= 0 ? b : int(0x80000000u) - b;
})"}}},
      // RILL_NATIVE_COMPARE (DriverRules::native_compare) on drivers whose own comparisons
      // the conformance suite found exact.
      {"lt",
       {{Glsl,
         R"(// RILL_NATIVE_COMPARE: the driver's own comparisons, on drivers whose comparisons the
// conformance suite found IEEE-exact in strict kernels (NVIDIA); they cost far less than
// the bit-pattern ones (the ray tracer's traversal compares a lot).
#if RILL_NATIVE_COMPARE
bool rill_lt(float a, float b) { return a < b; }
#else
bool rill_lt(float a, float b) { return !rill_isnan(a) && !rill_isnan(b) && rill_key(a) < rill_key(b); }
#endif)"}}},
      {"le", {{Glsl, R"(#if RILL_NATIVE_COMPARE
bool rill_le(float a, float b) { return a <= b; }
#else
bool rill_le(float a, float b) { return !rill_isnan(a) && !rill_isnan(b) && rill_key(a) <= rill_key(b); }
#endif)"}}},
      {"eq", {{Glsl, R"(#if RILL_NATIVE_COMPARE
bool rill_eq(float a, float b) { return a == b; }
#else
bool rill_eq(float a, float b) { return !rill_isnan(a) && !rill_isnan(b) && rill_key(a) == rill_key(b); }
#endif)"}}},

      // min and max as `b < a ? b : a`: a NaN in a gives b, a NaN in b gives a, and of two
      // zeros the first operand; fmin/fmax, GLSL's min and vector min instructions differ.
      {"min_f",
       {{C, R"(
/* Float helpers with one meaning on every backend. */
RILL_FN rill_real rill_min_f(rill_real a, rill_real b) { return b < a ? b : a; })"},
        {Glsl, R"(float rill_min_f(float a, float b) { return rill_sel_f(rill_lt(b, a), b, a); })"},
        {Lockstep,
         R"(RILL_FN rill_vr rill_v_min_f(rill_vr a, rill_vr b) { return rill_sel_r(RILL_CMP(b < a), b, a); })"}}},
      {"max_f",
       {{C, R"(RILL_FN rill_real rill_max_f(rill_real a, rill_real b) { return a < b ? b : a; })"},
        {Glsl, R"(float rill_max_f(float a, float b) { return rill_sel_f(rill_lt(a, b), b, a); })"},
        {Lockstep,
         R"(RILL_FN rill_vr rill_v_max_f(rill_vr a, rill_vr b) { return rill_sel_r(RILL_CMP(a < b), b, a); })"}}},
      // sign(NaN) and sign(-0) are 0.
      {"sign_f",
       {{C,
         R"(RILL_FN rill_real rill_sign_f(rill_real x) { return x > 0 ? (rill_real)1 : (x < 0 ? (rill_real)-1 : (rill_real)0); })"},
        {Glsl, R"(float rill_sign_f(float x) {
  int b = floatBitsToInt(x);
  int m = b & 0x7fffffff;
  return intBitsToFloat((m == 0 || m > 0x7f800000) ? 0 : ((b & int(0x80000000u)) | 0x3f800000));
})"}}},
      {"abs_f",
       {{C, R"(RILL_FN rill_real rill_abs_f(rill_real x) { return RILL_M(fabs)(x); })"},
        {Glsl,
         R"(// RILL_ABS_ON_BITS (the Vulkan dialect): the sign bit cleared, as abs is data movement
// (the denormal rule); NVIDIA's Vulkan compiler makes abs an add that flushes denormals.
#ifdef RILL_ABS_ON_BITS
float rill_abs_f(float x) { return intBitsToFloat(floatBitsToInt(x) & 0x7fffffff); }
#else
float rill_abs_f(float x) { return abs(x); }
#endif)"},
        {Lockstep,
         R"(RILL_FN rill_vr rill_v_abs_f(rill_vr a) { return (rill_vr)((rill_vi)a & 0x7fffffff); })"}}},
      // Rounding to an integer is exact everywhere. Lockstep C uses AVX's rounding
      // instruction where it has it, which strict code would otherwise call lane by lane.
      {"floor",
       {{C, R"(RILL_FN rill_real rill_floor(rill_real x) { return RILL_M(floor)(x); })"},
        {Glsl, R"(float rill_floor(float x) { return floor(x); })"},
        {Lockstep,
         R"(/* With AVX: exact in every mode, so the same bits as the scalar helpers (NaN, infinities,
   -0 included): rounding to an integer and the square root are correctly rounded
   instructions. Strict code would otherwise call floorf, ceilf, truncf and sqrtf lane by
   lane. The rounding immediates are _MM_FROUND_TO_NEG_INF, _TO_POS_INF and _TO_ZERO, each
   with _MM_FROUND_NO_EXC (8); with 16 lanes, AVX-512's vrndscaleps takes the same ones. */
#ifdef RILL_AVX2
RILL_FN rill_vr rill_v_floor(rill_vr a) { return __builtin_ia32_roundps256(a, 1 | 8); }
#elif defined(RILL_AVX512)
RILL_FN rill_vr rill_v_floor(rill_vr a) { return RILL_ROUND16(a, 1 | 8); }
#else
RILL_LANES1(rill_v_floor, rill_vr, rill_vr, rill_floor)
#endif)"}}},
      {"ceil",
       {{C, R"(RILL_FN rill_real rill_ceil(rill_real x) { return RILL_M(ceil)(x); })"},
        {Glsl, R"(float rill_ceil(float x) { return ceil(x); })"},
        {Lockstep, R"(#ifdef RILL_AVX2
RILL_FN rill_vr rill_v_ceil(rill_vr a) { return __builtin_ia32_roundps256(a, 2 | 8); }
#elif defined(RILL_AVX512)
RILL_FN rill_vr rill_v_ceil(rill_vr a) { return RILL_ROUND16(a, 2 | 8); }
#else
RILL_LANES1(rill_v_ceil, rill_vr, rill_vr, rill_ceil)
#endif)"}}},
      {"trunc",
       {{C, R"(RILL_FN rill_real rill_trunc(rill_real x) { return RILL_M(trunc)(x); })"},
        {Glsl, R"(float rill_trunc(float x) { return trunc(x); })"},
        {Lockstep, R"(#ifdef RILL_AVX2
RILL_FN rill_vr rill_v_trunc(rill_vr a) { return __builtin_ia32_roundps256(a, 3 | 8); }
#elif defined(RILL_AVX512)
RILL_FN rill_vr rill_v_trunc(rill_vr a) { return RILL_ROUND16(a, 3 | 8); }
#else
RILL_LANES1(rill_v_trunc, rill_vr, rill_vr, rill_trunc)
#endif)"}}},
      // x - floor(x), as two rounded operations (GLSL's fract may be computed otherwise).
      {"fract",
       {{C,
         R"(RILL_FN rill_real rill_fract(rill_real x) { rill_real f = RILL_M(floor)(x); return x - f; })"},
        {Glsl,
         R"(float rill_fract(float x) { RILL_PRECISE float f = floor(x); RILL_PRECISE float r = x - f; return r; })"}}},

      // GLSL's float division (the dialect's float_div in strict mode) and square root:
      // GLSL promises only 2.5 ulp, so strict kernels correct the driver's results where the
      // driver is not known to be exact. The method and the rules: glsl/DivSqrt.h.
      {"native_div",
       {{Glsl,
         R"(
float rill_native_div(float a, float b) { RILL_PRECISE float q = a / b; return q; })",
         Variant::DriverOps},
        {Glsl, R"(
// Test mode: division and square root as NVIDIA's GLSL computes them (not correctly rounded).
float rill_native_div(float a, float b) { RILL_PRECISE float y = RILL_ONE / b; RILL_PRECISE float q = a * y; return q; })",
         Variant::InexactOps}}},
      {"native_sqrt",
       {{Glsl, R"(float rill_native_sqrt(float x) { RILL_PRECISE float s = sqrt(x); return s; })",
         Variant::DriverOps},
        {Glsl,
         R"(float rill_native_sqrt(float x) { RILL_PRECISE float y = inversesqrt(x); RILL_PRECISE float s = x * y; return s; })",
         Variant::InexactOps}}},
      // The lean correction starts from the driver's inversesqrt (the test modes' too).
      {"native_rsqrt",
       {{Glsl,
         R"(float rill_native_rsqrt(float x) { RILL_PRECISE float y = inversesqrt(x); return y; })",
         Variant::Lean}}},
      // Operands of the exact steps lie in [0.5, 4], so nothing overflows or underflows.
      {"residual",
       {{Glsl,
         R"(// a - q * b, exact when q * b is within a factor 2 of a and the result is representable:
// Dekker's product p + e == q * b (Veltkamp splitting by 4097 = 2^12 + 1), then a - p is
// exact (Sterbenz) and (a - p) - e rounds only when the residual is not representable.
float rill_residual(float a, float q, float b) {
  RILL_PRECISE float p = q * b;
  RILL_PRECISE float tq = 4097.0 * q;
  RILL_PRECISE float qh = tq - (tq - q);
  RILL_PRECISE float ql = q - qh;
  RILL_PRECISE float tb = 4097.0 * b;
  RILL_PRECISE float bh = tb - (tb - b);
  RILL_PRECISE float bl = b - bh;
  RILL_PRECISE float e = ((qh * bh - p) + qh * bl + ql * bh) + ql * bl;
  RILL_PRECISE float d = a - p;
  RILL_PRECISE float r = d - e;
  return r;
})",
         Variant::SplitResidual},
        {Glsl,
         R"(// a - q * b with one rounding, so exact under the same conditions: the driver's fma is
// fused (glsl/DivSqrt.h, fused_fma_mode).
float rill_residual(float a, float q, float b) { RILL_PRECISE float r = fma(-q, b, a); return r; })",
         Variant::FusedResidual}}},
      {"nan_bits",
       {{Glsl, R"(bool rill_nan_bits(uint u) { return (u & 0x7fffffffu) > 0x7f800000u; })",
         Variant::Corrected}}},
      {"div_f",
       {{Glsl, R"(float rill_div_f(float a, float b) { return a / b; })", Variant::Fast},
        {Glsl, R"(float rill_div_f(float a, float b) { return rill_native_div(a, b); })",
         Variant::Uncorrected},
        {Glsl, R"(float rill_div_f(float a, float b) {
  uint ua = floatBitsToUint(a), ub = floatBitsToUint(b);
  uint sign = (ua ^ ub) & 0x80000000u;
  uint xa = (ua >> 23) & 0xffu, xb = (ub >> 23) & 0xffu;
  if (xa == 0u || xa == 255u || xb == 0u || xb == 255u) {
    bool inf_a = xa == 255u, inf_b = xb == 255u, zero_a = xa == 0u, zero_b = xb == 0u;
    if (rill_nan_bits(ua) || rill_nan_bits(ub) || (inf_a && inf_b) || (zero_a && zero_b))
      return uintBitsToFloat(0x7fc00000u);
    if (inf_a || zero_b) return uintBitsToFloat(sign | 0x7f800000u);
    return uintBitsToFloat(sign);
  }
  RILL_PRECISE float ma = uintBitsToFloat((ua & 0x7fffffu) | 0x3f800000u);
  RILL_PRECISE float mb = uintBitsToFloat((ub & 0x7fffffu) | 0x3f800000u);
  int e = int(xa) - int(xb);
  // The biased exponent of the exact quotient decides underflow (before rounding) and overflow.
  int exact_exp = e + 127 - (floatBitsToUint(ma) < floatBitsToUint(mb) ? 1 : 0);
  if (exact_exp <= 0) return uintBitsToFloat(sign);
  if (exact_exp >= 255) return uintBitsToFloat(sign | 0x7f800000u);
  RILL_PRECISE float q0 = rill_native_div(ma, mb);
  RILL_PRECISE float r0 = rill_residual(ma, q0, mb);
  RILL_PRECISE float c = rill_native_div(r0, mb);
  RILL_PRECISE float q = q0 + c;
  RILL_PRECISE float r = rill_residual(ma, q, mb);
  uint bq = floatBitsToUint(q);
  RILL_PRECISE float up = uintBitsToFloat(bq + 1u) - q;
  RILL_PRECISE float down = q - uintBitsToFloat(bq - 1u);
  RILL_PRECISE float half_up = mb * (0.5 * up);
  RILL_PRECISE float half_down = mb * (0.5 * down);
  RILL_PRECISE float minus_r = -r;
  if (r > half_up) bq += 1u;
  else if (minus_r > half_down) bq -= 1u;
  return uintBitsToFloat(sign | (bq + (uint(e) << 23)));
})",
         Variant::Corrected},
        {Glsl, kLeanDivGlsl, Variant::Lean}}},
      // a - b * floor(a / b), each step rounded (fmod and GLSL's mod differ).
      {"mod_f",
       {{C, R"(RILL_FN rill_real rill_mod_f(rill_real a, rill_real b) {
  rill_real q = a / b;
  rill_real f = RILL_M(floor)(q);
  rill_real m = b * f;
  return a - m;
})"},
        {Glsl, R"(float rill_mod_f(float a, float b) {
  RILL_PRECISE float q = rill_div_f(a, b);
  RILL_PRECISE float f = floor(q);
  RILL_PRECISE float m = b * f;
  RILL_PRECISE float r = a - m;
  return r;
})"}}},
      // Correctly rounded: libm's and OpenCL's (-cl-fp32-correctly-rounded-divide-sqrt), and
      // GLSL's under the driver's rule (see div_f).
      {"sqrt",
       {{C, R"(RILL_FN rill_real rill_sqrt(rill_real x) { return RILL_M(sqrt)(x); })"},
        {Glsl, R"(float rill_sqrt(float x) { return sqrt(x); })", Variant::Fast},
        {Glsl, R"(float rill_sqrt(float x) { return rill_native_sqrt(x); })", Variant::Uncorrected},
        {Glsl, R"(float rill_sqrt(float x) {
  uint u = floatBitsToUint(x);
  uint xe = (u >> 23) & 0xffu;
  if (xe == 0u) return uintBitsToFloat(u & 0x80000000u);
  if ((u & 0x80000000u) != 0u) return uintBitsToFloat(0x7fc00000u);
  if (xe == 255u) return x;
  int k = int(xe) - 127;
  int odd = k & 1;
  RILL_PRECISE float m = uintBitsToFloat((u & 0x7fffffu) | (uint(127 + odd) << 23));
  RILL_PRECISE float s0 = rill_native_sqrt(m);
  RILL_PRECISE float r0 = rill_residual(m, s0, s0);
  RILL_PRECISE float h = rill_native_div(0.5, s0);
  RILL_PRECISE float s1 = s0 + r0 * h;
  RILL_PRECISE float s = uintBitsToFloat(clamp(floatBitsToUint(s1), 0x3f800000u, 0x3fffffffu));
  RILL_PRECISE float r = rill_residual(m, s, s);
  uint bs = floatBitsToUint(s);
  RILL_PRECISE float up = uintBitsToFloat(bs + 1u) - s;
  RILL_PRECISE float down = s - uintBitsToFloat(bs - 1u);
  // sqrt(m) > s + up/2 iff r > s*up + up*up/4; r and s*up are multiples of up*up, so the
  // last term never matters. Likewise below, with <=.
  RILL_PRECISE float t_up = s * up;
  RILL_PRECISE float t_down = -(s * down);
  if (r > t_up) bs += 1u;
  else if (r <= t_down) bs -= 1u;
  return uintBitsToFloat(bs + (uint((k - odd) / 2) << 23));
})",
         Variant::Corrected},
        {Glsl, kLeanSqrtGlsl, Variant::Lean},
        {Lockstep, R"(#ifdef RILL_AVX2
RILL_FN rill_vr rill_v_sqrt(rill_vr a) { return __builtin_ia32_sqrtps256(a); }
#elif defined(RILL_AVX512)
RILL_FN rill_vr rill_v_sqrt(rill_vr a) { return RILL_SQRT16(a); }
#else
RILL_LANES1(rill_v_sqrt, rill_vr, rill_vr, rill_sqrt)
#endif)"}}},
      // 1 / sqrt(x), each step rounded (inversesqrt and rsqrt instructions are approximate).
      {"rsqrt",
       {{C,
         R"(RILL_FN rill_real rill_rsqrt(rill_real x) { rill_real s = RILL_M(sqrt)(x); return (rill_real)1 / s; })"},
        {Glsl,
         R"(float rill_rsqrt(float x) { RILL_PRECISE float s = rill_sqrt(x); RILL_PRECISE float r = rill_div_f(RILL_ONE, s); return r; })"}}},
      // The transcendental functions as the language has them: only the fast and double modes
      // call these; strict kernels compute Rill's own routines (passes/LowerMath.cpp).
      {"exp",
       {{C, R"(RILL_FN rill_real rill_exp(rill_real x) { return RILL_M(exp)(x); })"},
        {Glsl, R"(float rill_exp(float x) { return exp(x); })"}}},
      {"log",
       {{C, R"(RILL_FN rill_real rill_log(rill_real x) { return RILL_M(log)(x); })"},
        {Glsl, R"(float rill_log(float x) { return log(x); })"}}},
      {"exp2",
       {{C, R"(RILL_FN rill_real rill_exp2(rill_real x) { return RILL_M(exp2)(x); })"},
        {Glsl, R"(float rill_exp2(float x) { return exp2(x); })"}}},
      {"log2",
       {{C, R"(RILL_FN rill_real rill_log2(rill_real x) { return RILL_M(log2)(x); })"},
        {Glsl, R"(float rill_log2(float x) { return log2(x); })"}}},
      {"sin",
       {{C, R"(RILL_FN rill_real rill_sin(rill_real x) { return RILL_M(sin)(x); })"},
        {Glsl, R"(float rill_sin(float x) { return sin(x); })"}}},
      {"cos",
       {{C, R"(RILL_FN rill_real rill_cos(rill_real x) { return RILL_M(cos)(x); })"},
        {Glsl, R"(float rill_cos(float x) { return cos(x); })"}}},
      {"tan",
       {{C, R"(RILL_FN rill_real rill_tan(rill_real x) { return RILL_M(tan)(x); })"},
        {Glsl, R"(float rill_tan(float x) { return tan(x); })"}}},
      {"atan",
       {{C, R"(RILL_FN rill_real rill_atan(rill_real x) { return RILL_M(atan)(x); })"},
        {Glsl, R"(float rill_atan(float x) { return atan(x); })"}}},
      {"pow",
       {{C,
         R"(RILL_FN rill_real rill_pow(rill_real x, rill_real y) { return RILL_M(pow)(x, y); })"},
        {Glsl, R"(float rill_pow(float x, float y) { return pow(x, y); })"}}},
      {"atan2",
       {{C,
         R"(RILL_FN rill_real rill_atan2(rill_real y, rill_real x) { return RILL_M(atan2)(y, x); })"},
        {Glsl, R"(float rill_atan2(float y, float x) { return atan(y, x); })"}}},

      // int to float, rounded to nearest.
      {"i2f",
       {{C, R"(RILL_FN rill_real rill_i2f(int32_t i) { return (rill_real)i; })"},
        {Glsl,
         R"(// A float made from an int constant would be a constant the shader compiler folds into the
// operations that use it (see literal()): strict kernels pass ints through RILL_ZERO_I, an
// xor with a zero read from a uniform.
float rill_i2f(int i) { return float(i ^ RILL_ZERO_I); })"},
        {Lockstep,
         R"(RILL_FN rill_vr rill_v_i2f(rill_vi a) { return __builtin_convertvector(a, rill_vr); })"}}},
      // float to int saturates (C leaves out-of-range conversions undefined).
      {"f2i",
       {{C, R"(/* Truncation toward zero; NaN gives 0, out-of-range values saturate. */
RILL_FN int32_t rill_f2i(rill_real x) {
  if (x != x) return 0;
  if (x >= (rill_real)2147483648.0) return 2147483647;
  if (x < (rill_real)-2147483648.0) return (int32_t)(-2147483647 - 1);
  return (int32_t)x;
})"},
        {Glsl, R"(int rill_f2i(float x) {
  if (rill_isnan(x)) return 0;
  if (x >= 2147483648.0) return 2147483647;
  if (x < -2147483648.0) return int(0x80000000u);
  return int(x);
})"}}},

      // Array indices under each boundary mode, for the dialects' gathers
      // (codegen::boundary_index_helper).
      {"clamp_index",
       {{C,
         R"(/* Array index in [0, n) under each boundary mode (ir::Boundary states them; ir::boundary_index
   is the reference). Wrap and mirror map a negative i through -1 - i, which never overflows,
   so no remainder of a negative number is taken. Computed in 64 bits. */
RILL_FN int64_t rill_clamp_index(int32_t i, int64_t n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); })"},
        {Glsl,
         R"(// Array index in [0, n) under each boundary mode (ir::boundary_index is the reference). A
// negative i is mapped through -1 - i (~i, never negative, never overflowing), since GLSL
// leaves % of a negative operand undefined.
int rill_clamp_index(int i, int n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); })"},
        {Lockstep, R"(
/* Array index clamped into [0, n), n < 2^31 (see rill_clamp_index). */
RILL_FN rill_vi rill_v_clamp_index(rill_vi i, int64_t n) {
  return rill_v_min_i(rill_v_max_i(i, rill_splat_i(0)), rill_splat_i((int32_t)(n - 1)));
})"}}},
      // CDialect's 1D clamped gathers (array_counts32 declares the counts).
      {"count32",
       {{C,
         R"(/* The same for one dimension in 32-bit arithmetic (64-bit compares cost GPUs two or more
   instructions each): n32 is n capped at 2^31, which no int32 index reaches, so the result is
   rill_clamp_index's for every n. */
RILL_FN uint32_t rill_count32(int64_t n) { return n < (int64_t)2147483648u ? (uint32_t)n : 2147483648u; })"}}},
      {"clamp_index32", {{C, R"(RILL_FN int32_t rill_clamp_index32(int32_t i, uint32_t n32) {
  return i < 0 ? 0 : ((uint32_t)i >= n32 ? (int32_t)(n32 - 1u) : i);
})"}}},
      {"wrap_index",
       {{C, R"(RILL_FN int64_t rill_wrap_index(int32_t i, int64_t n) {
  const int64_t j = i >= 0 ? (int64_t)i : -1 - (int64_t)i;
  return i >= 0 ? j % n : n - 1 - j % n;
})"},
        {Glsl, R"(int rill_wrap_index(int i, int n) {
  int j = i >= 0 ? i : ~i;
  return i >= 0 ? j % n : n - 1 - j % n;
})"},
        {Lockstep,
         R"(/* The other boundary modes lane by lane through the scalar helpers (n < 2^31, so each result
   fits a lane), and the lanes whose index is inside [0, n) as a lane mask. */
RILL_FN rill_vi rill_v_wrap_index(rill_vi i, int64_t n) {
  rill_vi r; for (int l = 0; l < RILL_W; ++l) r[l] = (int32_t)rill_wrap_index(i[l], n); return r;
})"}}},
      {"mirror_index",
       {{C, R"(RILL_FN int64_t rill_mirror_index(int32_t i, int64_t n) {
  const int64_t j = i >= 0 ? (int64_t)i : -1 - (int64_t)i;
  const int64_t r = j % n;
  return (j / n) % 2 == 0 ? r : n - 1 - r;
})"},
        {Glsl, R"(int rill_mirror_index(int i, int n) {
  int j = i >= 0 ? i : ~i;
  int r = j % n;
  return ((j / n) & 1) == 0 ? r : n - 1 - r;
})"},
        {Lockstep, R"(RILL_FN rill_vi rill_v_mirror_index(rill_vi i, int64_t n) {
  rill_vi r; for (int l = 0; l < RILL_W; ++l) r[l] = (int32_t)rill_mirror_index(i[l], n); return r;
})"}}},
      {"index_inside",
       {{C, R"(RILL_FN int rill_index_inside(int32_t i, int64_t n) { return i >= 0 && i < n; })"},
        {Glsl, R"(bool rill_index_inside(int i, int n) { return i >= 0 && i < n; })"},
        {Lockstep, R"(RILL_FN rill_vi rill_v_index_inside(rill_vi i, int64_t n) {
  return RILL_CMP(i >= rill_splat_i(0)) & RILL_CMP(i < rill_splat_i((int32_t)n));
})"}}},

      // An Int's 32 bits as an unsigned number, for hashes and counter-based random numbers
      // (rill/Random.h). On demand: only the kernels that call them define them.
      // The logical right shift: zeros in from the left, by the low 5 bits of the count.
      {"shr_u",
       {{C,
         R"(RILL_FN int32_t rill_shr_u(int32_t a, int32_t b) { return (int32_t)((uint32_t)a >> (b & 31)); })"},
        {Glsl, R"(int rill_shr_u(int a, int b) { return int(uint(a) >> uint(b & 31)); })"},
        {Lockstep,
         R"(RILL_FN rill_vi rill_v_shr_u(rill_vi a, rill_vi b) { return (rill_vi)((rill_vu)a >> (rill_vu)(b & 31)); })"}},
       true},
      // The high 32 bits of the 64-bit unsigned product (the low ones are rill_mul_i's).
      // OpenCL C has it built in. GLSL's umulExtended crashes llvmpipe's code generator (LLVM
      // 15, Debian 12: SelectionDAG's SimplifyDemandedBits), so GLSL adds the four 16 x 16-bit
      // partial products, none of which overflows. Lockstep C runs the C body lane by lane.
      {"mul_hi_u",
       {{C,
         R"(RILL_FN int32_t rill_mul_hi_u(int32_t a, int32_t b) { return (int32_t)(uint32_t)(((uint64_t)(uint32_t)a * (uint32_t)b) >> 32); })"},
        {OpenCL,
         R"(RILL_FN int32_t rill_mul_hi_u(int32_t a, int32_t b) { return (int32_t)mul_hi((uint32_t)a, (uint32_t)b); })"},
        {Glsl, R"(int rill_mul_hi_u(int a, int b) {
  uint x = uint(a), y = uint(b);
  uint xl = x & 0xffffu, xh = x >> 16u, yl = y & 0xffffu, yh = y >> 16u;
  uint lh = xl * yh, hl = xh * yl;
  uint mid = ((xl * yl) >> 16u) + (lh & 0xffffu) + (hl & 0xffffu);
  return int(xh * yh + (lh >> 16u) + (hl >> 16u) + (mid >> 16u));
})"}},
       true},
      // A float in [0, 1): the high 24 bits, unsigned, times 2^-24. Both steps are exact (a
      // value below 2^24 converts exactly, and a power of two scales exactly), so a driver that
      // fuses the product with a later add still rounds once, as the others do.
      {"unit_f",
       {{C,
         R"(RILL_FN rill_real rill_unit_f(int32_t a) { return (rill_real)((uint32_t)a >> 8) * (rill_real)0x1p-24f; })"},
        {Glsl,
         R"(float rill_unit_f(int a) { return float(uint(a) >> 8u) * 5.9604644775390625e-8; })"},
        {Lockstep,
         R"(RILL_FN rill_vr rill_v_unit_f(rill_vi a) { return __builtin_convertvector((rill_vu)a >> 8, rill_vr) * rill_splat_r((rill_real)0x1p-24f); })"}},
       true},
  };
  return table;
}

namespace {

// Helper h's text in language d for the prelude that takes `variants` (and Any).
std::string body_text(const Helper& h, Language d, const std::vector<Variant>& variants,
                      const std::function<std::string(const Helper&)>& missing) {
  auto takes = [&](const Body& b) {
    return b.variant == Variant::Any ||
           std::find(variants.begin(), variants.end(), b.variant) != variants.end();
  };
  auto line = [](const char* text) {  // a body without its last newline gets one
    std::string s = text;
    return s.empty() || s.back() == '\n' ? s : s + '\n';
  };
  // OpenCL C takes the C bodies of the helpers that have no OpenCL body.
  Language want = d;
  if (d == OpenCL && std::none_of(h.bodies.begin(), h.bodies.end(),
                                  [](const Body& b) { return b.language == OpenCL; }))
    want = C;
  std::string out;
  bool found = false;
  for (const Body& b : h.bodies)
    if (b.language == want) {
      found = true;
      if (takes(b)) out += line(b.text);
    }
  if (!found && missing) out += missing(h);
  return out;
}

// Whether kernel f contains an op whose HELPER form is h.
bool calls(const ir::Function& f, const Helper& h) {
  for (int o = 0; o < ir::kOpCount; ++o) {
    const ir::Op op = static_cast<ir::Op>(o);
    const ir::OpInfo& info = ir::op_info(op);
    for (ir::ScalarKind k : {ir::ScalarKind::Float, ir::ScalarKind::Int, ir::ScalarKind::Bool}) {
      const ir::OpForm& form = info.form(k);
      if (form.kind == ir::FormKind::Helper && form.text == std::string_view(h.name) &&
          ir::contains(f.body, op))
        return true;
    }
  }
  return false;
}

}  // namespace

std::string helper_bodies(Language d, const std::vector<Variant>& variants,
                          const std::function<std::string(const Helper&)>& missing) {
  std::string out;
  for (const Helper& h : helper_table())
    if (!h.on_demand) out += body_text(h, d, variants, missing);
  return out;
}

std::string on_demand_bodies(Language d, const ir::Function& f,
                             const std::function<std::string(const Helper&)>& missing) {
  std::string out;
  for (const Helper& h : helper_table())
    if (h.on_demand && calls(f, h)) out += body_text(h, d, {}, missing);
  return out;
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
