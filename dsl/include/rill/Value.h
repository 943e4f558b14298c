// DSL value types: Float, Int, Bool and their 2-4 component vectors.
//
// A Value<T, N> stands for a per-element variable of a kernel. Inside a program's body each
// operation on values records IR (see Capture.h); outside any program a value is just a
// constant, which programs can read (handy for shared constants such as an up vector).
//
//   Float3 v(1.0f, 2.0f, 3.0f);
//   Float3 w = v(2, 0, 1);       // swizzle: (3, 1, 2)
//   v(0, 1) = w(1, 1);           // write mask: v.x = v.y = w.y
//   Float l = length(v) + v.x();
//
// Scalars broadcast against vectors (Float3 * Float). Vectors of different sizes do not
// mix: that is a compile-time error pointing at the expression.
#pragma once

#include <glm/glm.hpp>

#include <bit>
#include <concepts>
#include <cstdint>
#include <type_traits>

#include "rill/Capture.h"

namespace rill {

template <class T, int N>
class Value;
template <class T, int M>
class Swizzle;

namespace detail {

template <class T>
constexpr ir::ScalarKind kind_of() {
  if constexpr (std::is_same_v<T, float>) return ir::ScalarKind::Float;
  else if constexpr (std::is_same_v<T, int32_t>) return ir::ScalarKind::Int;
  else {
    static_assert(std::is_same_v<T, bool>, "rill: scalar type must be float, int32_t or bool");
    return ir::ScalarKind::Bool;
  }
}

template <class T, int N>
constexpr ir::Type type_of() {
  static_assert(N >= 1 && N <= 4, "rill: vectors have 1 to 4 components");
  return ir::Type{kind_of<T>(), static_cast<uint8_t>(N)};
}

template <class T>
uint32_t scalar_bits(T v) {
  if constexpr (std::is_same_v<T, float>) return std::bit_cast<uint32_t>(v);
  else if constexpr (std::is_same_v<T, int32_t>) return static_cast<uint32_t>(v);
  else return v ? 1u : 0u;
}

template <class T>
ir::Constant splat(T v, int n) {
  ir::Constant c;
  c.type = ir::Type{kind_of<T>(), static_cast<uint8_t>(n)};
  for (int i = 0; i < n; ++i) c.bits[static_cast<size_t>(i)] = scalar_bits(v);
  return c;
}

// Host scalars that may stand for a DSL scalar of kind T without losing meaning:
// any arithmetic type for Float, integers for Int, bool for Bool.
template <class S, class T>
concept HostScalarFor =
    std::is_arithmetic_v<S> &&
    ((std::is_same_v<T, float> && !std::is_same_v<S, bool>) ||
     (std::is_same_v<T, int32_t> && std::is_integral_v<S> && !std::is_same_v<S, bool>) ||
     (std::is_same_v<T, bool> && std::is_same_v<S, bool>));

struct AdoptTag {};

// Components contributed by a constructor argument: a host scalar gives 1; anything that is a
// Value<T, N> (swizzles, inputs, outputs, uniforms included) gives N.
template <class T, int N>
constexpr int width_of(const Value<T, N>*) {
  return N;
}
constexpr int width_of(...) { return 1; }
template <class A>
struct arg_width {
  static constexpr int value = width_of(static_cast<const A*>(nullptr));
};

}  // namespace detail

// The host-side type matching a DSL type (GLM vectors): what streams, arrays and uniforms
// take and give back on the host.
template <class T, int N>
struct HostTypeOf {
  using type = glm::vec<N, T, glm::defaultp>;
};
template <class T>
struct HostTypeOf<T, 1> {
  using type = T;
};

template <class T, int N>
class Value {
 public:
  using scalar_type = T;
  static constexpr int width = N;
  using host_type = typename HostTypeOf<T, N>::type;
  static constexpr ir::Type type() { return detail::type_of<T, N>(); }

  // Inside a program: a new variable, zero-initialized. Outside: the constant zero.
  Value() : Value(T{}, broadcast) {}

  // From a host scalar (scalars implicitly; vectors explicitly, broadcasting it). Inside a
  // program the new variable's statement records the line it is declared on.
  template <detail::HostScalarFor<T> S>
    requires(N == 1)
  Value(S v, SourceLoc loc = RILL_HERE) : Value(static_cast<T>(v), broadcast, loc) {}
  template <detail::HostScalarFor<T> S>
    requires(N > 1)
  explicit Value(S v, SourceLoc loc = RILL_HERE) : Value(static_cast<T>(v), broadcast, loc) {}

