// Correctly rounded a / b where the driver's fma is fused (glsl/DivSqrt.h, the lean rule):
// special operands (0, inf, NaN; subnormals count as zero) and quotients outside the normal
// range are decided from the bits, as in the split rule; the significands are scaled into
// [1, 2), so every other quotient takes one branch-free path. The driver's reciprocal (within
// 2.5 ulp) is refined by one Newton step, then Markstein's two fmas give the correctly
// rounded quotient: the residual d = ma - q0*mb is exact, and q0 + d*r rounds once. The
// quotient of floats is never halfway between two floats, so there are no ties. Proved with
// the driver's reciprocal anywhere within 3 ulp by tools/divsqrt-check (this exact text).
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
  RILL_PRECISE float r0 = rill_native_div(RILL_ONE, mb);
  RILL_PRECISE float t = fma(-mb, r0, RILL_ONE);
  RILL_PRECISE float r = fma(r0, t, r0);
  RILL_PRECISE float q0 = ma * r;
  RILL_PRECISE float d = fma(-q0, mb, ma);
  RILL_PRECISE float q = fma(d, r, q0);
  return uintBitsToFloat(sign | (floatBitsToUint(q) + (uint(e) << 23)));
}
