// The debug mode (CompileOptions::debug) on every backend: an out-of-range gather and a NaN
// or infinity are reported with the lowest failing element, its index and array (or the
// statement), and a kernel that stays in range computes the same bits with debug on.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class DebugModeTest : public BackendTest {
 protected:
  Kernel compile_debug(const Program& p, bool nonfinite = false) {
    CompileOptions o;
    o.debug = true;
    o.debug_nonfinite = nonfinite;
    return rill::compile(p, GetParam(), o);
  }
  // The message of the Error a launch throws ("" if none).
  template <class... Outs, class... Hs>
  std::string launch_error(Kernel& k, int64_t n, const std::vector<Hs>&... ins) {
    try {
      run_kernel<Outs...>(k, n, ins...);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
};

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The lowest element that read outside is reported, whichever array it read; elements read
// outside below zero and past the end alike.
TEST_P(DebugModeTest, AnOutOfRangeGatherNamesElementIndexAndArray) {
  Array<Float> a(std::vector<float>(10, 1.0f), "table");
  Array<Int> b(std::vector<int32_t>{3, 1, 4, 1, 5}, "digits");
  Program p = program("reads", [&] {
    Input<Int> i("i");
    Input<Int> j("j");
    Output<Float> y("y");
    y = a[i] + to_float(b[j]);
  });
  //                          e0 e1 e2  e3 e4 e5  e6
  std::vector<int32_t> is = {0, 9, 3, 10, 2, -1, 0};
  std::vector<int32_t> js = {0, 4, 5, 0, 1, 0, -7};
  Kernel k = compile_debug(p);
  std::string what = launch_error<Float>(k, 7, is, js);
  EXPECT_TRUE(contains(what,
                       "kernel 'reads' (debug mode): element 2 read array 'digits' at "
                       "index 5, outside its 5 elements"))
      << what;
  EXPECT_TRUE(contains(what, "4 elements read outside an array in all")) << what;
  EXPECT_TRUE(contains(what, "gather")) << what;
  // The gather is made by an operator: the nearest line the capture recorded, in this file.
  EXPECT_TRUE(contains(what, "tests/backends/DebugModeTest.cpp:")) << what;

  // In range everywhere: no report, and the same bits as without the debug mode.
  std::vector<int32_t> in_i = {0, 9, 3, 4, 2, 1, 0}, in_j = {0, 4, 3, 0, 1, 2, 4};
  Kernel plain = compile(p);
  std::vector<float> want = run_kernel<Float>(plain, 7, in_i, in_j);
  std::vector<float> got = run_kernel<Float>(k, 7, in_i, in_j);
  EXPECT_TRUE(bits_equal(got, want));
}

// In one element, the first gather that ran is the one reported (b's index comes from a).
TEST_P(DebugModeTest, WithinAnElementTheFirstGatherInProgramOrderIsReported) {
  Array<Int> a(std::vector<int32_t>{7, 8}, "first");
  Array<Int> b(std::vector<int32_t>{1, 2, 3}, "second");
  Program p = program("chain", [&] {
    Input<Int> i("i");
    Output<Int> y("y");
    y = b[a[i] + i];
  });
  Kernel k = compile_debug(p);
  // e0: a[0] = 7, b[7] outside; e1: a[5] outside (then b[8 + 5] outside too).
  std::string what = launch_error<Int>(k, 2, std::vector<int32_t>{0, 5});
  EXPECT_TRUE(contains(what, "element 0 read array 'second' at index 7, outside its 3 elements"))
      << what;
  what = launch_error<Int>(k, 2, std::vector<int32_t>{1, 5});  // e0: a[1] = 8, b[9]
  EXPECT_TRUE(contains(what, "element 0 read array 'second' at index 9")) << what;
  what = launch_error<Int>(k, 2, std::vector<int32_t>{-3, 0});
  EXPECT_TRUE(contains(what, "element 0 read array 'first' at index -3, outside its 2 elements"))
      << what;
}

// 2D arrays report both indices and both sizes; modes other than clamp read outside on
// purpose and are not checked.
TEST_P(DebugModeTest, TwoDimensionalIndicesAndUncheckedModes) {
  Array<Float> grid(4, 3, std::vector<float>(12, 0.5f), "grid");
  Array<Float> ring(std::vector<float>{1.0f, 2.0f, 3.0f}, "ring");
  ring.boundary(Boundary::Wrap);
  Program p = program("plane", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = grid(i, i - 2) + ring[i - 5];
  });
  Kernel k = compile_debug(p);
  std::string what = launch_error<Float>(k, 4, std::vector<int32_t>{2, 3, 4, 2});
  EXPECT_TRUE(contains(what,
                       "element 2 read array 'grid' at index (4, 2), outside its 4 x 3 "
                       "elements"))
      << what;
  EXPECT_FALSE(contains(what, "ring")) << what;
  // Elements 0 and 1 read grid(2, 0) and (3, 1) in range and ring at -3, -2 (wrapped): no report.
  EXPECT_EQ(launch_error<Float>(k, 2, std::vector<int32_t>{2, 3}), "");
}

