// Value.h: constants outside programs, swizzles, write masks, vector constructors, and the
// type rules the operators enforce at compile time.
#include <functional>
#include <type_traits>

#include "TestUtil.h"

namespace rill {
namespace {

using test::normalized;

// ---- compile-time rules ----------------------------------------------------------------------

template <class A, class B>
concept Addable = requires(const A& a, const B& b) {
  a + b;
};
template <class A, class B>
concept Remainder = requires(const A& a, const B& b) {
  a % b;
};
template <class A, class B>
concept LogicalAnd = requires(const A& a, const B& b) {
  a&& b;
};
template <class A, class B>
concept BitAnd = requires(const A& a, const B& b) {
  a& b;
};
template <class A, class B>
concept Ordered = requires(const A& a, const B& b) {
  a < b;
};

// Mismatched vector sizes (Float3 + Float2) are a static_assert inside the operator, a hard
// error that concepts cannot observe; the rules below are constraints and can be checked.
static_assert(Addable<Float, Float>);
static_assert(Addable<Float3, Float>);
static_assert(Addable<Float, Float3>);
static_assert(Addable<Float3, float>);
static_assert(Addable<Int2, int>);
static_assert(!Addable<Float, Int>, "kinds never mix implicitly");
static_assert(!Addable<Int, float>, "a float host scalar does not become an Int");
static_assert(!Addable<Bool, Bool>, "no arithmetic on Bool");
static_assert(!Addable<Float, bool>);
static_assert(Remainder<Int, Int>);
static_assert(!Remainder<Float, Float>, "float remainder is mod()");
static_assert(BitAnd<Int3, Int3>);
static_assert(!BitAnd<Float, Float>);
static_assert(LogicalAnd<Bool, Bool>);
static_assert(LogicalAnd<Bool3, bool>);
static_assert(!LogicalAnd<Int, Int>);
static_assert(Ordered<Float3, Float3>);
static_assert(!Ordered<Bool, Bool>, "bools are not ordered");
static_assert(std::is_same_v<decltype(std::declval<Float3>() < std::declval<Float>()), Bool3>);
static_assert(std::is_same_v<decltype(std::declval<Float>() * std::declval<Float4>()), Float4>);
static_assert(std::is_same_v<decltype(std::declval<Float3>()(2, 0)), Swizzle<float, 2>>);
static_assert(std::is_convertible_v<float, Float>, "scalars convert implicitly");
static_assert(!std::is_convertible_v<float, Float3>, "broadcasting to a vector is explicit");
static_assert(std::is_constructible_v<Float3, float>);
static_assert(!std::is_convertible_v<Float, Int>);
static_assert(std::is_same_v<Point3, Float3> && std::is_same_v<Color4, Float4>);
static_assert(Float3::type() == ir::float_type(3) && Int2::type() == ir::int_type(2) &&
              Bool4::type() == ir::bool_type(4));

TEST(Value, TypeRulesHoldAtCompileTime) {
  SUCCEED() << "checked by the static_asserts above";
}

// Components of Input/Output/Uniform vectors count with their width, like any Value: the
// documented Float4(xyz, 1.0f) must accept an Input<Float3> as xyz.
TEST(Value, ConstructorCountsTheWidthOfInterfaceValues) {
  EXPECT_EQ(detail::arg_width<Float3>::value, 3);
  EXPECT_EQ((detail::arg_width<Swizzle<float, 2>>::value), 2);
  EXPECT_EQ(detail::arg_width<Input<Float3>>::value, 3)
      << "Float4(input3, 1.0f) fails to compile and Float4(input3, a, b, c) compiles";
  EXPECT_EQ(detail::arg_width<Output<Float2>>::value, 2);
  EXPECT_EQ(detail::arg_width<Uniform<Float3>>::value, 3);
}

// ---- constants outside programs --------------------------------------------------------------

TEST(Value, OutsideAProgramValuesAreConstants) {
  ASSERT_FALSE(detail::in_program());
  Float3 a(1.0f, 2.0f, 3.0f);
  EXPECT_EQ(a.ref().kind, detail::Ref::Kind::Const);
  EXPECT_EQ(a.ref().value.type, ir::float_type(3));
  EXPECT_EQ(a.ref().value.f(0), 1.0f);
  EXPECT_EQ(a.ref().value.f(2), 3.0f);

  Float3 s = a(2, 0, 1);  // swizzles of constants stay constants
  EXPECT_EQ(s.ref().kind, detail::Ref::Kind::Const);
  EXPECT_EQ(s.ref().value.f(0), 3.0f);
  EXPECT_EQ(s.ref().value.f(1), 1.0f);
  EXPECT_EQ(s.ref().value.f(2), 2.0f);

  Float4 h(a, 4.0f);  // so do vectors built from constants
  EXPECT_EQ(h.ref().kind, detail::Ref::Kind::Const);
  EXPECT_EQ(h.ref().value.f(3), 4.0f);
  EXPECT_EQ(h.ref().value.f(0), 1.0f);

  Float3 g(glm::vec3(4.0f, 5.0f, 6.0f));
  EXPECT_EQ(g.ref().value.f(1), 5.0f);
  Int3 i(7);
  EXPECT_EQ(i.ref().value.type, ir::int_type(3));
  EXPECT_EQ(i.ref().value.i(2), 7);
  Float z;
  EXPECT_EQ(z.ref().value.bits[0], 0u);
  Bool b = true;
  EXPECT_EQ(b.ref().value.bits[0], 1u);

  Float copy = Float(-0.0f);
  copy = Float(5.0f);  // assigning constants to constants is fine on the host
  EXPECT_EQ(copy.ref().value.f(0), 5.0f);
}

TEST(Value, ConstantsMadeOutsideAreInlinedInsidePrograms) {
  const Float3 up(0.0f, 1.0f, 0.0f);
  const Float3 odd = up(1, 1, 0);
  auto make = [&](const char* name) {
    return program(name, [&] {
      Input<Float3> v("v");
      Output<Float3> y("y");
      y = v * up + odd;
    });
  };
  Program a = make("a"), b = make("b");  // one constant, any number of programs
  std::string text = normalized(a.print());
  EXPECT_LINE(text, "t# = mul(v_0, float3(0.0, 1.0, 0.0))");
  EXPECT_LINE(text, "t# = add(t#, float3(1.0, 1.0, 0.0))");
  EXPECT_EQ(test::count_lines(text, "var float3 t#"), 2) << text;  // only the two results
  EXPECT_EQ(a.hash(), b.hash());
}

// ---- swizzles --------------------------------------------------------------------------------

TEST(Value, SwizzleOfAVariableReadsTheNamedComponents) {
  Program p = program("swizzle", [] {
    Input<Float4> v("v");
    Output<Float3> y("y");
    Output<Float2> z("z");
    y = v(2, 0, 1);
    z = v(1, 0);
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = copy(v_0.zxy)");
  EXPECT_LINE(text, "t# = copy(v_0.yx)");
}

TEST(Value, SwizzleReadsWithRepeatsAndSingleComponents) {
  Program p = program("repeat", [] {
    Input<Float4> v("v");
    Output<Float4> y("y");
    Output<Float> s("s");
    y = v(3, 3, 3, 3);
    s = v.w() + v[1] + v.x();
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = copy(v_0.wwww)");
  EXPECT_LINE(text, "t# = copy(v_0.w)");
  EXPECT_LINE(text, "t# = copy(v_0.y)");
  EXPECT_LINE(text, "t# = copy(v_0.x)");
}

TEST(Value, SwizzleOfASwizzleComposes) {
  Program p = program("compose", [] {
    Input<Float3> v("v");
    Output<Float2> y("y");
    y = v(2, 1, 0)(0, 0);  // (v.z, v.z)
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = copy(t#.xx)");
}

// ---- named swizzles --------------------------------------------------------------------------

template <class V>
concept HasXY = requires(const V& v) {
  v.xy();
};
template <class V>
concept HasXYZ = requires(const V& v) {
  v.xyz();
};
template <class V>
concept HasXZ = requires(const V& v) {
  v.xz();
};
template <class V>
concept HasRGBA = requires(const V& v) {
  v.rgba();
};
template <class V>
concept HasB = requires(const V& v) {
  v.b();
};
template <class V>
concept HasA = requires(const V& v) {
  v.a();
};

// Named swizzles exist only where the width has the components they name.
static_assert(HasXY<Float2> && HasXY<Int4> && !HasXY<Float>);
static_assert(HasXYZ<Float3> && HasXYZ<Float4> && !HasXYZ<Float2>);
static_assert(HasXZ<Float3> && !HasXZ<Int2>);
static_assert(HasRGBA<Float4> && !HasRGBA<Float3>);
static_assert(HasB<Float3> && !HasB<Float2>);
static_assert(HasA<Float4> && !HasA<Float3>);
static_assert(std::is_same_v<decltype(std::declval<Float4>().xyz()), Swizzle<float, 3>>);
static_assert(std::is_same_v<decltype(std::declval<Int3>().rg()), Swizzle<int32_t, 2>>);

TEST(Value, NamedSwizzlesReadTheirComponents) {
  Program p = program("named", [] {
    Input<Float4> v("v");
    Output<Float3> a("a");
    Output<Float2> b("b");
    Output<Float4> c("c");
    Output<Float> d("d");
    a = v.xyz() + v.rgb();
    b = v.xy() + v.xz() + v.yz() + v.rg();
    c = v.xyzw() + v.rgba();
    d = v.r() + v.g() + v.b() + v.a();
  });
  std::string text = normalized(p.print());
  EXPECT_EQ(test::count_lines(text, "t# = copy(v_0.xyz)"), 2);
  EXPECT_EQ(test::count_lines(text, "t# = copy(v_0.xy)"), 2);
  EXPECT_LINE(text, "t# = copy(v_0.xz)");
  EXPECT_LINE(text, "t# = copy(v_0.yz)");
  EXPECT_EQ(test::count_lines(text, "t# = copy(v_0)"), 2);  // xyzw and rgba: the whole vector
  for (const char* c : {"x", "y", "z", "w"})
    EXPECT_LINE(text, std::string("t# = copy(v_0.") + c + ")");
}

TEST(Value, NamedSwizzlesAreWriteMasks) {
  Program p = program("named_masks", [] {
    Input<Float2> w("w");
    Input<Float> s("s");
    Output<Float4> y("y");
    y = Float4(0.0f);
    y.xy() = w;
    y.b() = s;
    y.a() = 1.0f;
    y.rgb() += 2.0f;
    Float3 t = y.xyz();
    t.yz() = w;
    y.xz() = t.xz();
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "y_2.xy = copy(w_0)");
  EXPECT_LINE(text, "y_2.z = copy(s_1)");
  EXPECT_LINE(text, "y_2.w = copy(1.0)");
  EXPECT_LINE(text, "y_2.xyz = copy(t#)");
  EXPECT_LINE(text, "t#.yz = copy(w_0)");
  EXPECT_LINE(text, "y_2.xz = copy(t#)");
}

// ---- write masks -----------------------------------------------------------------------------

TEST(Value, WriteMasksAssignTheSelectedComponents) {
  Program p = program("mask", [] {
    Input<Float3> v("v");
    Input<Float> s("s");
    Output<Float3> y("y");
    y = v;
    y(0, 2) = Float2(s, s);
    y(1) = 5.0f;
    y(2, 1) = 7.0f;  // a host scalar fills every selected component
    y(0, 1) += 1.0f;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "y_2.xz = copy(t#)");
  EXPECT_LINE(text, "y_2.y = copy(5.0)");
  EXPECT_LINE(text, "y_2.zy = copy(float2(7.0, 7.0))");
  EXPECT_LINE(text, "y_2.xy = copy(t#)");
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Add), 1);
}

TEST(Value, WriteMaskThroughAnOutputAndALocal) {
  Program p = program("mask2", [] {
    Input<Float4> v("v");
    Output<Float4> y("y");
    Float4 t = v;
    t(3, 0) = v(0, 3);  // swap x and w
    y = t;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t#.wx = copy(t#)");
  EXPECT_EQ(test::problems(p.ir()), "");
}

// ---- vector constructors ---------------------------------------------------------------------

TEST(Value, ConstructorsFromVariablesRecordConstruct) {
  Program p = program("construct", [] {
    Input<Float> x("x");
    Input<Float2> xy("xy");
    Output<Float4> y("y");
    Float3 a(x, x, 1.0f);
    Float4 b(Float2(xy), 0.5f, x);
    Float4 c(xy(1, 0), Float2(xy));  // swizzles are components too
    y = Float4(a, 2.0f) + b + c;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = construct(x_0, x_0, 1.0)");
  EXPECT_LINE(text, "t# = construct(t#, 0.5, x_0)");
  EXPECT_LINE(text, "t# = construct(t#, t#)");
  EXPECT_LINE(text, "t# = construct(t#, 2.0)");
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Construct), 4);
}

// Inside a program a value made from constants is a variable (it may be assigned later), so
// only constructors whose every component is a constant are folded.
TEST(Value, ConstructorsFromConstantsInsideAProgramAreFoldedOnTheSpot) {
  Program p = program("consts", [] {
    Input<Float> x("x");
    Output<Float4> y("y");
    Output<Int2> w("w");
    Float3 a(1.0f, 2.0f, 3.0f);
    Float4 b(a, 4.0f);
    Float4 c(2.0f);
    Int2 d(glm::ivec2(5, 6));
    y = b + c * x;
    w = d;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = copy(float3(1.0, 2.0, 3.0))");
  EXPECT_LINE(text, "t# = construct(t#, 4.0)");  // a is a variable
  EXPECT_LINE(text, "t# = copy(float4(2.0, 2.0, 2.0, 2.0))");
  EXPECT_LINE(text, "t# = copy(int2(5, 6))");
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Construct), 1) << text;
}

TEST(Value, CopiesInsideAProgramAreNewVariables) {
  Program p = program("copies", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float a = x;  // a variable of its own, initialized from x
    a += 1.0f;
    y = a + x;  // x is unchanged
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = copy(x_0)");
  EXPECT_EQ(test::count_lines(text, "x_0 = copy(t#)"), 0);
}

TEST(Value, DefaultValueInsideAProgramIsAZeroedVariable) {
  Program p = program("zero", [] {
    Input<Float> x("x");
    Output<Int3> y("y");
    Int3 z;
    y = z + to_int(x);
  });
  EXPECT_LINE(normalized(p.print()), "t# = copy(int3(0, 0, 0))");
}

}  // namespace
}  // namespace rill
