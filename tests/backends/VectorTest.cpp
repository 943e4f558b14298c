// Vectors: swizzles (reads in any order, repeated, nested), write masks (including masks whose
// source aliases the destination), constructors, and the geometric functions, which are
// defined by formula (Math.h) and so compared bit for bit with the same formula in C++.
#include "BackendTest.h"

namespace rill::testing {
namespace {

using F2 = glm::vec2;
using F3 = glm::vec3;
using F4 = glm::vec4;
using I4 = glm::ivec4;

class VectorTest : public BackendTest {};

// Moderate random 4-vectors with distinct components (so a wrong component shows).
std::vector<F4> moderate_vec4(uint32_t seed, size_t n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-8.0f, 8.0f);
  std::vector<F4> v(n);
  for (F4& x : v) x = F4(d(rng), d(rng), d(rng), d(rng));
  return v;
}

// A constant made outside any program: programs may read it.
const Float3 kUp(0.0f, 1.0f, 0.0f);

// ---- swizzles -------------------------------------------------------------------------------

TEST_P(VectorTest, SwizzleReads) {
  auto xs = as_vec4(sweep_floats(3, 1024));
  Program p = program("swizzle_reads", [] {
    Input<Float4> x("x");
    Output<Float3> zxy("zxy");
    Output<Float4> wzyx("wzyx");
    Output<Float4> xxyy("xxyy");
    Output<Float2> wy("wy");
    Output<Float2> nested("nested");
    Output<Float> z("z");
    zxy = x(2, 0, 1);
    wzyx = x(3, 2, 1, 0);
    xxyy = x(0, 0, 1, 1);
    wy = Float2(x.w(), x[1]);
    nested = x(3, 2, 1, 0)(1, 0);  // (z, w)
    z = x.z();
  });
  auto [zxy, wzyx, xxyy, wy, nested, z] = run<Float3, Float4, Float4, Float2, Float2, Float>(p, xs);
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(zxy, map(xs, [](F4 v) { return F3(v.z, v.x, v.y); }), d)) << "x(2, 0, 1)";
  EXPECT_TRUE(bits_equal(wzyx, map(xs, [](F4 v) { return F4(v.w, v.z, v.y, v.x); }), d))
      << "x(3, 2, 1, 0)";
  EXPECT_TRUE(bits_equal(xxyy, map(xs, [](F4 v) { return F4(v.x, v.x, v.y, v.y); }), d))
      << "x(0, 0, 1, 1)";
  EXPECT_TRUE(bits_equal(wy, map(xs, [](F4 v) { return F2(v.w, v.y); }), d)) << "(x.w, x[1])";
  EXPECT_TRUE(bits_equal(nested, map(xs, [](F4 v) { return F2(v.z, v.w); }), d))
      << "x(3, 2, 1, 0)(1, 0)";
  EXPECT_TRUE(bits_equal(z, map(xs, [](F4 v) { return v.z; }), d)) << "x.z()";
}

// Reordering swizzles as operands of an operation (not just copied).
TEST_P(VectorTest, SwizzledOperands) {
  auto xs = moderate_vec4(5, 512);
  auto ys = moderate_vec4(6, 512);
  Program p = program("swizzled_operands", [] {
    Input<Float4> x("x");
    Input<Float4> y("y");
    Output<Float4> o("o");
    Output<Float2> neg("neg");
    o = x(3, 1, 2, 0) * y(1, 0, 0, 2) - x.w();
    neg = -x(1, 0);
  });
  auto [o, neg] = run<Float4, Float2>(p, xs, ys);
  Describe d = describe_inputs(xs, ys);
  EXPECT_TRUE(bits_equal(o,
                         map(xs, ys,
                             [](F4 x, F4 y) {
                               return F4(x.w * y.y - x.w, x.y * y.x - x.w, x.z * y.x - x.w,
                                         x.x * y.z - x.w);
                             }),
                         d));
  EXPECT_TRUE(bits_equal(neg, map(xs, [](F4 x) { return F2(-x.y, -x.x); }), d)) << "-x(1, 0)";
}

