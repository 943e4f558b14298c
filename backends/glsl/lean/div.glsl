// Correctly rounded a / b where the driver's fma is fused (glsl/DivSqrt.h, the lean rule):
// special operands (0, inf, NaN; subnormals count as zero) and quotients outside the normal
// range are decided from the bits, as in the split rule; the significands are scaled into
// [1, 2), so every other quotient takes one branch-free path. From the driver's reciprocal r
// (within 2.5 ulp), q0 = ma * r is corrected once by its residual (Markstein's step: q1 =
// q0 + (ma - q0 mb) r, in fmas), which leaves q1 within an ulp; then q1's exact residual
// decides between q1 and its neighbours. (Markstein's step alone rounds correctly only with
// a correctly rounded reciprocal, which one Newton step does not give for divisors near 2:
// tools/divsqrt-check found a / (2 - 2^-23) wrong that way.) A quotient of floats is never
// halfway between two floats, so there are no ties. Proved with the driver's reciprocal any
// float within 3 of the correctly rounded one by tools/divsqrt-check (this exact text).
float rill_div_f(float a, float b) {
  uint ua = floatBitsToUint(a), ub = floatBitsToUint(b);
  uint sign = (ua ^ ub) & 0x80000000u;
  uint xa = (ua >> 23) & 0xffu, xb = (ub >> 23) & 0xffu;
  uint fa = ua & 0x7fffffu, fb = ub & 0x7fffffu;
  if (xa == 0u || xa == 255u || xb == 0u || xb == 255u) {
    bool inf_a = xa == 255u, inf_b = xb == 255u, zero_a = xa == 0u, zero_b = xb == 0u;
    if ((inf_a && fa != 0u) || (inf_b && fb != 0u) || (inf_a && inf_b) || (zero_a && zero_b))
      return uintBitsToFloat(0x7fc00000u);
    if (inf_a || zero_b) return uintBitsToFloat(sign | 0x7f800000u);
    return uintBitsToFloat(sign);
  }
  int e = int(xa) - int(xb);
  // The biased exponent of the exact quotient decides underflow (before rounding) and overflow.
  int exact_exp = e + 127 - (fa < fb ? 1 : 0);
  if (exact_exp <= 0) return uintBitsToFloat(sign);
  if (exact_exp >= 255) return uintBitsToFloat(sign | 0x7f800000u);
  RILL_PRECISE float ma = uintBitsToFloat(fa | 0x3f800000u);
  RILL_PRECISE float mb = uintBitsToFloat(fb | 0x3f800000u);
  RILL_PRECISE float r = rill_native_div(RILL_ONE, mb);
  RILL_PRECISE float q0 = ma * r;
  RILL_PRECISE float d0 = fma(-q0, mb, ma);
  RILL_PRECISE float q1 = fma(d0, r, q0);
  RILL_PRECISE float d1 = fma(-q1, mb, ma);
  // q1 is within an ulp of ma / mb, so d1 is exact, and which neighbour is nearest follows
  // from the signs of ma - (q1 +- half an ulp) mb: one rounding of an exact value each (below
  // a power of two the ulp is half the one above it).
  uint bq = floatBitsToUint(q1);
  RILL_PRECISE float half_up = uintBitsToFloat((bq & 0x7f800000u) - (24u << 23));
  RILL_PRECISE float half_down = (bq & 0x7fffffu) == 0u ? 0.5 * half_up : half_up;
  RILL_PRECISE float above = fma(-half_up, mb, d1);
  RILL_PRECISE float below = fma(half_down, mb, d1);
  bq = above > 0.0 ? bq + 1u : (below < 0.0 ? bq - 1u : bq);
  return uintBitsToFloat(sign | (bq + (uint(e) << 23)));
}
