// Gather boundary modes (Boundary: clamp, wrap, mirror, constant) on every backend: 1D, 2D and
// 3D arrays read at indices inside, just outside and far outside (INT32_MIN, INT32_MAX),
// compared bit for bit with a host reference written independently of Rill's helpers and
// with the reference interpreter.
#include <rill/Reference.h>

#include "BackendTest.h"

namespace rill::testing {
namespace {

using F3 = glm::vec3;
using I2 = glm::ivec2;

class GatherBoundaryTest : public BackendTest {};

// The host reference of each mode, in 64-bit arithmetic with the plain textbook formulas
// (a double period for mirror), not the ~i mapping the backends use (tests/dsl/ir/
// BoundaryTest.cpp holds ir::boundary_index to the same formulas).
int64_t wrap_ref(int64_t i, int64_t n) {
  return ((i % n) + n) % n;
}
int64_t mirror_ref(int64_t i, int64_t n) {
  const int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);
  return m < n ? m : 2 * n - 1 - m;
}
int64_t clamp_ref(int64_t i, int64_t n) {
  return std::clamp<int64_t>(i, 0, n - 1);
}
// The index read in a dimension of n, or -1 for outside (Constant).
int64_t index_ref(Boundary b, int32_t i, int64_t n) {
  switch (b) {
    case Boundary::Clamp:
      return clamp_ref(i, n);
    case Boundary::Wrap:
      return wrap_ref(i, n);
    case Boundary::Mirror:
      return mirror_ref(i, n);
    case Boundary::Constant:
      return i >= 0 && i < n ? i : -1;
  }
  return -1;
}

// Indices around every edge of dimensions up to 7, and far outside.
std::vector<int32_t> edge_indices() {
  const int32_t lo = std::numeric_limits<int32_t>::min(), hi = std::numeric_limits<int32_t>::max();
  return {lo, lo + 1, lo + 2, -1000001, -1000000, -29, -15, -14, -13,     -8,     -7,     -6,
          -5, -4,     -3,     -2,       -1,       0,   1,   2,   3,       4,      5,      6,
          7,  8,      9,      10,       13,       14,  15,  27,  1000001, hi - 2, hi - 1, hi};
}

const Boundary kModes[] = {Boundary::Clamp, Boundary::Wrap, Boundary::Mirror, Boundary::Constant};

// Every mode on a 1D Float, a 2D Float3 and a 3D Int2 array (the vector element types take the
// simd backend's whole-element loads).
TEST_P(GatherBoundaryTest, EveryModeIn1D2DAnd3DAgainstTheHostAndTheInterpreter) {
  const int64_t n1 = 7, nx = 5, ny = 3, nx3 = 3, ny3 = 4, nz3 = 2;
  std::vector<float> a1(n1);
  for (int64_t i = 0; i < n1; ++i) a1[static_cast<size_t>(i)] = 0.5f + static_cast<float>(i);
  std::vector<F3> a2(static_cast<size_t>(nx * ny));
  for (int64_t y = 0; y < ny; ++y)
    for (int64_t x = 0; x < nx; ++x)
      a2[static_cast<size_t>(x + nx * y)] =
          F3(static_cast<float>(x), static_cast<float>(10 * y), -1.0f);
  std::vector<I2> a3(static_cast<size_t>(nx3 * ny3 * nz3));
  for (int64_t z = 0; z < nz3; ++z)
    for (int64_t y = 0; y < ny3; ++y)
      for (int64_t x = 0; x < nx3; ++x)
        a3[static_cast<size_t>(x + nx3 * (y + ny3 * z))] =
            I2(static_cast<int>(x + 10 * y + 100 * z), 7);

  // Every pair of edge indices for i, j; k cycles through them too.
  const std::vector<int32_t> idx = edge_indices();
  std::vector<int32_t> is, js, ks;
  for (size_t a = 0; a < idx.size(); ++a)
    for (size_t b = 0; b < idx.size(); ++b) {
      is.push_back(idx[a]);
      js.push_back(idx[b]);
      ks.push_back(idx[(a * 7 + b * 3) % idx.size()]);
    }
  const int64_t count = static_cast<int64_t>(is.size());

  const float border1 = -2.5f;
  const F3 border2(1.0f, std::numeric_limits<float>::infinity(), -0.0f);
  const I2 border3(-1, std::numeric_limits<int32_t>::min());
  for (Boundary mode : kModes) {
    SCOPED_TRACE(ir::boundary_name(mode));
    Array<Float> arr1(a1, "line");
    Array<Float3> arr2(nx, ny, a2, "plane");
    Array<Int2> arr3(nx3, ny3, nz3, a3, "volume");
    if (mode == Boundary::Constant) {
      arr1.boundary(mode, border1);
      arr2.boundary(mode, border2);
      arr3.boundary(mode, border3);
    } else {
      arr1.boundary(mode);
      arr2.boundary(mode);
      arr3.boundary(mode);
    }
    Program p = program("boundary", [&] {
      Input<Int> i("i");
      Input<Int> j("j");
      Input<Int> k("k");
      Output<Float> g1("g1");
      Output<Float3> g2("g2");
      Output<Int2> g3("g3");
      g1 = arr1[i];
      g2 = arr2(i, j);
      g3 = arr3(i, j, k);
    });
    auto [g1, g2, g3] = run<Float, Float3, Int2>(p, is, js, ks);

    std::vector<float> w1;
    std::vector<F3> w2;
    std::vector<I2> w3;
    for (size_t e = 0; e < is.size(); ++e) {
      const int64_t x1 = index_ref(mode, is[e], n1);
      w1.push_back(x1 < 0 ? border1 : a1[static_cast<size_t>(x1)]);
      const int64_t x2 = index_ref(mode, is[e], nx), y2 = index_ref(mode, js[e], ny);
      w2.push_back(x2 < 0 || y2 < 0 ? border2 : a2[static_cast<size_t>(x2 + nx * y2)]);
      const int64_t x3 = index_ref(mode, is[e], nx3), y3 = index_ref(mode, js[e], ny3),
                    z3 = index_ref(mode, ks[e], nz3);
      w3.push_back(x3 < 0 || y3 < 0 || z3 < 0
                       ? border3
                       : a3[static_cast<size_t>(x3 + nx3 * (y3 + ny3 * z3))]);
    }
    Describe d = describe_inputs(is, js, ks);
    EXPECT_TRUE(bits_equal(g1, w1, d));
    EXPECT_TRUE(bits_equal(g2, w2, d));
    EXPECT_TRUE(bits_equal(g3, w3, d));

    // The interpreter (the reference every strict kernel is held to) agrees.
    ir::InterpreterLaunch l = reference_launch(p);
    std::vector<uint32_t> o1(static_cast<size_t>(count)), o2(static_cast<size_t>(count * 3)),
        o3(static_cast<size_t>(count * 2));
    for (const auto* in : {&is, &js, &ks})
      l.inputs.push_back(reinterpret_cast<const uint32_t*>(in->data()));
    l.outputs = {o1.data(), o2.data(), o3.data()};
    l.count = count;
    l.width = count;
    ir::interpret(p.ir(), l);
    std::vector<float> i1(o1.size());
    std::memcpy(i1.data(), o1.data(), o1.size() * 4);
    std::vector<F3> i2(static_cast<size_t>(count));
    std::memcpy(i2.data(), o2.data(), o2.size() * 4);
    std::vector<I2> i3(static_cast<size_t>(count));
    std::memcpy(i3.data(), o3.data(), o3.size() * 4);
    EXPECT_TRUE(bits_equal(g1, i1, d));
    EXPECT_TRUE(bits_equal(g2, i2, d));
    EXPECT_TRUE(bits_equal(g3, i3, d));
  }
}

// One array read with two modes in one kernel (two Array objects sharing the data): two
// arrays of the program, bound to the same storage.
TEST_P(GatherBoundaryTest, TheSameDataReadWithTwoModesInOneKernel) {
  std::vector<int32_t> data = {10, 11, 12, 13};
  Array<Int> clamped(data, "t");
  Array<Int> wrapped = clamped;
  wrapped.boundary(Boundary::Wrap);
  Array<Int> outside = clamped;
  outside.boundary(Boundary::Constant, -1);
  Program p = program("two_modes", [&] {
    Input<Int> i("i");
    Output<Int3> y("y");
    y = Int3(clamped[i], wrapped[i], outside[i]);
  });
  EXPECT_EQ(p.ir().arrays.size(), 3u);
  std::vector<int32_t> is = {-5, -1, 0, 3, 4, 9};
  auto got = run<Int3>(p, is);
  std::vector<glm::ivec3> want = {{10, 13, -1}, {10, 13, -1}, {10, 10, 10},
                                  {13, 13, 13}, {13, 10, -1}, {13, 11, -1}};
  EXPECT_TRUE(bits_equal(got, want, describe_inputs(is)));
}

// A one-element array: every mode reads the element (or the border) at any index.
TEST_P(GatherBoundaryTest, OneElementArrays) {
  const std::vector<int32_t> is = edge_indices();
  for (Boundary mode : kModes) {
    SCOPED_TRACE(ir::boundary_name(mode));
    Array<Float> a(std::vector<float>{3.0f}, "one");
    a.boundary(mode);
    Program p = program("one", [&] {
      Input<Int> i("i");
      Output<Float> y("y");
      y = a[i];
    });
    auto got = run<Float>(p, is);
    EXPECT_TRUE(bits_equal(
        got, map(is, [&](int32_t i) { return mode == Boundary::Constant && i != 0 ? 0.0f : 3.0f; }),
        describe_inputs(is)));
  }
}

// Groups of 8 consecutive elements (the simd backend's lanes) whose indices are all the same,
// all the same but one, all different, the same index clamped from outside, and a short last
// group: with gather instructions, simd loads a shared index once and broadcasts it
// (rill_same_index), and every other group gathers; both must read each element's own value.
// Int, Float, Float3 and Int2 elements, against the host.
TEST_P(GatherBoundaryTest, LanesThatShareAnIndexReadTheirOwnElement) {
  const int32_t n = 11;
  std::vector<int32_t> ai(n);
  std::vector<float> af(n);
  std::vector<F3> a3(n);
  std::vector<I2> a2(n);
  for (int32_t e = 0; e < n; ++e) {
    const size_t u = static_cast<size_t>(e);
    ai[u] = 1000 + e;
    af[u] = 0.25f * static_cast<float>(e) - 1.0f;
    a3[u] = F3(static_cast<float>(e), -static_cast<float>(e), 0.5f + static_cast<float>(e));
    a2[u] = I2(e, -7 * e);
  }
  std::vector<int32_t> is;
  auto group = [&](std::initializer_list<int32_t> g) { is.insert(is.end(), g); };
  group({4, 4, 4, 4, 4, 4, 4, 4});          // all the same
  group({2, 2, 2, 2, 2, 2, 2, 9});          // all but the last
  group({9, 2, 2, 2, 2, 2, 2, 2});          // all but the first
  group({0, 1, 2, 3, 4, 5, 6, 7});          // all different
  group({-3, -3, -3, -3, -3, -3, -3, -3});  // the same, clamped to 0
  group({40, 40, 40, 40, 40, 40, 40, 40});  // the same, clamped to n - 1
  group({-1, 0, -1, 0, -1, 0, -1, 0});      // different indices, one element
  group({10, 10, 10, 10, 10, 10, 10, 10});  // the last element
  group({6, 6, 6});                         // a short group (spare lanes repeat 6)
  Array<Int> arr_i(ai, "ints");
  Array<Float> arr_f(af, "floats");
  Array<Float3> arr_3(a3, "vec3s");
  Array<Int2> arr_2(a2, "ivec2s");
  Program p = program("shared_index", [&] {
    Input<Int> i("i");
    Output<Int> gi("gi");
    Output<Float> gf("gf");
    Output<Float3> g3("g3");
    Output<Int2> g2("g2");
    gi = arr_i[i];
    gf = arr_f[i];
    g3 = arr_3[i];
    g2 = arr_2[i];
  });
  auto [gi, gf, g3, g2] = run<Int, Float, Float3, Int2>(p, is);
  std::vector<int32_t> wi;
  std::vector<float> wf;
  std::vector<F3> w3;
  std::vector<I2> w2;
  for (int32_t i : is) {
    const size_t k = static_cast<size_t>(clamp_ref(i, n));
    wi.push_back(ai[k]);
    wf.push_back(af[k]);
    w3.push_back(a3[k]);
    w2.push_back(a2[k]);
  }
  Describe d = describe_inputs(is);
  EXPECT_TRUE(bits_equal(gi, wi, d));
  EXPECT_TRUE(bits_equal(gf, wf, d));
  EXPECT_TRUE(bits_equal(g3, w3, d));
  EXPECT_TRUE(bits_equal(g2, w2, d));
}

RILL_BACKEND_TEST_SUITE(GatherBoundaryTest);

}  // namespace
}  // namespace rill::testing
