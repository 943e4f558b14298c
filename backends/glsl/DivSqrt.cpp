// Correctly rounded division and square root for GLSL (see DivSqrt.h for the method).
#include "DivSqrt.h"

#include <cstdlib>

#include "GLSession.h"
#include "rill/Error.h"

namespace rill::glsl {

namespace {

// The driver's operations, or the inexact stand-ins of the test modes.
const char* kNativeOps = R"(
float rill_native_div(float a, float b) { RILL_PRECISE float q = a / b; return q; }
float rill_native_sqrt(float x) { RILL_PRECISE float s = sqrt(x); return s; }
)";
const char* kInexactOps = R"(
// Test mode: division and square root as NVIDIA's GLSL computes them (not correctly rounded).
float rill_native_div(float a, float b) { RILL_PRECISE float y = RILL_ONE / b; RILL_PRECISE float q = a * y; return q; }
float rill_native_sqrt(float x) { RILL_PRECISE float y = inversesqrt(x); RILL_PRECISE float s = x * y; return s; }
)";

const char* kUncorrected = R"(
float rill_div_f(float a, float b) { return rill_native_div(a, b); }
float rill_sqrt(float x) { return rill_native_sqrt(x); }
)";

// Operands of the exact steps lie in [0.5, 4], so nothing overflows or underflows.
const char* kCorrected = R"(
// a - q * b, exact when q * b is within a factor 2 of a and the result is representable:
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
}
bool rill_nan_bits(uint u) { return (u & 0x7fffffffu) > 0x7f800000u; }

float rill_div_f(float a, float b) {
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
}

float rill_sqrt(float x) {
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
}
)";

}  // namespace

const char* divsqrt_name(DivSqrt m) {
  switch (m) {
    case DivSqrt::Native:
      return "native";
    case DivSqrt::Corrected:
      return "corrected";
    case DivSqrt::Inexact:
      return "inexact";
    case DivSqrt::InexactCorrected:
      return "inexact-corrected";
  }
  return "?";
}

DivSqrt divsqrt_mode(const std::string& renderer) {
  const char* env = std::getenv("RILL_GLSL_DIVSQRT");
  std::string v = env ? env : "auto";
  if (v == "auto" || v.empty()) return is_llvmpipe(renderer) ? DivSqrt::Native : DivSqrt::Corrected;
  for (DivSqrt m :
       {DivSqrt::Native, DivSqrt::Corrected, DivSqrt::Inexact, DivSqrt::InexactCorrected})
    if (v == divsqrt_name(m)) return m;
  throw Error("RILL_GLSL_DIVSQRT='" + v +
              "' is not one of auto, native, corrected, inexact, inexact-corrected");
}

std::string divsqrt_helpers(DivSqrt m) {
  bool inexact = m == DivSqrt::Inexact || m == DivSqrt::InexactCorrected;
  bool corrected = m == DivSqrt::Corrected || m == DivSqrt::InexactCorrected;
  return std::string(inexact ? kInexactOps : kNativeOps) + (corrected ? kCorrected : kUncorrected);
}

}  // namespace rill::glsl
