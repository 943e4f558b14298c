// Array boundary modes in the IR (ir::Boundary): the index arithmetic, capture, printing,
// hashing and verification. Backends are checked against these in
// tests/backends/GatherBoundaryTest.cpp.
#include <algorithm>

#include "TestUtil.h"

namespace rill {
namespace {

// Textbook formulas in 64 bits (a double period for mirror): independent of the ~i mapping
// ir::boundary_index and the backends' helpers use.
int64_t wrap_ref(int64_t i, int64_t n) {
  return ((i % n) + n) % n;
}
int64_t mirror_ref(int64_t i, int64_t n) {
  const int64_t m = ((i % (2 * n)) + 2 * n) % (2 * n);
  return m < n ? m : 2 * n - 1 - m;
}

TEST(Boundary, IndexArithmeticMatchesTheTextbookFormulasFarOutside) {
  const int32_t lo = std::numeric_limits<int32_t>::min(), hi = std::numeric_limits<int32_t>::max();
  std::vector<int32_t> is = {lo, lo + 1, -1000001, -15, -14, -8, -7, -6,   -2,     -1,
                             0,  1,      5,        6,   7,   13, 14, 1000, hi - 1, hi};
  for (int64_t n : {1LL, 2LL, 3LL, 7LL, 1000LL, 2147483647LL, 3000000000LL})
    for (int32_t i : is) {
      EXPECT_EQ(ir::boundary_index(ir::Boundary::Wrap, i, n), wrap_ref(i, n))
          << "i=" << i << " n=" << n;
      EXPECT_EQ(ir::boundary_index(ir::Boundary::Mirror, i, n), mirror_ref(i, n))
          << "i=" << i << " n=" << n;
      EXPECT_EQ(ir::boundary_index(ir::Boundary::Clamp, i, n), std::clamp<int64_t>(i, 0, n - 1));
      EXPECT_EQ(ir::index_inside(i, n), i >= 0 && i < n);
    }
  // The edges exactly as documented: mirror repeats the edge element (GL's MIRRORED_REPEAT),
  // wrap is periodic.
  std::vector<int64_t> mirrored, wrapped;
  for (int32_t i = -7; i <= 10; ++i) {
    mirrored.push_back(ir::boundary_index(ir::Boundary::Mirror, i, 4));
    wrapped.push_back(ir::boundary_index(ir::Boundary::Wrap, i, 4));
  }
  EXPECT_EQ(mirrored, (std::vector<int64_t>{1, 2, 3, 3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1, 2}));
  EXPECT_EQ(wrapped, (std::vector<int64_t>{1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2}));
}

TEST(Boundary, ArraysDefaultToClampAndKeepTheirMode) {
  Array<Float> a(4, "a");
  EXPECT_EQ(a.boundary(), Boundary::Clamp);
  a.boundary(Boundary::Constant, 2.5f);
  EXPECT_EQ(a.boundary(), Boundary::Constant);
  EXPECT_EQ(a.outside(), 2.5f);
  Array<Float> b = a;  // a copy shares the data and may read it with another mode
  b.boundary(Boundary::Mirror);
  EXPECT_EQ(a.boundary(), Boundary::Constant);
  EXPECT_EQ(b.boundary(), Boundary::Mirror);
  EXPECT_HAS(
      test::error_of([&] { a.boundary(Boundary::Wrap, 1.0f); }),
      "only Boundary::Constant takes a value for outside the array (the mode given is wrap)");
}

TEST(Boundary, ModesArePrintedAndCapturedPerArray) {
  Array<Float> clamp(4, "c");
  Array<Float2> wrap(4, 3, "w");
  wrap.boundary(Boundary::Wrap);
  Array<Int> mirror(2, 2, 2, "m");
  mirror.boundary(Boundary::Mirror);
  Array<Float3> border(5, "b");
  border.boundary(Boundary::Constant, glm::vec3(1.0f, -0.0f, 0.5f));
  Array<Float> zero = clamp;
  zero.boundary(Boundary::Constant);
  Program p = program("modes", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    // One statement each: the order of operands of + is unspecified in C++.
    Float s = clamp[i];
    s += wrap(i, i).y();
    s += to_float(mirror(i, i, i));
    s += border[i].z();
    s += zero[i];
    s += clamp[i + 1];
    y = s;
  });
  const std::string text = p.print();
  EXPECT_LINE(text, "array1d float a0:c");  // clamp, the default, prints nothing
  EXPECT_LINE(text, "array2d float2 a1:w wrap");
  EXPECT_LINE(text, "array3d int a2:m mirror");
  EXPECT_LINE(text, "array1d float3 a3:b constant(float3(1.0, -0.0, 0.5))");
  EXPECT_LINE(text, "array1d float a4:c constant(0.0)");
  // Both clamp gathers share one array; the constant-mode copy of the same data is another.
  ASSERT_EQ(p.ir().arrays.size(), 5u);
  EXPECT_EQ(p.captured().arrays[0], p.captured().arrays[4]);
  EXPECT_TRUE(ir::verify(p.ir()).empty());
}

Program one_gather(Array<Float>& a) {
  return program("g", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = a[i];
  });
}

TEST(Boundary, TheModeAndTheBorderValueChangeTheHash) {
  Array<Float> a(4, "a");
  const uint64_t clamp = one_gather(a).hash();
  EXPECT_EQ(one_gather(a).hash(), clamp);
  a.boundary(Boundary::Wrap);
  const uint64_t wrap = one_gather(a).hash();
  a.boundary(Boundary::Mirror);
  const uint64_t mirror = one_gather(a).hash();
  a.boundary(Boundary::Constant, 0.0f);
  const uint64_t zero = one_gather(a).hash();
  a.boundary(Boundary::Constant, -0.0f);
  const uint64_t minus_zero = one_gather(a).hash();
  a.boundary(Boundary::Clamp);
  EXPECT_EQ(one_gather(a).hash(), clamp);
  std::vector<uint64_t> all = {clamp, wrap, mirror, zero, minus_zero};
  std::sort(all.begin(), all.end());
  EXPECT_EQ(std::unique(all.begin(), all.end()), all.end()) << "two modes hash alike";
}

TEST(Boundary, TheVerifierChecksTheModeAndTheBorderType) {
  Array<Float2> a(4, "a");
  a.boundary(Boundary::Constant, glm::vec2(1.0f, 2.0f));
  Program p = program("v", [&] {
    Input<Int> i("i");
    Output<Float2> y("y");
    y = a[i];
  });
  ir::Function f = p.ir();
  EXPECT_TRUE(ir::verify(f).empty());
  f.arrays[0].border = ir::Constant::of_float(1.0f);
  auto problems = ir::verify(f);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_HAS(problems[0], "array 'a' of float2 has a constant boundary of type float");
  f = p.ir();
  f.arrays[0].boundary = static_cast<ir::Boundary>(9);
  problems = ir::verify(f);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_HAS(problems[0], "array 'a' has an unknown boundary mode 9");
}

}  // namespace
}  // namespace rill
