// The exact meaning of each IR operation on one component: the eval column of Ops.def.
//
// Constant folding (passes/Fold.cpp) and the reference interpreter compute with these, so
// they are the definition every backend's output is checked against. Each function is
// overloaded on the component types it accepts (float, int32_t, bool); an op is not defined
// on a kind it has no overload for. Float operations are binary32, one rounding per
// operation: the library is compiled without FMA contraction (CMakeLists.txt), and x86-64
// float arithmetic is SSE, so each result is the correctly rounded value every strict backend
// produces. Operations whose result IEEE 754 does not pin down (exp, sin, ...) are
// eval::none: never folded, and lowered to Rill's own routines in strict mode.
//
// Dot, Cross and Construct combine components, so theirs take whole constants.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "rill/ir/IR.h"

namespace rill::ir::eval {

// Not evaluated exactly (transcendental), or not a computation on values (gather, element).
struct None {};
inline constexpr None none{};

inline int32_t wrap(int64_t v) {
  return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(v)));
}

template <class T>
T copy(T a) {
  return a;
}

inline float neg(float a) {
  return -a;
}
inline int32_t neg(int32_t a) {
  return wrap(-static_cast<int64_t>(a));
}
inline float add(float a, float b) {
  return a + b;
}
inline int32_t add(int32_t a, int32_t b) {
  return wrap(static_cast<int64_t>(a) + b);
}
inline float sub(float a, float b) {
  return a - b;
}
inline int32_t sub(int32_t a, int32_t b) {
  return wrap(static_cast<int64_t>(a) - b);
}
inline float mul(float a, float b) {
  return a * b;
}
inline int32_t mul(int32_t a, int32_t b) {
  return wrap(static_cast<int64_t>(a) * b);
}
inline float div(float a, float b) {
  return a / b;
}
// Division by zero gives 0; INT_MIN / -1 wraps.
inline int32_t div(int32_t a, int32_t b) {
  return b == 0 ? 0 : wrap(static_cast<int64_t>(a) / b);
}
// a - b * floor(a / b), one rounding per step (GLSL's mod).
inline float mod(float a, float b) {
  float q = a / b;
  float fl = std::floor(q);
  float m = b * fl;
  return a - m;
}
// C's remainder (sign of a); by zero gives 0.
inline int32_t mod(int32_t a, int32_t b) {
  return b == 0 ? 0 : static_cast<int32_t>(static_cast<int64_t>(a) % b);
}
// min and max return the first operand unless the second is strictly smaller (larger), so a
// NaN second operand is ignored and a NaN first one returned.
inline float min(float a, float b) {
  return b < a ? b : a;
}
inline int32_t min(int32_t a, int32_t b) {
  return b < a ? b : a;
}
inline float max(float a, float b) {
  return a < b ? b : a;
}
inline int32_t max(int32_t a, int32_t b) {
  return a < b ? b : a;
}
inline float abs(float a) {
  return std::bit_cast<float>(std::bit_cast<uint32_t>(a) & 0x7fffffffu);
}
inline int32_t abs(int32_t a) {
  return wrap(a < 0 ? -static_cast<int64_t>(a) : a);
}
inline float sign(float x) {
  return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f);
}
inline int32_t sign(int32_t a) {
  return a > 0 ? 1 : (a < 0 ? -1 : 0);
}

inline float floor(float a) {
  return std::floor(a);
}
inline float ceil(float a) {
  return std::ceil(a);
}
// Rounds toward zero (-0.5 gives -0).
inline float trunc(float a) {
  return std::trunc(a);
}
inline float fract(float a) {
  float fl = std::floor(a);
  return a - fl;
}
inline float sqrt(float a) {
  return std::sqrt(a);
}
inline float rsqrt(float a) {
  float s = std::sqrt(a);
  return 1.0f / s;
}