TEST_P(VectorTest, WriteMasks) {
  auto xs = moderate_vec4(7, 512);
  Program p = program("write_masks", [] {
    Input<Float4> x("x");
    Output<Float4> o("o");
    Float4 v = x;
    v(1, 3) = Float2(10.0f, 20.0f);  // (x, 10, z, 20)
    v.x() = x.w();                   // (w, 10, z, 20)
    v(2, 0) = v(0, 2);               // swap x and z: (z, 10, w, 20)
    v.w() += 1.0f;                   // (z, 10, w, 21)
    v(1, 2) *= 2.0f;                 // (z, 20, 2w, 21)
    v(3, 0) = 5.0f;                  // host scalar to two components: (5, 20, 2w, 5)
    v.y() = v.y() - x.y();           // (5, 20 - y, 2w, 5)
    o = v;
  });
  auto o = run<Float4>(p, xs);
  EXPECT_TRUE(bits_equal(o, map(xs, [](F4 x) { return F4(5.0f, 20.0f - x.y, x.w * 2.0f, 5.0f); }),
                         describe_inputs(xs)));
}

// A swizzle of v assigned to v (or to a mask of v) reads every component before writing any.
TEST_P(VectorTest, AliasedSwizzleAssignment) {
  auto xs = moderate_vec4(8, 512);
  Program p = program("aliased", [] {
    Input<Float4> x("x");
    Output<Float4> a("a");
    Output<Float3> b("b");
    Output<Float4> c("c");
    Float4 v = x;
    v = v(1, 0, 3, 2);  // whole vector
    a = v;
    Float3 u = x(0, 1, 2);
    u = u(1, 2, 0);  // rotate
    b = u;
    Float4 w = x;
    w(0, 1, 2) = w(2, 0, 1);  // mask and source overlap
    w(3, 1) = w(1, 3);        // swap through a mask
    c = w;
  });
  auto [a, b, c] = run<Float4, Float3, Float4>(p, xs);
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(a, map(xs, [](F4 x) { return F4(x.y, x.x, x.w, x.z); }), d))
      << "v = v(1, 0, 3, 2)";
  EXPECT_TRUE(bits_equal(b, map(xs, [](F4 x) { return F3(x.y, x.z, x.x); }), d))
      << "u = u(1, 2, 0)";
  EXPECT_TRUE(bits_equal(c,
                         map(xs,
                             [](F4 x) {
                               F4 w(x.z, x.x, x.y, x.w);       // w.xyz = w.zxy
                               return F4(w.x, w.w, w.z, w.y);  // w.wy = w.yw
                             }),
                         d))
      << "w(0, 1, 2) = w(2, 0, 1); w(3, 1) = w(1, 3)";
}

// An output written through a mask: the other components keep the stream's old value.
TEST_P(VectorTest, MaskedOutputKeepsOtherComponents) {
  auto xs = moderate_vec4(9, 300);
  Program p = program("masked_output", [] {
    Input<Float4> x("x");
    Output<Float4> o("o");
    o(2, 0) = x(0, 1);
  });
  Kernel k = compile(p);
  Stream<Float4> in(xs), out(static_cast<int64_t>(xs.size()));
  out.fill(F4(-1.0f, -2.0f, -3.0f, -4.0f));
  k.inputs(in).outputs(out);
  EXPECT_EQ(k.execute(), static_cast<int64_t>(xs.size()));
  EXPECT_TRUE(bits_equal(out.download(), map(xs, [](F4 x) { return F4(x.y, -2.0f, x.x, -4.0f); }),
                         describe_inputs(xs)));
}

TEST_P(VectorTest, IntSwizzlesAndMasks) {
  auto xs = as_vec4(sweep_ints(4, 512));
  Program p = program("int_swizzles", [] {
    Input<Int4> x("x");
    Output<Int4> o("o");
    Output<Int3> r("r");
    Int4 v = x(3, 3, 0, 1);
    v(0, 2) = Int2(7, -9);
    v.w() += x.z();
    o = v;
    r = x(2, 1, 0) ^ x.w();
  });
  auto [o, r] = run<Int4, Int3>(p, xs);
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(o,
                         map(xs,
                             [](I4 x) {
                               return I4(7, x.w, -9,
                                         static_cast<int32_t>(static_cast<uint32_t>(x.y) +
                                                              static_cast<uint32_t>(x.z)));
                             }),
                         d));
  EXPECT_TRUE(
      bits_equal(r, map(xs, [](I4 x) { return glm::ivec3(x.z ^ x.w, x.y ^ x.w, x.x ^ x.w); }), d));
}

