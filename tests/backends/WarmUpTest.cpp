// What compile() reports per stage on every backend, and its warm-up: the launch over no
// elements that makes PoCL and Mesa finish compiling inside compile() (Backend.h, warm_up).
#include "BackendTest.h"

namespace rill::testing {
namespace {

class WarmUpTest : public BackendTest {};

TEST_P(WarmUpTest, EveryStageThatRanIsTimed) {
  Uniform<Float> gain(3.0f, "gain");
  Program p = program("timed_" + backend_name(), [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * gain + 0.125f;
  });
  clear_kernel_cache();
  Kernel k = compile(p);
  const CompileInfo& i = k.info();
  EXPECT_GT(i.capture_ms, 0.0);
  EXPECT_GT(i.optimize_ms, 0.0);
  EXPECT_GT(i.codegen_ms, 0.0);
  EXPECT_GT(i.backend_compile_ms, 0.0);
  // cpu and simd defer nothing to the first launch; PoCL and Mesa do, unless the kernel
  // came from a disk cache of finished binaries. On llvmpipe a kernel that reads a stream is
  // not warmed up (its variant depends on the textures' sizes: glsl::warm_up_pays).
  const bool llvmpipe =
      rill::backend(backend_name()).description().find("llvmpipe") != std::string::npos;
  if (backend_name() == "opencl" || (backend_name() == "glsl" && !llvmpipe)) {
    EXPECT_GT(i.driver_finish_ms, 0.0);
  }
  EXPECT_GE(i.compile_ms, i.optimize_ms + i.codegen_ms + i.backend_compile_ms + i.driver_finish_ms);
  EXPECT_NE(i.origin, KernelOrigin::ProcessCache);
  EXPECT_NE(i.origin, KernelOrigin::DriverCache);  // no driver here says so (Kernel.h)

  Kernel hit = compile(p);
  EXPECT_EQ(hit.info().origin, KernelOrigin::ProcessCache);
  EXPECT_EQ(hit.info().compile_ms, 0.0);
}

// The warm-up ran with stand-ins of every kind of parameter; the kernel then computes the
// same as ever, unmasked and masked, with its real streams, uniforms and arrays.
TEST_P(WarmUpTest, LeavesTheKernelComputingCorrectly) {
  Uniform<Int> shift(2, "shift");
  Array<Float> table(std::vector<float>{0.5f, 1.5f, 2.5f, 3.5f}, "table");
  Program p = program("warmed", [&] {
    Input<Float> x("x");
    Input<Int3> v("v");
    Output<Float> y("y");
    Output<Int> w("w");
    y = x + table[v.x()];
    w = v.y() + shift * v.z();
  });
  Kernel k = compile(p);
  const int n = 300;
  std::vector<float> xs(n);
  std::vector<glm::ivec3> vs(n);
  for (int i = 0; i < n; ++i) {
    xs[i] = 0.25f * static_cast<float>(i);
    vs[i] = glm::ivec3(i % 4, i, i % 7);
  }
  auto [ys, ws] = run_kernel<Float, Int>(k, n, xs, vs);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(ys[i], xs[i] + 0.5f + static_cast<float>(i % 4)) << i;
    ASSERT_EQ(ws[i], i + 2 * (i % 7)) << i;
  }
  EXPECT_EQ(last_written_, n);

  Stream<Int> state(n);
  std::vector<int32_t> states(n);
  for (int i = 0; i < n; ++i) states[i] = i % 3;
  state.upload(states);
  Stream<Float> xst(xs), yst(n);
  Stream<Int3> vst(vs);
  Stream<Int> wst(n);
  k.inputs(xst, vst).outputs(yst, wst);
  EXPECT_EQ(k.execute(where(state, 1)), n / 3);
  std::vector<float> masked = yst.download();
  for (int i = 0; i < n; ++i)
    ASSERT_EQ(masked[i], i % 3 == 1 ? xs[i] + 0.5f + static_cast<float>(i % 4) : 0.0f) << i;
}

// The warm-up runs no element: a loop that never ends on a zero input (what stand-in data
// holds) does not hang compile().
TEST_P(WarmUpTest, RunsNoElement) {
  Program p = program("doubles_until_one", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float v = x;
    RILL_WHILE(v < 1.0f) {
      v = v * 2.0f;
    }
    RILL_ENDWHILE;
    y = v;
  });
  Kernel k = compile(p);
  std::vector<float> got = run_kernel<Float>(k, 3, std::vector<float>{0.25f, 0.3f, 4.0f});
  EXPECT_EQ(got, (std::vector<float>{1.0f, 1.2f, 4.0f}));
}

// Kernel::warm_up() with the streams bound (the shapes a driver compiles its variant for),
// unmasked and masked, runs no element: the outputs keep their values, nothing is counted as
// launched, and its time is added to driver_finish_ms. Launches after it compute as ever.
TEST_P(WarmUpTest, ExplicitWarmUpWithTheBoundStreamsRunsNoElement) {
  Program p = program("warmed_for_its_streams", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  Kernel k = compile(p);
  const int w = 300, h = 75;  // not powers of two: llvmpipe's other shader variant
  std::vector<float> xs(static_cast<size_t>(w * h)), before(xs.size(), -1.0f);
  for (size_t i = 0; i < xs.size(); ++i) xs[i] = static_cast<float>(i);
  Stream<Float> x(w, h), y(w, h);
  x.upload(xs);
  y.upload(before);
  Stream<Int> state(w, h);
  std::vector<int32_t> states(xs.size());
  for (size_t i = 0; i < states.size(); ++i) states[i] = static_cast<int32_t>(i % 2);
  state.upload(states);
  k.inputs(x).outputs(y);
  const double finish = k.info().driver_finish_ms;
  const double ms = k.warm_up();
  EXPECT_GE(ms, 0.0);
  const double masked_ms = k.warm_up(where(state, 1));
  EXPECT_GE(masked_ms, 0.0);
  EXPECT_DOUBLE_EQ(k.info().driver_finish_ms, finish + ms + masked_ms);
  EXPECT_EQ(k.last_launch().processed, 0);
  EXPECT_EQ(y.download(), before);

  EXPECT_EQ(k.execute(where(state, 1)), w * h / 2);
  std::vector<float> got = y.download();
  for (size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], i % 2 == 1 ? 2.0f * xs[i] : -1.0f) << i;
  // A mask of the wrong size is the same error as at launch.
  Stream<Int> small(4);
  EXPECT_THROW(k.warm_up(where(small, 1)), Error);
}

RILL_BACKEND_TEST_SUITE(WarmUpTest);

}  // namespace
}  // namespace rill::testing
