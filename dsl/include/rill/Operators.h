// Arithmetic, comparison and logic operators on DSL values.
//
// Each operator records one IR operation. Operands may be values of the same scalar kind and
// equal width, a vector and a scalar (the scalar is broadcast), or a value and a host scalar
// (which becomes a constant). Comparisons are componentwise and give Bool vectors; use
// any()/all() to reduce them.
#pragma once

#include "rill/Value.h"

namespace rill {

namespace detail {

template <int N, int M>
constexpr int broadcast_width() {
  static_assert(N == M || N == 1 || M == 1,
                "rill: operand vector sizes differ (for example Float3 + Float2); use a "
                "swizzle such as v(0, 1) or a scalar");
  return N > M ? N : M;
}

template <class R, int W, class T, int N, int M>
Value<R, W> binary(ir::Op op, const Value<T, N>& a, const Value<T, M>& b) {
  return Value<R, W>(emit(op, type_of<R, W>(), {a.operand(), b.operand()}), AdoptTag{});
}

template <class R, int N, class T>
Value<R, N> unary(ir::Op op, const Value<T, N>& a) {
  return Value<R, N>(emit(op, type_of<R, N>(), {a.operand()}), AdoptTag{});
}

// A host scalar as a constant operand (no variable is created for it).
template <class T, class S>
Value<T, 1> host(S s) {
  return Value<T, 1>(Ref::constant(splat<T>(static_cast<T>(s), 1)), AdoptTag{});
}
template <class T, int N, class S>
Value<T, N> host_splat(S s) {
  return Value<T, N>(Ref::constant(splat<T>(static_cast<T>(s), N)), AdoptTag{});
}

}  // namespace detail

// Defines OP for (value, value), (value, host scalar) and (host scalar, value).
#define RILL_DEFINE_BINARY(OP, IROP, RESULT, CONSTRAINT)                                         \
  template <class T, int N, int M>                                                              \
    requires(CONSTRAINT)                                                                        \
  Value<RESULT, detail::broadcast_width<N, M>()> operator OP(const Value<T, N>& a,              \
                                                             const Value<T, M>& b) {            \
    return detail::binary<RESULT, detail::broadcast_width<N, M>()>(ir::Op::IROP, a, b);         \
  }                                                                                             \
  template <class T, int N, detail::HostScalarFor<T> S>                                         \
    requires(CONSTRAINT)                                                                        \
  Value<RESULT, N> operator OP(const Value<T, N>& a, S b) {                                     \
    return a OP detail::host<T>(b);                                                             \
  }                                                                                             \
  template <class T, int N, detail::HostScalarFor<T> S>                                         \
    requires(CONSTRAINT)                                                                        \
  Value<RESULT, N> operator OP(S a, const Value<T, N>& b) {                                     \
    return detail::host<T>(a) OP b;                                                             \
  }

#define RILL_NUMERIC (!std::is_same_v<T, bool>)
#define RILL_INTEGER (std::is_same_v<T, int32_t>)
#define RILL_BOOLEAN (std::is_same_v<T, bool>)
#define RILL_ANY true

RILL_DEFINE_BINARY(+, Add, T, RILL_NUMERIC)
RILL_DEFINE_BINARY(-, Sub, T, RILL_NUMERIC)
RILL_DEFINE_BINARY(*, Mul, T, RILL_NUMERIC)
// Float division is IEEE; Int division truncates, and x / 0 gives 0 on every backend.
RILL_DEFINE_BINARY(/, Div, T, RILL_NUMERIC)
// Int remainder (sign of the dividend, as in C); x % 0 gives 0. For floats use mod().
RILL_DEFINE_BINARY(%, Mod, T, RILL_INTEGER)
RILL_DEFINE_BINARY(&, BitAnd, T, RILL_INTEGER)
RILL_DEFINE_BINARY(|, BitOr, T, RILL_INTEGER)
RILL_DEFINE_BINARY(^, BitXor, T, RILL_INTEGER)
// Shifts use the low 5 bits of the count; >> is arithmetic (sign-extending).
RILL_DEFINE_BINARY(<<, Shl, T, RILL_INTEGER)
RILL_DEFINE_BINARY(>>, Shr, T, RILL_INTEGER)
RILL_DEFINE_BINARY(<, Lt, bool, RILL_NUMERIC)
RILL_DEFINE_BINARY(<=, Le, bool, RILL_NUMERIC)
RILL_DEFINE_BINARY(>, Gt, bool, RILL_NUMERIC)
RILL_DEFINE_BINARY(>=, Ge, bool, RILL_NUMERIC)
RILL_DEFINE_BINARY(==, Eq, bool, RILL_ANY)
RILL_DEFINE_BINARY(!=, Ne, bool, RILL_ANY)
// Both sides are always evaluated (there is no short circuit in a data-parallel kernel).
RILL_DEFINE_BINARY(&&, And, bool, RILL_BOOLEAN)
RILL_DEFINE_BINARY(||, Or, bool, RILL_BOOLEAN)

#undef RILL_DEFINE_BINARY
#undef RILL_NUMERIC
#undef RILL_INTEGER
#undef RILL_BOOLEAN
#undef RILL_ANY

template <class T, int N>
  requires(!std::is_same_v<T, bool>)
Value<T, N> operator-(const Value<T, N>& a) {
  return detail::unary<T>(ir::Op::Neg, a);
}
template <class T, int N>
  requires(!std::is_same_v<T, bool>)
Value<T, N> operator+(const Value<T, N>& a) {
  return a;
}
template <int N>
Value<bool, N> operator!(const Value<bool, N>& a) {
  return detail::unary<bool>(ir::Op::Not, a);
}
template <int N>
Value<int32_t, N> operator~(const Value<int32_t, N>& a) {
  return detail::unary<int32_t>(ir::Op::BitNot, a);
}

}  // namespace rill