// ---- constructors ---------------------------------------------------------------------------

TEST_P(VectorTest, Constructors) {
  auto xs = as_vec4(sweep_floats(12, 512));
  Program p = program("constructors", [] {
    Input<Float4> x("x");
    Output<Float4> a("a");
    Output<Float3> b("b");
    Output<Float4> c("c");
    Output<Float3> d("d");
    Output<Float2> e("e");
    Output<Float4> f("f");
    a = Float4(x.x(), 1.0f, x(1, 2));                    // scalar, host, 2-vector
    b = Float3(Float2(x.w(), 2.0f), x.y());              // nested
    c = Float4(glm::vec4(1.0f, -0.0f, 3.5f, 4.0f)) + x;  // from a host vector
    d = Float3(2.5f) * x.z();                            // explicit broadcast
    e = Float2(x.z(), -0.0f);
    f = Float4(kUp, x.x());  // a constant made outside the program
  });
  auto [a, b, c, d, e, f] = run<Float4, Float3, Float4, Float3, Float2, Float4>(p, xs);
  Describe dx = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(a, map(xs, [](F4 x) { return F4(x.x, 1.0f, x.y, x.z); }), dx));
  EXPECT_TRUE(bits_equal(b, map(xs, [](F4 x) { return F3(x.w, 2.0f, x.y); }), dx));
  EXPECT_TRUE(bits_equal(c, map(xs, [](F4 x) { return F4(1.0f, -0.0f, 3.5f, 4.0f) + x; }), dx));
  EXPECT_TRUE(bits_equal(d, map(xs, [](F4 x) { return F3(2.5f * x.z); }), dx));
  EXPECT_TRUE(bits_equal(e, map(xs, [](F4 x) { return F2(x.z, -0.0f); }), dx));
  EXPECT_TRUE(bits_equal(f, map(xs, [](F4 x) { return F4(0.0f, 1.0f, 0.0f, x.x); }), dx));
}

TEST_P(VectorTest, IntConstructors) {
  auto xs = sweep_ints(13, 512);
  Program p = program("int_constructors", [] {
    Input<Int> i("i");
    Output<Int4> a("a");
    Output<Int2> b("b");
    a = Int4(i, 7, -i, Int(-2147483647 - 1));
    b = Int2(3) * i;
  });
  auto [a, b] = run<Int4, Int2>(p, xs);
  auto neg = [](int32_t v) { return static_cast<int32_t>(0u - static_cast<uint32_t>(v)); };
  auto mul = [](int32_t x, int32_t y) {
    return static_cast<int32_t>(static_cast<uint32_t>(x) * static_cast<uint32_t>(y));
  };
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(
      a, map(xs, [&](int32_t i) { return I4(i, 7, neg(i), std::numeric_limits<int32_t>::min()); }),
      d));
  EXPECT_TRUE(bits_equal(b, map(xs, [&](int32_t i) { return glm::ivec2(mul(3, i)); }), d));
}

// ---- geometric functions (defined by formula, so exact) -------------------------------------

float dot3(F3 a, F3 b) {
  float s = a.x * b.x;
  s = s + a.y * b.y;
  return s + a.z * b.z;
}
float dot4(F4 a, F4 b) {
  float s = a.x * b.x;
  s = s + a.y * b.y;
  s = s + a.z * b.z;
  return s + a.w * b.w;
}
F3 ref_normalize(F3 v) {
  float l = std::sqrt(dot3(v, v));
  return F3(v.x / l, v.y / l, v.z / l);
}