inline int32_t bit_and(int32_t a, int32_t b) {
  return a & b;
}
inline int32_t bit_or(int32_t a, int32_t b) {
  return a | b;
}
inline int32_t bit_xor(int32_t a, int32_t b) {
  return a ^ b;
}
inline int32_t bit_not(int32_t a) {
  return ~a;
}
// Shift counts are taken modulo 32.
inline int32_t shl(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) << (b & 31));
}
inline int32_t shr(int32_t a, int32_t b) {
  return a >> (b & 31);
}
// The unsigned views of the 32 bits, for hashes and counter-based random numbers: the
// logical (zero-filling) right shift, and the high half of the 64-bit unsigned product.
inline int32_t shr_u(int32_t a, int32_t b) {
  return static_cast<int32_t>(static_cast<uint32_t>(a) >> (b & 31));
}
inline int32_t mul_hi_u(int32_t a, int32_t b) {
  const uint64_t p = uint64_t{static_cast<uint32_t>(a)} * static_cast<uint32_t>(b);
  return static_cast<int32_t>(static_cast<uint32_t>(p >> 32));
}

inline bool logic_and(bool a, bool b) {
  return a && b;
}
inline bool logic_or(bool a, bool b) {
  return a || b;
}
inline bool logic_not(bool a) {
  return !a;
}

template <class T>
bool lt(T a, T b) requires(!std::is_same_v<T, bool>) {
  return a < b;
}
template <class T>
bool le(T a, T b) requires(!std::is_same_v<T, bool>) {
  return a <= b;
}
template <class T>
bool gt(T a, T b) requires(!std::is_same_v<T, bool>) {
  return a > b;
}
template <class T>
bool ge(T a, T b) requires(!std::is_same_v<T, bool>) {
  return a >= b;
}
template <class T>
bool eq(T a, T b) {
  return a == b;
}
template <class T>
bool ne(T a, T b) {
  return a != b;
}

template <class T>
T select(bool c, T a, T b) {
  return c ? a : b;
}

inline float int_to_float(int32_t i) {
  return static_cast<float>(i);
}
// Truncation toward zero; NaN gives 0, out-of-range values saturate.
inline int32_t float_to_int(float x) {
  if (x != x) return 0;
  if (x >= 2147483648.0f) return std::numeric_limits<int32_t>::max();
  if (x < -2147483648.0f) return std::numeric_limits<int32_t>::min();
  return static_cast<int32_t>(x);
}
inline int32_t float_bits(float x) {
  return std::bit_cast<int32_t>(x);
}
inline float int_bits(int32_t i) {
  return std::bit_cast<float>(i);
}
// The high 24 bits of the unsigned value, times 2^-24: a float in [0, 1) on the grid of
// 2^-24, exact (every such value is a binary32 number), so the same on every backend and mode.
inline float unit_float(int32_t i) {
  return static_cast<float>(static_cast<uint32_t>(i) >> 8) * 0x1p-24f;
}

// Whole-value ops: (result type, operands) -> result.
using Constants = std::vector<Constant>;

// ((a.x*b.x + a.y*b.y) + a.z*b.z) + a.w*b.w: one fixed order everywhere.
inline Constant dot(Type result, const Constants& args) {
  Constant out;
  out.type = result;
  float s = 0.0f;
  for (int c = 0; c < args[0].type.width; ++c) {
    float p = args[0].f(c) * args[1].f(c);
    s = c == 0 ? p : s + p;
  }
  out.bits[0] = std::bit_cast<uint32_t>(s);
  return out;
}
// Component c is a[c+1] b[c+2] - a[c+2] b[c+1].
inline Constant cross(Type result, const Constants& args) {
  Constant out;
  out.type = result;
  for (int c = 0; c < 3; ++c) {
    int i = (c + 1) % 3, j = (c + 2) % 3;
    float p = args[0].f(i) * args[1].f(j);
    float q = args[0].f(j) * args[1].f(i);
    out.bits[static_cast<size_t>(c)] = std::bit_cast<uint32_t>(p - q);
  }
  return out;
}
// The operands' components, in order.
inline Constant construct(Type result, const Constants& args) {
  Constant out;
  out.type = result;
  size_t i = 0;
  for (const Constant& k : args)
    for (int c = 0; c < k.type.width; ++c) out.bits[i++] = k.bits[static_cast<size_t>(c)];
  return out;
}

}  // namespace rill::ir::eval
