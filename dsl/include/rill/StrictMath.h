// Rill's own math routines: transcendental functions built only from +, -, *, /, floor,
// comparisons, selects and bit operations, so every backend computes the same bits.
//
// In the `strict` accuracy mode the compiler replaces exp, log, sin, ... by these routines
// (passes::lower_math); `fast` uses each backend's built-ins instead. They are ordinary DSL
// code, so a kernel can also call them directly (rill::strict::sin(x)); their bits are
// portable only in strict mode, since in fast mode the backend's compiler may reassociate
// their arithmetic (and then their error bounds do not hold either). Their measured error
// against a double-precision reference is in docs/accuracy.md.
//
// Special values follow C99 Annex F (exp(-inf) = 0, log(0) = -inf, log(-1) = NaN,
// pow(x, 0) = 1, atan2(+0, -0) = pi, sin(inf) = NaN, ...). sin, cos and tan reduce their
// argument with a four-part pi/4 (Cody and Waite), exact while |x| < 6434; beyond that the
// error grows with |x| (there is no Payne-Hanek reduction), and beyond about 2^23, where
// floats are farther apart than the period, results are only bounded (sin and cos in
// [-1, 1], tan finite).
#pragma once

#include "rill/Math.h"

namespace rill::strict {

Float exp(const Float& x);
Float exp2(const Float& x);
Float log(const Float& x);
Float log2(const Float& x);
Float pow(const Float& x, const Float& y);
// pow(x, y) for x = +0 or -0, with pow's bits, in a few selects: for a caller that skips
// pow's work where its base is zero (and still must give pow's result there). Undefined
// for any other x.
Float pow_of_zero(const Float& x, const Float& y);
// Whether c + s * pow(x, y) is sure to have the bits of c + s * 0 (c's own, but for c = -0),
// whatever pow's rounding: a test of a few operations for a caller that adds a pow term (a
// Phong highlight) and may leave pow out where the term is too small to change the sum. True
// only for a finite s >= 0, a positive normal x and y > 0, where an upper bound of pow(x, y)
// from x's bits, added in the caller's own arithmetic, leaves c as it is (rounding is
// monotonic, so the smaller true term does too). Valid in every accuracy mode.
Bool pow_term_is_lost(const Float& c, const Float& s, const Float& x, const Float& y);
Float sin(const Float& x);
Float cos(const Float& x);
Float tan(const Float& x);
Float atan(const Float& x);
Float atan2(const Float& y, const Float& x);

// Exact classification by bit pattern (comparisons with NaN are not reliable in every
// shading language).
Bool is_nan(const Float& x);
Bool is_inf(const Float& x);
// +0 or -0, by the bits: a denormal is not zero even where a backend flushes it in arithmetic.
Bool is_zero(const Float& x);
Bool sign_bit(const Float& x);
Float copy_sign(const Float& magnitude, const Float& sign);
// x * 2^n for n in [-252, 254], rounded once.
Float scale_by_power_of_two(const Float& x, const Int& n);

}  // namespace rill::strict