TEST_P(VectorTest, DotCrossLength) {
  // Moderate values plus hard ones (overflow, NaN, signed zeros) in some components.
  auto as = moderate_vec4(20, 1024);
  auto bs = moderate_vec4(21, 1024);
  auto hard = as_vec4(sweep_floats(22, 1024));
  for (size_t i = 0; i < as.size(); i += 3) as[i] = hard[i % hard.size()];
  Program p = program("geometry", [] {
    Input<Float4> a("a");
    Input<Float4> b("b");
    Output<Float> d2("d2");
    Output<Float> d3("d3");
    Output<Float> d4("d4");
    Output<Float3> cr("cross");
    Output<Float> len("length");
    Output<Float> dist("distance");
    d2 = dot(a(0, 1), b(0, 1));
    d3 = dot(a(0, 1, 2), b(0, 1, 2));
    d4 = dot(a, b);
    cr = cross(a(0, 1, 2), b(0, 1, 2));
    len = length(a);
    dist = distance(a(0, 1, 2), b(0, 1, 2));
  });
  auto [d2, d3, d4, cr, len, dist] = run<Float, Float, Float, Float3, Float, Float>(p, as, bs);
  Describe d = describe_inputs(as, bs);
  EXPECT_TRUE(bits_equal(d2,
                         map(as, bs,
                             [](F4 a, F4 b) {
                               float s = a.x * b.x;
                               return s + a.y * b.y;
                             }),
                         d))
      << "dot 2";
  EXPECT_TRUE(bits_equal(d3, map(as, bs, [](F4 a, F4 b) { return dot3(F3(a), F3(b)); }), d))
      << "dot 3";
  EXPECT_TRUE(bits_equal(d4, map(as, bs, dot4), d)) << "dot 4";
  EXPECT_TRUE(bits_equal(cr,
                         map(as, bs,
                             [](F4 a, F4 b) {
                               return F3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z,
                                         a.x * b.y - a.y * b.x);
                             }),
                         d))
      << "cross";
  EXPECT_TRUE(bits_equal(len, map(as, [](F4 a) { return std::sqrt(dot4(a, a)); }), d)) << "length";
  EXPECT_TRUE(bits_equal(dist,
                         map(as, bs,
                             [](F4 a, F4 b) {
                               F3 v = F3(a) - F3(b);
                               return std::sqrt(dot3(v, v));
                             }),
                         d))
      << "distance";
}

TEST_P(VectorTest, NormalizeReflectRefract) {
  auto is = moderate_vec4(30, 1024);
  auto ns = moderate_vec4(31, 1024);
  is[0] = F4(0.0f);  // normalize of a zero vector: NaN
  Program p = program("shading", [] {
    Input<Float4> i("i");
    Input<Float4> n("n");
    Output<Float3> nrm("normalize");
    Output<Float3> refl("reflect");
    Output<Float3> refr("refract");
    Float3 nn = normalize(n(0, 1, 2));
    nrm = normalize(i(0, 1, 2));
    refl = reflect(i(0, 1, 2), nn);
    refr = refract(normalize(i(0, 1, 2)), nn, abs(n.w()) * 0.25f);
  });
  auto [nrm, refl, refr] = run<Float3, Float3, Float3>(p, is, ns);
  auto ref_reflect = [](F3 i, F3 n) {
    float k = 2.0f * dot3(n, i);
    return F3(i.x - k * n.x, i.y - k * n.y, i.z - k * n.z);
  };
  auto ref_refract = [](F3 i, F3 n, float eta) {
    float d = dot3(n, i);
    float k = 1.0f - eta * eta * (1.0f - d * d);
    float s = eta * d + std::sqrt(k < 0.0f ? 0.0f : k);
    F3 r(eta * i.x - s * n.x, eta * i.y - s * n.y, eta * i.z - s * n.z);
    return k < 0.0f ? F3(0.0f) : r;
  };
  Describe d = describe_inputs(is, ns);
  EXPECT_TRUE(bits_equal(nrm, map(is, [](F4 i) { return ref_normalize(F3(i)); }), d));
  EXPECT_TRUE(bits_equal(
      refl, map(is, ns, [&](F4 i, F4 n) { return ref_reflect(F3(i), ref_normalize(F3(n))); }), d));
  EXPECT_TRUE(bits_equal(refr,
                         map(is, ns,
                             [&](F4 i, F4 n) {
                               return ref_refract(ref_normalize(F3(i)), ref_normalize(F3(n)),
                                                  std::fabs(n.w) * 0.25f);
                             }),
                         d));
}