  // Broadcast of a DSL scalar: Float3(s) is (s, s, s).
  template <int M>
    requires(N > 1 && M == 1)
  explicit Value(const Value<T, M>& s) {
    ir::Operand o = s.operand();
    if (o.is_const()) {
      ir::Constant c = detail::splat<T>(T{}, N);
      for (int i = 0; i < N; ++i) c.bits[static_cast<size_t>(i)] = o.value.bits[0];
      init_from(detail::Ref::constant(c));
      return;
    }
    o.type = type();
    o.swizzle = {o.swizzle[0], o.swizzle[0], o.swizzle[0], o.swizzle[0]};
    ref_ = detail::emit(ir::Op::Copy, type(), {o});
  }

  // From a host vector of the matching size (a glm vector).
  template <class H>
    requires(N > 1 && std::is_same_v<H, host_type>)
  explicit Value(const H& v) {
    ir::Constant c;
    c.type = type();
    for (int i = 0; i < N; ++i) c.bits[static_cast<size_t>(i)] = detail::scalar_bits<T>(v[i]);
    init_from(detail::Ref::constant(c));
  }

  // From components: Float3(x, y, z), Float4(xyz, 1.0f), Float3(xy, z), ...
  template <class A0, class A1, class... As>
  Value(const A0& a0, const A1& a1, const As&... as) {
    constexpr int total = (detail::arg_width<std::remove_cvref_t<A0>>::value +
                           detail::arg_width<std::remove_cvref_t<A1>>::value +
                           (0 + ... + detail::arg_width<std::remove_cvref_t<As>>::value));
    static_assert(total == N, "rill: constructor components do not add up to the vector size");
    construct({component_operand(a0), component_operand(a1), component_operand(as)...});
  }

  // A copy (Float y = x;) is a statement too, located where it is made.
  Value(const Value& o, SourceLoc loc = RILL_HERE) { init_from_value(o.ref_, loc); }
  Value(Value&& o) noexcept : ref_(std::move(o.ref_)) {}
  ~Value() = default;

  Value& operator=(const Value& o) {
    write(ir::Mask{}, o.operand());
    return *this;
  }
  template <detail::HostScalarFor<T> S>
    requires(N == 1)
  Value& operator=(S v) {
    write(ir::Mask{}, ir::Operand::of_const(detail::splat<T>(static_cast<T>(v), 1)));
    return *this;
  }

  // Swizzles: v(2, 0, 1) reads components in that order; assigning to it writes them.
  template <std::integral... I>
    requires(sizeof...(I) >= 1 && sizeof...(I) <= 4)
  Swizzle<T, static_cast<int>(sizeof...(I))> operator()(I... idx) const {
    return Swizzle<T, static_cast<int>(sizeof...(I))>(*this, {static_cast<int>(idx)...});
  }
  Swizzle<T, 1> operator[](int i) const { return (*this)(i); }
  Swizzle<T, 1> x() const { return (*this)(0); }
  Swizzle<T, 1> y() const { return (*this)(1); }
  Swizzle<T, 1> z() const { return (*this)(2); }
  Swizzle<T, 1> w() const { return (*this)(3); }
  // Named swizzles, GLSL's spellings, as far as the width allows (v.xyz() on a Float2 does not
  // compile). Like v(0, 1), they can be assigned to: v.xy() = w;
  Swizzle<T, 2> xy() const requires(N >= 2) { return (*this)(0, 1); }
  Swizzle<T, 2> xz() const requires(N >= 3) { return (*this)(0, 2); }
  Swizzle<T, 2> yz() const requires(N >= 3) { return (*this)(1, 2); }
  Swizzle<T, 3> xyz() const requires(N >= 3) { return (*this)(0, 1, 2); }
  Swizzle<T, 4> xyzw() const requires(N == 4) { return (*this)(0, 1, 2, 3); }
  Swizzle<T, 1> r() const { return (*this)(0); }
  Swizzle<T, 1> g() const requires(N >= 2) { return (*this)(1); }
  Swizzle<T, 1> b() const requires(N >= 3) { return (*this)(2); }
  Swizzle<T, 1> a() const requires(N == 4) { return (*this)(3); }
  Swizzle<T, 2> rg() const requires(N >= 2) { return (*this)(0, 1); }
  Swizzle<T, 3> rgb() const requires(N >= 3) { return (*this)(0, 1, 2); }
  Swizzle<T, 4> rgba() const requires(N == 4) { return (*this)(0, 1, 2, 3); }

