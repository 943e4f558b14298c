// Counter-based random numbers in kernels: Philox4x32-10 (Salmon, Moraes, Dror and Shaw,
// "Parallel random numbers: as easy as 1, 2, 3", SC 2011; the generator of Random123, cuRAND
// and PyTorch's GPU back end).
//
// A counter-based generator has no state to carry: the numbers are a function of a counter
// and a key, so each element computes its own from what identifies it (a pixel, a sample
// index, a bounce, a purpose) and a user's seed, in any order, on any backend, and gets the
// same bits. Philox4x32-10 maps a 128-bit counter and a 64-bit key to 128 random bits in ten
// rounds of two 32 x 32 -> 64-bit multiplications; it passes BigCrush, and its outputs for
// the counters of Random123's known-answer vectors are checked on every backend
// (tests/backends/RandomTest.cpp).
//
//   Int4 bits = philox4x32(Int4(pixel, sample, bounce, purpose), Int2(seed, 0));
//   Float4 u = unit_float(bits);  // four uniform floats in [0, 1), on the grid of 2^-24
//
// Distinct counters under one key give independent streams; keep every field of the counter
// meaningful (a purpose number per use in a kernel) rather than reusing one counter for two
// things. Rill's Int is signed, so the unsigned arithmetic goes through shr_logical and
// mul_hi_unsigned (rill/Math.h): + and * wrap, which is the unsigned arithmetic's low half.
#pragma once

#include "rill/Math.h"
#include "rill/Value.h"

namespace rill {

namespace detail {
// The 32-bit pattern of an unsigned constant, as an Int.
constexpr int32_t bits32(uint32_t u) {
  return static_cast<int32_t>(u);
}
}  // namespace detail

// Philox4x32 with 10 rounds: 128 random bits from a 128-bit counter and a 64-bit key.
inline Int4 philox4x32(const Int4& counter, const Int2& key) {
  const Int m0 = detail::bits32(0xD2511F53u), m1 = detail::bits32(0xCD9E8D57u);
  Int c0 = counter.x(), c1 = counter.y(), c2 = counter.z(), c3 = counter.w();
  Int k0 = key.x(), k1 = key.y();
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {  // the key schedule: Weyl sequences of the golden ratio and sqrt(3) - 1
      k0 = k0 + detail::bits32(0x9E3779B9u);
      k1 = k1 + detail::bits32(0xBB67AE85u);
    }
    const Int hi0 = mul_hi_unsigned(m0, c0), lo0 = m0 * c0;
    const Int hi1 = mul_hi_unsigned(m1, c2), lo1 = m1 * c2;
    c0 = hi1 ^ c1 ^ k0;
    c1 = lo1;
    c2 = hi0 ^ c3 ^ k1;
    c3 = lo0;
  }
  return Int4(c0, c1, c2, c3);
}

}  // namespace rill
