// The DSL's math library: free functions on DSL values, found by argument-dependent lookup,
// so kernels read like the math (normalize(v), dot(a, b), min(x, 1.0f)).
//
// Functions marked "defined as" are built from other operations here, so that every
// backend evaluates the same formula; the rest are single IR operations whose exact results
// per accuracy mode are documented in docs/accuracy.md.
//
// Each takes its call site as a defaulted last argument (SourceLoc), so the statements it
// records, its own operations included, carry the user's line (detail::LocatedCall).
#pragma once

#include "rill/Operators.h"

namespace rill {

namespace detail {
template <class T, int N, class S>
Value<T, N> lift(const S& s) {
  if constexpr (std::is_arithmetic_v<S>) return host_splat<T, N>(s);
  else return Value<T, N>(s);
}
}  // namespace detail

#define RILL_FLOAT_UNARY(fn, IROP)                                          \
  template <int N>                                                          \
  Value<float, N> fn(const Value<float, N>& x, SourceLoc loc = RILL_HERE) { \
    detail::LocatedCall at(loc);                                            \
    return detail::unary<float>(ir::Op::IROP, x);                           \
  }

RILL_FLOAT_UNARY(floor, Floor)
RILL_FLOAT_UNARY(ceil, Ceil)
RILL_FLOAT_UNARY(trunc, Trunc)  // toward zero
RILL_FLOAT_UNARY(fract, Fract)  // x - floor(x)
RILL_FLOAT_UNARY(sqrt, Sqrt)
RILL_FLOAT_UNARY(rsqrt, Rsqrt)  // 1 / sqrt(x)
RILL_FLOAT_UNARY(exp, Exp)
RILL_FLOAT_UNARY(log, Log)
RILL_FLOAT_UNARY(exp2, Exp2)
RILL_FLOAT_UNARY(log2, Log2)
RILL_FLOAT_UNARY(sin, Sin)
RILL_FLOAT_UNARY(cos, Cos)
RILL_FLOAT_UNARY(tan, Tan)
RILL_FLOAT_UNARY(atan, Atan)
#undef RILL_FLOAT_UNARY

template <class T, int N>
  requires(!std::is_same_v<T, bool>)
Value<T, N> abs(const Value<T, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<T>(ir::Op::Abs, x);
}
// -1, 0 or +1 (and sign(NaN) = 0, sign(-0) = 0).
template <class T, int N>
  requires(!std::is_same_v<T, bool>)
Value<T, N> sign(const Value<T, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<T>(ir::Op::Sign, x);
}

#define RILL_BINARY_FN(fn, IROP, CONSTRAINT)                                                    \
  template <class T, int N, int M>                                                              \
    requires(CONSTRAINT)                                                                        \
  Value<T, detail::broadcast_width<N, M>()> fn(const Value<T, N>& a, const Value<T, M>& b,      \
                                               SourceLoc loc = RILL_HERE) {                     \
    detail::LocatedCall at(loc);                                                                \
    return detail::binary<T, detail::broadcast_width<N, M>()>(ir::Op::IROP, a, b);              \
  }                                                                                             \
  template <class T, int N, detail::HostScalarFor<T> S>                                         \
    requires(CONSTRAINT)                                                                        \
  Value<T, N> fn(const Value<T, N>& a, S b, SourceLoc loc = RILL_HERE) {                        \
    return fn(a, detail::host<T>(b), loc);                                                      \
  }                                                                                             \
  template <class T, int N, detail::HostScalarFor<T> S>                                         \
    requires(CONSTRAINT)                                                                        \
  Value<T, N> fn(S a, const Value<T, N>& b, SourceLoc loc = RILL_HERE) {                        \
    return fn(detail::host<T>(a), b, loc);                                                      \
  }

// min(a, b) = b < a ? b : a and max(a, b) = a < b ? b : a, on every backend: with a NaN
// operand the first operand is returned.
RILL_BINARY_FN(min, Min, (!std::is_same_v<T, bool>))
RILL_BINARY_FN(max, Max, (!std::is_same_v<T, bool>))
// mod(x, y) = x - y * floor(x / y), as in GLSL.
RILL_BINARY_FN(mod, Mod, (std::is_same_v<T, float>))
RILL_BINARY_FN(pow, Pow, (std::is_same_v<T, float>))
RILL_BINARY_FN(atan2, Atan2, (std::is_same_v<T, float>))  // atan2(y, x)
// An Int's 32 bits read as an unsigned number, for hashes and counter-based random numbers
// (rill/Random.h): shr_logical(x, n) shifts right filling with zeros (by the low 5 bits of n,
// as >> does), and mul_hi_unsigned(a, b) is the high 32 bits of the 64-bit product of a and b
// as unsigned numbers (the low half is a * b).
RILL_BINARY_FN(shr_logical, ShrU, (std::is_same_v<T, int32_t>))
RILL_BINARY_FN(mul_hi_unsigned, MulHiU, (std::is_same_v<T, int32_t>))
#undef RILL_BINARY_FN

// Defined as min(max(x, lo), hi).
template <class T, int N, class L, class H>
Value<T, N> clamp(const Value<T, N>& x, const L& lo, const H& hi, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return min(max(x, lo), hi);
}
// Defined as a + (b - a) * t.
template <int N, class B, class U>
Value<float, N> lerp(const Value<float, N>& a, const B& b, const U& t, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return a + (detail::lift<float, N>(b) - a) * t;
}

// Componentwise choice: c ? a : b (a scalar condition chooses whole vectors).
template <class T, int N, int C>
  requires(C == 1 || C == N)
Value<T, N> select(const Value<bool, C>& c, const Value<T, N>& a, const Value<T, N>& b,
                   SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return Value<T, N>(detail::emit(ir::Op::Select, detail::type_of<T, N>(),
                                  {c.operand(), a.operand(), b.operand()}),
                     detail::AdoptTag{});
}
template <class T, int N, int C, detail::HostScalarFor<T> S>
Value<T, N> select(const Value<bool, C>& c, const Value<T, N>& a, S b, SourceLoc loc = RILL_HERE) {
  return select(c, a, detail::host_splat<T, N>(b), loc);
}
template <class T, int N, int C, detail::HostScalarFor<T> S>
Value<T, N> select(const Value<bool, C>& c, S a, const Value<T, N>& b, SourceLoc loc = RILL_HERE) {
  return select(c, detail::host_splat<T, N>(a), b, loc);
}
// Sh's name for select.
template <class C, class A, class B>
auto cond(const C& c, const A& a, const B& b, SourceLoc loc = RILL_HERE) {
  return select(c, a, b, loc);
}

// Defined as the sum of products in component order: ((a.x*b.x + a.y*b.y) + a.z*b.z) + ...
template <int N>
Float dot(const Value<float, N>& a, const Value<float, N>& b, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return Float(detail::emit(ir::Op::Dot, ir::float_type(1), {a.operand(), b.operand()}),
               detail::AdoptTag{});
}
inline Float3 cross(const Float3& a, const Float3& b, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return Float3(detail::emit(ir::Op::Cross, ir::float_type(3), {a.operand(), b.operand()}),
                detail::AdoptTag{});
}
// Defined as sqrt(dot(v, v)).
template <int N>
Float length(const Value<float, N>& v, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return sqrt(dot(v, v));
}
template <int N>
Float distance(const Value<float, N>& a, const Value<float, N>& b, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return length(a - b);
}
// Defined as v / sqrt(dot(v, v)); a zero vector gives NaN components.
template <int N>
Value<float, N> normalize(const Value<float, N>& v, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return v / length(v);
}
// Defined as i - 2 * dot(n, i) * n (n normalized), as in GLSL.
template <int N>
Value<float, N> reflect(const Value<float, N>& i, const Value<float, N>& n,
                        SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return i - (2.0f * dot(n, i)) * n;
}
// Defined as in GLSL: with k = 1 - eta^2 (1 - dot(n, i)^2), zero if k < 0 (total internal
// reflection), else eta * i - (eta * dot(n, i) + sqrt(k)) * n.
template <int N>
Value<float, N> refract(const Value<float, N>& i, const Value<float, N>& n, const Float& eta,
                        SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  Float d = dot(n, i);
  Float k = 1.0f - eta * eta * (1.0f - d * d);
  Value<float, N> r = eta * i - (eta * d + sqrt(max(k, 0.0f))) * n;
  return select(k < 0.0f, detail::host_splat<float, N>(0.0f), r);
}

// Reductions of Bool vectors.
template <int N>
Bool any(const Value<bool, N>& b, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  Bool r = b[0];
  for (int i = 1; i < N; ++i) r = r || b[i];
  return r;
}
template <int N>
Bool all(const Value<bool, N>& b, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  Bool r = b[0];
  for (int i = 1; i < N; ++i) r = r && b[i];
  return r;
}

// Conversions. to_int truncates toward zero; NaN gives 0 and out-of-range values saturate.
template <int N>
Value<float, N> to_float(const Value<int32_t, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<float>(ir::Op::IntToFloat, x);
}
template <int N>
Value<int32_t, N> to_int(const Value<float, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<int32_t>(ir::Op::FloatToInt, x);
}
// Bit reinterpretation (IEEE binary32 <-> two's complement), e.g. for robust ray offsets.
template <int N>
Value<int32_t, N> as_int(const Value<float, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<int32_t>(ir::Op::FloatBitsToInt, x);
}
template <int N>
Value<float, N> as_float(const Value<int32_t, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<float>(ir::Op::IntBitsToFloat, x);
}
// A float in [0, 1) from the high 24 bits of x read as unsigned: (x >>> 8) * 2^-24, exact,
// so every backend and accuracy mode gives the same value. Uniform when x is.
template <int N>
Value<float, N> unit_float(const Value<int32_t, N>& x, SourceLoc loc = RILL_HERE) {
  detail::LocatedCall at(loc);
  return detail::unary<float>(ir::Op::UnitFloat, x);
}

// The index of the stream element being computed, 0 .. n-1.
Int element_index(SourceLoc loc = RILL_HERE);
// For streams with a 2D shape: (column, row) of the element; for 1D streams (index, 0).
Int2 element_coord(SourceLoc loc = RILL_HERE);

}  // namespace rill