  template <class O>
  Value& operator+=(const O& o) {
    return *this = Value(*this + o);
  }
  template <class O>
  Value& operator-=(const O& o) {
    return *this = Value(*this - o);
  }
  template <class O>
  Value& operator*=(const O& o) {
    return *this = Value(*this * o);
  }
  template <class O>
  Value& operator/=(const O& o) {
    return *this = Value(*this / o);
  }

  // The operand reading this value in the current program (for the library's own use).
  ir::Operand operand(SourceLoc loc = {}) const { return detail::operand(ref_, type(), loc); }
  const detail::Ref& ref() const { return ref_; }

  // Adopts an existing reference (a fresh temporary, an input, an output...).
  Value(detail::Ref r, detail::AdoptTag) : ref_(std::move(r)) {}

 protected:
  struct BroadcastTag {};
  static constexpr BroadcastTag broadcast{};

  Value(T v, BroadcastTag, SourceLoc loc = {}) {
    init_from(detail::Ref::constant(detail::splat<T>(v, N)), loc);
  }

  // Constants stay constants outside programs; inside one a value is a variable of its own.
  void init_from(const detail::Ref& src, SourceLoc loc = {}) {
    if (!detail::in_program()) {
      ref_ = src;
      return;
    }
    ref_ = detail::new_var(type(), ir::VarRole::Local, {}, loc);
    detail::assign(ref_, ir::Mask{}, detail::operand(src, type(), loc), loc);
  }
  void init_from_value(const detail::Ref& src, SourceLoc loc = {}) {
    if (src.kind != detail::Ref::Kind::Var && !detail::in_program()) {
      ref_ = src;
      return;
    }
    init_from(src, loc);
  }

  void write(const ir::Mask& mask, const ir::Operand& src) {
    if (ref_.kind == detail::Ref::Kind::Uniform)
      throw Error("a uniform is read-only inside a kernel; set it on the host with set()",
                  detail::nearest_location());
    if (ref_.kind == detail::Ref::Kind::Const) {
      if (detail::in_program())
        throw Error(
            "a value created outside this program cannot be assigned inside it; declare it "
            "inside the program body",
            detail::nearest_location());
      if (!src.is_const() || !mask.full())
        throw Error("assignment outside a program scope");
      ref_.value = src.value;
      return;
    }
    detail::assign(ref_, mask, src);
  }

  template <class A>
  static ir::Operand component_operand(const A& a) {
    if constexpr (std::is_arithmetic_v<A>) {
      static_assert(detail::HostScalarFor<A, T>, "rill: component has the wrong scalar kind");
      return ir::Operand::of_const(detail::splat<T>(static_cast<T>(a), 1));
    } else {
      static_assert(std::is_same_v<typename A::scalar_type, T>,
                    "rill: components must have the vector's scalar kind (convert explicitly)");
      return a.operand();
    }
  }

  void construct(std::vector<ir::Operand> parts) {
    bool all_const = true;
    for (const auto& p : parts) all_const = all_const && p.is_const();
    if (all_const) {  // fold on the spot: constants stay readable and usable anywhere
      ir::Constant c;
      c.type = type();
      int i = 0;
      for (const auto& p : parts)
        for (int k = 0; k < p.width(); ++k) c.bits[static_cast<size_t>(i++)] = p.value.bits[static_cast<size_t>(k)];
      init_from(detail::Ref::constant(c));
      return;
    }
    detail::require_program("building a vector from variables");
    ref_ = detail::emit(ir::Op::Construct, type(), std::move(parts));
  }

  detail::Ref ref_;

  template <class, int>
  friend class Swizzle;
};

// A swizzle of a value: reads like a value; assigning to it writes the selected components
// of the value it came from (a write mask).
template <class T, int M>
class Swizzle : public Value<T, M> {
 public:
  template <int N>
  Swizzle(const Value<T, N>& parent, std::initializer_list<int> idx)
      : Value<T, M>(read(parent, idx), detail::AdoptTag{}), parent_(parent.ref()) {
    int i = 0;
    for (int c : idx) mask_.comps[static_cast<size_t>(i++)] = static_cast<uint8_t>(c);
    mask_.count = static_cast<uint8_t>(M);
  }

