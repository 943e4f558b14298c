// Correctly rounded sqrt(x) where the driver's fma is fused (glsl/DivSqrt.h, the lean rule):
// special operands (0, subnormals as zero, negatives, inf, NaN) as in the split rule; x is
// scaled by an even power of two into m in [1, 4), so every other root takes one branch-free
// path. The driver's inversesqrt (within 2 ulp) gives s0 ~ sqrt(m) and h ~ 1/(2 sqrt(m)); one
// coupled Newton step refines both, then the exact residual m - s1*s1 corrects s1 with one
// rounding. A root of a float is never halfway between two floats, so there are no ties.
// Proved with the driver's inversesqrt anywhere within 3 ulp by tools/divsqrt-check (this
// exact text).
float rill_sqrt(float x) {
  uint u = floatBitsToUint(x);
  uint xe = (u >> 23) & 0xffu;
  if (xe == 0u) return uintBitsToFloat(u & 0x80000000u);
  if ((u & 0x80000000u) != 0u) return uintBitsToFloat(0x7fc00000u);
  if (xe == 255u) return x;
  int k = int(xe) - 127;
  int odd = k & 1;
  RILL_PRECISE float m = uintBitsToFloat((u & 0x7fffffu) | (uint(127 + odd) << 23));
  RILL_PRECISE float y = rill_native_rsqrt(m);
  RILL_PRECISE float s0 = m * y;
  RILL_PRECISE float h = 0.5 * y;
  RILL_PRECISE float t = fma(-s0, h, 0.5);
  RILL_PRECISE float s1 = fma(s0, t, s0);
  RILL_PRECISE float h1 = fma(h, t, h);
  RILL_PRECISE float d = fma(-s1, s1, m);
  RILL_PRECISE float s = fma(d, h1, s1);
  return uintBitsToFloat(floatBitsToUint(s) + (uint((k - odd) / 2) << 23));
}