TEST_P(VectorTest, ClampLerpAnyAll) {
  auto xs = as_vec4(sweep_floats(40, 1024));
  auto ys = moderate_vec4(41, xs.size());
  Program p = program("clamp_lerp", [] {
    Input<Float4> x("x");
    Input<Float4> y("y");
    Output<Float4> c1("clamp_host");
    Output<Float4> c2("clamp_vec");
    Output<Float4> l1("lerp_scalar");
    Output<Float4> l2("lerp_vec");
    Output<Int> reduce("reduce");
    c1 = clamp(x, -1.0f, 2.0f);
    c2 = clamp(x, y, y + 1.0f);
    l1 = lerp(x, y, 0.25f);
    l2 = lerp(y, x, y(1, 2, 3, 3));
    Bool4 b = x < y;
    reduce = select(any(b), Int(1), Int(0)) + select(all(b), Int(2), Int(0)) +
             select(any(x(0, 1) > 0.0f), Int(4), Int(0)) +
             select(all(x(1, 2, 3) > 0.0f), Int(8), Int(0));
  });
  auto [c1, c2, l1, l2, reduce] = run<Float4, Float4, Float4, Float4, Int>(p, xs, ys);
  auto cl = [](float v, float lo, float hi) {
    float m = v < lo ? lo : v;  // max(v, lo)
    return hi < m ? hi : m;     // min(m, hi)
  };
  auto le = [](float a, float b, float t) {
    float d = b - a;
    float m = d * t;
    return a + m;
  };
  Describe d = describe_inputs(xs, ys);
  EXPECT_TRUE(bits_equal(
      c1,
      map(xs,
          [&](F4 x) { return F4(cl(x.x, -1, 2), cl(x.y, -1, 2), cl(x.z, -1, 2), cl(x.w, -1, 2)); }),
      d));
  EXPECT_TRUE(bits_equal(c2,
                         map(xs, ys,
                             [&](F4 x, F4 y) {
                               F4 h = y + 1.0f;
                               return F4(cl(x.x, y.x, h.x), cl(x.y, y.y, h.y), cl(x.z, y.z, h.z),
                                         cl(x.w, y.w, h.w));
                             }),
                         d));
  EXPECT_TRUE(bits_equal(l1,
                         map(xs, ys,
                             [&](F4 x, F4 y) {
                               return F4(le(x.x, y.x, 0.25f), le(x.y, y.y, 0.25f),
                                         le(x.z, y.z, 0.25f), le(x.w, y.w, 0.25f));
                             }),
                         d));
  EXPECT_TRUE(bits_equal(l2,
                         map(xs, ys,
                             [&](F4 x, F4 y) {
                               return F4(le(y.x, x.x, y.y), le(y.y, x.y, y.z), le(y.z, x.z, y.w),
                                         le(y.w, x.w, y.w));
                             }),
                         d));
  EXPECT_TRUE(bits_equal(reduce,
                         map(xs, ys,
                             [](F4 x, F4 y) {
                               bool b[4] = {x.x < y.x, x.y < y.y, x.z < y.z, x.w < y.w};
                               bool any = b[0] || b[1] || b[2] || b[3];
                               bool all = b[0] && b[1] && b[2] && b[3];
                               bool any2 = x.x > 0.0f || x.y > 0.0f;
                               bool all3 = x.y > 0.0f && x.z > 0.0f && x.w > 0.0f;
                               return int32_t{any} + 2 * int32_t{all} + 4 * int32_t{any2} +
                                      8 * int32_t{all3};
                             }),
                         d));
}

RILL_BACKEND_TEST_SUITE(VectorTest);

}  // namespace
}  // namespace rill::testing