// NaN and infinity checks name the element and the statement that produced the value.
TEST_P(DebugModeTest, NanAndInfinityNameTheStatementThatProducedThem) {
  Program p = program("roots", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float r = sqrt(x);
    y = r + 1.0f;
  });
  Kernel k = compile_debug(p, true);
  std::string what = launch_error<Float>(k, 5, std::vector<float>{4.0f, 1.0f, 0.0f, -1.0f, -4.0f});
  EXPECT_TRUE(contains(what, "element 3 produced a NaN")) << what;
  EXPECT_TRUE(contains(what, "sqrt")) << what;
  EXPECT_TRUE(contains(what, "2 elements produced a NaN or infinity in all")) << what;

  Program q = program("inverse", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = 1.0f / x;
  });
  Kernel kq = compile_debug(q, true);
  what = launch_error<Float>(kq, 3, std::vector<float>{2.0f, -0.0f, 0.0f});
  EXPECT_TRUE(contains(what, "element 1 produced an infinity -inf (bits 0xff800000)")) << what;
  // Without debug_nonfinite the same kernel reports nothing.
  Kernel quiet = compile_debug(q, false);
  EXPECT_EQ(launch_error<Float>(quiet, 3, std::vector<float>{2.0f, -0.0f, 0.0f}), "");
}

// Gathers, loops, branches and float math in range: every bit the same with debug on.
TEST_P(DebugModeTest, AnInRangeKernelComputesTheSameBitsWithDebugOn) {
  std::vector<float> data;
  for (int i = 0; i < 64; ++i) data.push_back(0.37f * static_cast<float>(i) - 5.0f);
  Array<Float> table(data, "table");
  Program p = program("mix", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> z("z");
    Float acc = x;
    Int i = 0;
    RILL_WHILE(i < 5) {
      Int at = to_int(abs(acc) * 3.0f) % 64;
      RILL_IF(acc > 0.0f) {
        acc = acc * 0.5f + table[at];
      }
      RILL_ELSE {
        acc = acc - table[63 - at] * 0.25f;
      }
      RILL_ENDIF;
      i += 1;
    }
    RILL_ENDWHILE;
    y = acc;
    z = to_int(acc * 100.0f);
  });
  std::vector<float> xs;
  for (int i = 0; i < 257; ++i) xs.push_back(static_cast<float>(i) * 0.731f - 90.0f);
  Kernel plain = compile(p);
  Kernel debug = compile_debug(p, true);
  auto [y0, z0] = run_kernel<Float, Int>(plain, 257, xs);
  auto [y1, z1] = run_kernel<Float, Int>(debug, 257, xs);
  EXPECT_TRUE(bits_equal(y1, y0));
  EXPECT_EQ(z1, z0);
}

// RILL_DEBUG=1 turns the mode on for a compile that did not ask for it.
TEST_P(DebugModeTest, TheEnvironmentTurnsItOn) {
  Array<Float> a(std::vector<float>{1.0f, 2.0f}, "pair");
  Program p = program("env", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = a[i];
  });
  ScopedEnv env("RILL_DEBUG", "1");
  Kernel k = compile(p);
  std::string what;
  try {
    run_kernel<Float>(k, 2, std::vector<int32_t>{0, 2});
  } catch (const Error& e) {
    what = e.what();
  }
  EXPECT_TRUE(contains(what, "element 1 read array 'pair' at index 2")) << what;
}

RILL_BACKEND_TEST_SUITE(DebugModeTest);

}  // namespace
}  // namespace rill::testing