  Swizzle& operator=(const Value<T, M>& v) {
    assign_parent(v.operand());
    return *this;
  }
  Swizzle& operator=(const Swizzle& v) {
    assign_parent(v.operand());
    return *this;
  }
  template <detail::HostScalarFor<T> S>
  Swizzle& operator=(S v) {
    assign_parent(ir::Operand::of_const(detail::splat<T>(static_cast<T>(v), M)));
    return *this;
  }
  template <class O>
  Swizzle& operator+=(const O& o) {
    return *this = Value<T, M>(*this + o);
  }
  template <class O>
  Swizzle& operator-=(const O& o) {
    return *this = Value<T, M>(*this - o);
  }
  template <class O>
  Swizzle& operator*=(const O& o) {
    return *this = Value<T, M>(*this * o);
  }
  template <class O>
  Swizzle& operator/=(const O& o) {
    return *this = Value<T, M>(*this / o);
  }

 private:
  template <int N>
  static detail::Ref read(const Value<T, N>& parent, std::initializer_list<int> idx) {
    for (int c : idx)
      if (c < 0 || c >= N)
        throw Error("swizzle component " + std::to_string(c) + " is out of range for a " +
                        detail::type_of<T, N>().str(),
                    detail::nearest_location());
    const detail::Ref& p = parent.ref();
    if (p.kind == detail::Ref::Kind::Const) {
      ir::Constant c;
      c.type = detail::type_of<T, M>();
      int i = 0;
      for (int s : idx) c.bits[static_cast<size_t>(i++)] = p.value.bits[static_cast<size_t>(s)];
      return detail::Ref::constant(c);
    }
    ir::Operand o = parent.operand();
    const auto from = o.swizzle;  // compose with a copy: the loop below overwrites o.swizzle
    o.type = detail::type_of<T, M>();
    int i = 0;
    for (int s : idx) o.swizzle[static_cast<size_t>(i++)] = from[static_cast<size_t>(s)];
    return detail::emit(ir::Op::Copy, detail::type_of<T, M>(), {o});
  }

  void assign_parent(const ir::Operand& src) {
    for (int i = 0; i < M; ++i)
      for (int j = 0; j < i; ++j)
        if (mask_.comps[static_cast<size_t>(i)] == mask_.comps[static_cast<size_t>(j)])
          throw Error("write mask repeats component " +
                          std::to_string(mask_.comps[static_cast<size_t>(i)]),
                      detail::nearest_location());
    if (parent_.kind == detail::Ref::Kind::Uniform)
      throw Error("a uniform is read-only inside a kernel; set it on the host with set()",
                  detail::nearest_location());
    if (parent_.kind != detail::Ref::Kind::Var)
      throw Error("only a variable inside a program can be written through a swizzle",
                  detail::nearest_location());
    detail::assign(parent_, mask_, src);
  }

  detail::Ref parent_;
  ir::Mask mask_;
};

// Names the variable behind a value of the program being captured, so that printed IR
// (Program::print, Kernel::ir) and generated code (Kernel::source) call it by that name:
//
//   Float t = dot(n, l);
//   rill::label(t, "ndotl");     // printed as ndotl_12 (the variable id keeps names unique)
//
// Printers keep only identifier characters. Throws rill::Error for a constant made outside
// any program, a uniform, an input or an output (which keep their declared names), or a value
// of another program. The optimizer keeps the name while the variable survives; a named copy
// of an unnamed temporary passes its name on when copy propagation removes it.
template <class T, int N>
void label(const Value<T, N>& v, std::string name, SourceLoc loc = RILL_HERE) {
  detail::label(v.ref(), std::move(name), loc);
}

// The value types users write kernels with.
using Float = Value<float, 1>;
using Float2 = Value<float, 2>;
using Float3 = Value<float, 3>;
using Float4 = Value<float, 4>;
using Int = Value<int32_t, 1>;
using Int2 = Value<int32_t, 2>;
using Int3 = Value<int32_t, 3>;
using Int4 = Value<int32_t, 4>;
using Bool = Value<bool, 1>;
using Bool2 = Value<bool, 2>;
using Bool3 = Value<bool, 3>;
using Bool4 = Value<bool, 4>;

// Semantic names, as in Sh, where they make kernels read better. They are the same types.
using Point2 = Float2;
using Point3 = Float3;
using Vector2 = Float2;
using Vector3 = Float3;
using Normal3 = Float3;
using Color3 = Float3;
using Color4 = Float4;
using TexCoord2 = Float2;

}  // namespace rill
