// Launching kernels: discard and execute() counts, loop() passes, streams bound as both input
// and output, uniforms, arrays (gathers with clamped indices), element_index/element_coord,
// Int streams, several inputs and outputs, binding by name, large streams (threading),
// accuracy modes, and launch errors.
#include <rill/Stopwatch.h>
#include <rill/StrictMath.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>

#include "BackendTest.h"

namespace rill::testing {
namespace {

using F2 = glm::vec2;
using F3 = glm::vec3;
using F4 = glm::vec4;
using I2 = glm::ivec2;

class LaunchTest : public BackendTest {};

std::vector<float> uniform_floats(uint32_t seed, size_t n, float lo, float hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  std::vector<float> v(n);
  for (float& x : v) x = d(rng);
  return v;
}

// Runs f, expecting rill::Error whose message contains every one of `parts`.
template <class F>
void expect_error(F f, std::initializer_list<const char*> parts) {
  try {
    f();
    ADD_FAILURE() << "expected rill::Error mentioning '" << *parts.begin() << "'";
  } catch (const rill::Error& e) {
    std::string what = e.what();
    for (const char* part : parts)
      EXPECT_NE(what.find(part), std::string::npos)
          << "message '" << what << "' does not mention '" << part << "'";
  }
}

// ---- discard --------------------------------------------------------------------------------

TEST_P(LaunchTest, DiscardKeepsPreviousValuesAndIsNotCounted) {
  auto xs = sweep_floats(1, 5000);
  Program p = program("discard", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> tag("tag");
    RILL_IF(x < 0.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    tag = 1;
    RILL_FOR(Int i = 0, i < 4, i += 1) {  // a discard inside a loop, nested in an if
      RILL_IF(x > 100.0f * to_float(i + 1) && x < 1e6f) {
        RILL_DISCARD;
      }
      RILL_ENDIF;
    }
    RILL_ENDFOR;
    y = x * 2.0f;
  });
  Kernel k = compile(p);
  Stream<Float> in(xs), y(static_cast<int64_t>(xs.size()));
  Stream<Int> tag(static_cast<int64_t>(xs.size()));
  y.fill(-7.0f);
  tag.fill(-1);
  k.inputs(in).outputs(y, tag);
  int64_t written = k.execute();
  auto discarded = [](float x) { return x < 0.0f || (x > 100.0f && x < 1e6f); };
  int64_t want_written = 0;
  for (float x : xs) want_written += discarded(x) ? 0 : 1;
  EXPECT_EQ(written, want_written);
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(y.download(),
                         map(xs, [&](float x) { return discarded(x) ? -7.0f : x * 2.0f; }), d));
  EXPECT_TRUE(
      bits_equal(tag.download(), map(xs, [&](float x) { return discarded(x) ? -1 : 1; }), d));
}

// An output not written on some path keeps its stream's value; the element still counts.
TEST_P(LaunchTest, UnwrittenOutputKeepsPreviousValue) {
  auto xs = sweep_floats(2, 1000);
  Program p = program("partial", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF(x > 0.0f) {
      y = x;
    }
    RILL_ENDIF;
  });
  Kernel k = compile(p);
  Stream<Float> in(xs), y(static_cast<int64_t>(xs.size()));
  y.fill(42.0f);
  k.inputs(in).outputs(y);
  EXPECT_EQ(k.execute(), static_cast<int64_t>(xs.size()));
  EXPECT_TRUE(bits_equal(y.download(), map(xs, [](float x) { return x > 0.0f ? x : 42.0f; }),
                         describe_inputs(xs)));
}

// ---- loop() ---------------------------------------------------------------------------------

// The terminating kernel: each pass doubles values below 1 (capped at 1); elements at 1
// discard. loop() runs until a pass writes nothing and counts that last pass too.
Program grow_program() {
  return program("grow", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF(x >= 1.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    y = min(x * 2.0f, 1.0f);
  });
}

TEST_P(LaunchTest, LoopCountsPassesUntilNothingIsWritten) {
  auto xs = uniform_floats(3, 10000, 1e-6f, 1.5f);
  xs[17] = 1e-30f;  // the longest: about 100 passes
  Kernel k = compile(grow_program());
  Stream<Float> s(xs);
  k.inputs(s).outputs(s);
  int64_t passes = k.loop();

  // Reference: simulate the passes.
  std::vector<float> v = xs;
  int64_t want = 0;
  for (;;) {
    ++want;
    int64_t written = 0;
    for (float& x : v)
      if (!(x >= 1.0f)) {
        float d = x * 2.0f;
        x = 1.0f < d ? 1.0f : d;
        ++written;
      }
    if (written == 0) break;
  }
  EXPECT_EQ(passes, want);
  EXPECT_TRUE(bits_equal(s.download(), v, describe_inputs(xs)));
  // Everything has terminated: one more loop() is the single empty pass.
  EXPECT_EQ(k.loop(), 1);
}

TEST_P(LaunchTest, LoopThrowsAfterMaxPasses) {
  Kernel k = compile(grow_program());
  Stream<Float> s(std::vector<float>{0.5f, 0.0f, 0.25f});  // 0 never grows
  k.inputs(s).outputs(s);
  expect_error([&] { k.loop(50); }, {"grow", "50 passes"});
}

// ---- streams as input and output -------------------------------------------------------------

TEST_P(LaunchTest, SameStreamAsInputAndOutput) {
  auto xs = sweep_floats(4, 3000);
  Program p = program("in_place", [] {
    Input<Float> x("x");
    Input<Float> w("w");
    Output<Float> y("y");
    Output<Float> z("z");
    y = x + 1.0f;
    y = y * w;  // reads the output variable (not the stream) after writing it
    z = x - w;
  });
  Kernel k = compile(p);
  Stream<Float> s(xs), t(xs);
  // s is input x, input w and output y at once; t is output z.
  k.inputs(s, s).outputs(s, t);
  k.execute();
  auto want_y = map(xs, [](float x) { return (x + 1.0f) * x; });
  auto want_z = map(xs, [](float x) { return x - x; });
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(s.download(), want_y, d));
  EXPECT_TRUE(bits_equal(t.download(), want_z, d));
  // Again: the input is now the previous result.
  k.execute();
  EXPECT_TRUE(bits_equal(s.download(), map(want_y, [](float x) { return (x + 1.0f) * x; }), d));
}

// ---- uniforms -------------------------------------------------------------------------------

TEST_P(LaunchTest, UniformsChangeWithoutRecompiling) {
  Uniform<Float> gain(2.0f, "gain");
  Uniform<Float3> offset(F3(1.0f, -2.0f, 0.5f), "offset");
  Uniform<Int> shift(3, "shift");
  auto define = [&] {
    return program("uniforms", [&] {
      Input<Float3> x("x");
      Input<Int> i("i");
      Output<Float3> y("y");
      Output<Int> j("j");
      y = x * gain + offset;
      j = i << shift;
    });
  };
  Program p = define();
  auto xs = unflatten<F3>(uniform_floats(5, 3 * 700, -10.0f, 10.0f));
  auto is = random_ints(6, 700);
  Kernel k = compile(p);
  Stream<Float3> xst(xs), yst(static_cast<int64_t>(xs.size()));
  Stream<Int> ist(is), jst(static_cast<int64_t>(is.size()));
  k.inputs(xst, ist).outputs(yst, jst);

  auto check = [&](float g, F3 o, int32_t sh) {
    k.execute();
    Describe d = describe_inputs(xs, is);
    EXPECT_TRUE(bits_equal(yst.download(), map(xs, [&](F3 x) { return x * g + o; }), d))
        << "gain " << g;
    EXPECT_TRUE(bits_equal(
        jst.download(),
        map(is,
            [&](int32_t i) { return static_cast<int32_t>(static_cast<uint32_t>(i) << (sh & 31)); }),
        d))
        << "shift " << sh;
  };
  check(2.0f, F3(1.0f, -2.0f, 0.5f), 3);
  int64_t misses = kernel_cache_stats().misses;

  gain.set(-0.5f);
  offset = F3(0.0f, 100.0f, -0.0f);
  shift.set(35);  // counts use their low 5 bits
  check(-0.5f, F3(0.0f, 100.0f, -0.0f), 35);

  // Compiling the same program again, or an identical one defined again, is a cache hit.
  Kernel again = compile(p);
  EXPECT_TRUE(again.info().cache_hit);
  Kernel redefined = compile(define());
  EXPECT_TRUE(redefined.info().cache_hit);
  EXPECT_EQ(kernel_cache_stats().misses, misses) << "a uniform change must not recompile";
}

// Programs with identical IR share one compiled kernel, but each launch reads its own
// program's uniforms and arrays.
TEST_P(LaunchTest, IdenticalProgramsKeepTheirOwnUniformsAndArrays) {
  Uniform<Float> g1(1.0f, "g"), g2(5.0f, "g");
  Uniform<Bool> flag(true, "flag");
  Array<Float> t1(std::vector<float>{1.0f, 2.0f, 3.0f}, "t");
  Array<Float> t2(std::vector<float>{10.0f, 20.0f, 30.0f}, "t");
  auto define = [&](Uniform<Float>& g, Array<Float>& t) {
    return program("shared_code", [&] {
      Input<Int> i("i");
      Output<Float> y("y");
      y = select(flag, t[i] * g, -t[i]);
    });
  };
  Kernel k1 = compile(define(g1, t1));
  Kernel k2 = compile(define(g2, t2));
  EXPECT_TRUE(k2.info().cache_hit);
  std::vector<int32_t> is = {0, 2, 7};
  EXPECT_TRUE(bits_equal(run_kernel<Float>(k1, 3, is), {1.0f, 3.0f, 3.0f}));
  EXPECT_TRUE(bits_equal(run_kernel<Float>(k2, 3, is), {50.0f, 150.0f, 150.0f}));
  flag.set(false);  // a Bool uniform
  EXPECT_TRUE(bits_equal(run_kernel<Float>(k1, 3, is), {-1.0f, -3.0f, -3.0f}));
}

// ---- streams between launches ---------------------------------------------------------------

TEST_P(LaunchTest, HostWritesAndChainedKernels) {
  Program twice = program("twice", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  Program inc = program("inc", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + 1.0f;
  });
  Kernel k1 = compile(twice), k2 = compile(inc);
  Stream<Float> a(std::vector<float>{1.0f, 2.0f, 3.0f}), b(3), c(3);
  k1.inputs(a).outputs(b);
  k2.inputs(b).outputs(c);
  k1.execute();
  k2.execute();  // reads what k1 wrote, without a download in between
  EXPECT_TRUE(bits_equal(c.download(), {3.0f, 5.0f, 7.0f}));
  a.upload(std::vector<float>{10.0f, 20.0f, 30.0f});  // the host writes an input
  k1.execute();
  k2.execute();
  EXPECT_TRUE(bits_equal(c.download(), {21.0f, 41.0f, 61.0f}));
  EXPECT_TRUE(bits_equal(b.download(), {20.0f, 40.0f, 60.0f}));
  b.fill(-1.0f);  // the host overwrites an intermediate stream
  k2.execute();
  EXPECT_TRUE(bits_equal(c.download(), {0.0f, 0.0f, 0.0f}));
}

// A stream written by this backend and read by the CPU backend, and back.
TEST_P(LaunchTest, StreamsMoveBetweenBackends) {
  Program inc = program("inc_interop", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + 1.0f;
  });
  Kernel here = compile(inc);
  Kernel cpu = rill::compile(inc, "cpu");
  Stream<Float> a(std::vector<float>{1.0f, 2.0f}), b(2), c(2);
  here.inputs(a).outputs(b).execute();
  cpu.inputs(b).outputs(c).execute();
  here.inputs(c).outputs(a).execute();
  EXPECT_TRUE(bits_equal(a.download(), {4.0f, 5.0f}));
  EXPECT_TRUE(bits_equal(b.download(), {2.0f, 3.0f}));
}

// Backends on the host's CPU cores (cpu, simd, PoCL, Mesa's llvmpipe) do not claim a GPU,
// and a GPU driver's device is one (what device-tuned defaults, like the ray tracer's grid,
// go by).
TEST_P(LaunchTest, RunsOnGpuNamesTheDeviceKind) {
  Backend& be = rill::backend(backend_name());
  const std::string d = be.description();
  const bool software = backend_name() == "cpu" || backend_name() == "simd" ||
                        d.find("llvmpipe") != std::string::npos ||
                        d.find("Portable Computing Language") != std::string::npos;
  const bool gpu_driver = d.find("NVIDIA") != std::string::npos;
  if (software) {
    EXPECT_FALSE(be.runs_on_gpu()) << d;
  }
  if (gpu_driver) {
    EXPECT_TRUE(be.runs_on_gpu()) << d;
  }
}

// A launch reports how long its kernel ran on the device: within the launch's wall time,
// and more than nothing for a kernel with work to do; 0 when nothing ran. Only the compute
// stage of a software GL renderer (Mesa's) cannot tell (its timer queries skip dispatches):
// -1.
TEST_P(LaunchTest, DeviceTimeIsWithinTheLaunch) {
  Program p = program("busy", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = x;
    RILL_FOR(Int i = 0, i < 200, i += 1) {
      acc = acc * 0.999f + 0.001f;
    }
    RILL_ENDFOR;
    y = acc;
  });
  Kernel k = compile(p);
  Stream<Float> in(uniform_floats(3, 1 << 18, 0.0f, 1.0f)), out(int64_t{1} << 18);
  k.inputs(in).outputs(out);
  k.execute();  // the first launch may finish the driver's compile
  const Stopwatch wall;
  k.execute();
  const double wall_ms = wall.ms();
  const double device_ms = k.last_launch().device_ms;
  const std::string d = rill::backend(backend_name()).description();
  if (backend_name() == "glsl-compute" && !rill::backend(backend_name()).runs_on_gpu()) {
    EXPECT_EQ(device_ms, -1.0) << d;
  } else {
    EXPECT_GT(device_ms, 0.0) << d;
    EXPECT_LE(device_ms, wall_ms) << d;
  }
  Stream<Float> none(0);
  k.inputs(none).outputs(none);
  k.execute();
  EXPECT_EQ(k.last_launch().device_ms, 0.0) << "an empty launch runs nothing";
}

TEST_P(LaunchTest, EmptyStream) {
  Kernel k = compile(grow_program());
  Stream<Float> s(0);
  k.inputs(s).outputs(s);
  EXPECT_EQ(k.execute(), 0);
  EXPECT_EQ(k.loop(), 1);
  EXPECT_TRUE(s.download().empty());
}

// ---- arrays ---------------------------------------------------------------------------------

TEST_P(LaunchTest, ArrayGathersClampIndices) {
  // 1D Float, 2D Float2 and 3D Int arrays; indices cover every element and far outside.
  const int nx = 5, ny = 4, nz = 3;
  std::vector<float> a1(11);
  for (size_t i = 0; i < a1.size(); ++i) a1[i] = 0.5f + static_cast<float>(i);
  std::vector<F2> a2(nx * ny);
  for (int y = 0; y < ny; ++y)
    for (int x = 0; x < nx; ++x) a2[static_cast<size_t>(x + nx * y)] = F2(x, 10 * y);
  std::vector<int32_t> a3(nx * ny * nz);
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x)
        a3[static_cast<size_t>(x + nx * (y + ny * z))] = x + 10 * y + 100 * z;
  Array<Float> arr1(a1, "lut");
  Array<Float2> arr2(nx, ny, "grid");
  arr2.upload(a2);
  Array<Int> arr3(nx, ny, nz, "volume");
  arr3.upload(a3);

  std::vector<int32_t> idx = {
      -2147483647 - 1, -1000, -1, 0, 1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 12, 1000, 2147483647};
  std::vector<int32_t> is, js, ks;
  for (int32_t i : idx)
    for (int32_t j : idx)
      for (int32_t k : {-5, 0, 1, 2, 3, 99}) {
        is.push_back(i);
        js.push_back(j);
        ks.push_back(k);
      }
  Program p = program("gathers", [&] {
    Input<Int> i("i");
    Input<Int> j("j");
    Input<Int> k("k");
    Output<Float> g1("g1");
    Output<Float2> g2("g2");
    Output<Int> g3("g3");
    g1 = arr1[i];
    g2 = arr2(i, j);
    g3 = arr3(i, j, k);
  });
  auto [g1, g2, g3] = run<Float, Float2, Int>(p, is, js, ks);
  auto cl = [](int32_t i, int n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); };
  Describe d = describe_inputs(is, js, ks);
  EXPECT_TRUE(
      bits_equal(g1, map(is, [&](int32_t i) { return a1[static_cast<size_t>(cl(i, 11))]; }), d));
  EXPECT_TRUE(bits_equal(g2,
                         map(is, js,
                             [&](int32_t i, int32_t j) {
                               return a2[static_cast<size_t>(cl(i, nx) + nx * cl(j, ny))];
                             }),
                         d));
  std::vector<int32_t> want3;
  for (size_t n = 0; n < is.size(); ++n)
    want3.push_back(
        a3[static_cast<size_t>(cl(is[n], nx) + nx * (cl(js[n], ny) + ny * cl(ks[n], nz)))]);
  EXPECT_TRUE(bits_equal(g3, want3, d));
}

TEST_P(LaunchTest, ArrayResizeWithoutRecompiling) {
  Array<Float> table(std::vector<float>{1.0f, 2.0f, 3.0f}, "table");
  Program p = program("table_lookup", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = table[i] * 2.0f;
  });
  std::vector<int32_t> is = {-1, 0, 1, 2, 3, 4, 5, 6, 100};
  Kernel k = compile(p);
  auto y = run_kernel<Float>(k, static_cast<int64_t>(is.size()), is);
  EXPECT_TRUE(bits_equal(y, {2.0f, 2.0f, 4.0f, 6.0f, 6.0f, 6.0f, 6.0f, 6.0f, 6.0f}));
  int64_t misses = kernel_cache_stats().misses;
  table.resize(6);
  table.upload(std::vector<float>{-1.0f, -2.0f, -3.0f, -4.0f, -5.0f, -6.0f});
  y = run_kernel<Float>(k, static_cast<int64_t>(is.size()), is);
  EXPECT_TRUE(bits_equal(y, {-2.0f, -2.0f, -4.0f, -6.0f, -8.0f, -10.0f, -12.0f, -12.0f, -12.0f}));
  EXPECT_EQ(kernel_cache_stats().misses, misses);
}

// Part of an array replaced after a launch (an animation's moving triangles): the next launch
// reads the new elements and the old ones around them, on every backend; a second part
// replaced before any launch joins the first; out of range is an error.
TEST_P(LaunchTest, ArrayPartialUploadKeepsTheRest) {
  std::vector<float> values(1000);
  for (size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(i);
  Array<Float> table(values, "table");
  Program p = program("table_copy", [&] {
    Input<Int> i("i");
    Output<Float> y("y");
    y = table[i];
  });
  std::vector<int32_t> is(values.size());
  for (size_t i = 0; i < is.size(); ++i) is[i] = static_cast<int32_t>(i);
  Kernel k = compile(p);
  auto y = run_kernel<Float>(k, static_cast<int64_t>(is.size()), is);
  ASSERT_TRUE(bits_equal(y, values));
  // The device copy is current now; replace 100..149, then 900..909 as well.
  std::vector<float> part(50, -1.0f), other(10, -2.0f);
  table.upload(100, part);
  std::copy(part.begin(), part.end(), values.begin() + 100);
  y = run_kernel<Float>(k, static_cast<int64_t>(is.size()), is);
  EXPECT_TRUE(bits_equal(y, values));
  table.upload(900, other);
  table.upload(5, std::vector<float>{-3.0f});
  std::copy(other.begin(), other.end(), values.begin() + 900);
  values[5] = -3.0f;
  y = run_kernel<Float>(k, static_cast<int64_t>(is.size()), is);
  EXPECT_TRUE(bits_equal(y, values));
  EXPECT_THROW(table.upload(995, other), Error);
  EXPECT_THROW(table.upload(-1, part), Error);
}

// ---- element index and coordinates ----------------------------------------------------------

TEST_P(LaunchTest, ElementIndexAndCoord1D) {
  Program p = program("index_1d", [] {
    Output<Int> idx("idx");
    Output<Int2> coord("coord");
    idx = element_index();
    coord = element_coord();
  });
  const int64_t n = 5000;
  auto [idx, coord] = run_n<Int, Int2>(p, n);
  std::vector<int32_t> want_idx;
  std::vector<I2> want_coord;
  for (int32_t i = 0; i < n; ++i) {
    want_idx.push_back(i);
    want_coord.emplace_back(i, 0);
  }
  EXPECT_TRUE(bits_equal(idx, want_idx));
  EXPECT_TRUE(bits_equal(coord, want_coord));
}

// Every element of a 2D launch runs once, whatever the shape (GPU backends may run them in
// tiles: shapes that are not whole tiles, one column, exactly one tile).
TEST_P(LaunchTest, ElementCoord2D) {
  Program p = program("coord_2d", [] {
    Input<Float> x("x");
    Output<Int2> coord("coord");
    Output<Float> y("y");
    Output<Int> idx("idx");
    coord = element_coord();
    idx = element_index();
    y = x + to_float(element_coord().y());
  });
  Kernel k = compile(p);
  for (auto [w, h] : {std::pair<int64_t, int64_t>{37, 23}, {1, 9}, {8, 4}, {65, 5}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h));
    std::vector<float> xs = uniform_floats(7, static_cast<size_t>(w * h), -1.0f, 1.0f);
    Stream<Float> in(xs), y(w, h);
    Stream<Int2> coord(w, h);
    Stream<Int> idx(w, h);
    ASSERT_EQ(coord.width(), w);
    ASSERT_EQ(coord.height(), h);
    k.inputs(in).outputs(coord, y, idx);
    EXPECT_EQ(k.execute(), w * h);
    std::vector<I2> want_coord;
    std::vector<float> want_y;
    std::vector<int32_t> want_idx;
    for (int32_t i = 0; i < w * h; ++i) {
      want_coord.emplace_back(i % w, i / w);
      want_y.push_back(xs[static_cast<size_t>(i)] + static_cast<float>(i / w));
      want_idx.push_back(i);
    }
    EXPECT_TRUE(bits_equal(coord.download(), want_coord));
    EXPECT_TRUE(bits_equal(y.download(), want_y));
    EXPECT_TRUE(bits_equal(idx.download(), want_idx));
  }
}

// ---- several inputs and outputs, Int streams, binding by name --------------------------------

TEST_P(LaunchTest, MixedInputsAndOutputs) {
  auto as = sweep_ints(8, 2000);
  auto bs = uniform_floats(9, as.size(), -100.0f, 100.0f);
  auto cs = unflatten<F3>(uniform_floats(10, 3 * as.size(), -5.0f, 5.0f));
  Program p = program("mixed", [] {
    Input<Int> a("a");
    Input<Float> b("b");
    Input<Float3> c("c");
    Output<Float4> o1("o1");
    Output<Int2> o2("o2");
    o1 = Float4(c * b, to_float(a));
    o2 = Int2(a + 1, to_int(b) * a);
  });
  auto [o1, o2] = run<Float4, Int2>(p, as, bs, cs);
  std::vector<F4> w1;
  std::vector<I2> w2;
  for (size_t i = 0; i < as.size(); ++i) {
    F3 cb = cs[i] * bs[i];
    w1.emplace_back(cb, static_cast<float>(as[i]));
    auto wrap = [](int64_t v) { return static_cast<int32_t>(static_cast<uint32_t>(v)); };
    w2.emplace_back(wrap(int64_t{as[i]} + 1), wrap(int64_t{static_cast<int32_t>(bs[i])} * as[i]));
  }
  Describe d = describe_inputs(as, bs, cs);
  EXPECT_TRUE(bits_equal(o1, w1, d));
  EXPECT_TRUE(bits_equal(o2, w2, d));
}

TEST_P(LaunchTest, BindByName) {
  Program p = program("named", [] {
    Input<Float> a("a");
    Input<Float> b("b");
    Output<Float> diff("diff");
    Output<Int> flag("flag");
    diff = a - b;
    flag = select(a < b, Int(1), Int(0));
  });
  std::vector<float> av = {1.0f, 5.0f, -2.0f}, bv = {4.0f, 2.0f, -2.0f};
  Kernel k = compile(p);
  Stream<Float> sa(av), sb(bv), sd(3);
  Stream<Int> sf(3);
  // Out of declaration order, outputs before inputs.
  k.bind("flag", sf).bind("b", sb).bind("diff", sd).bind("a", sa);
  EXPECT_EQ(k.execute(), 3);
  EXPECT_TRUE(bits_equal(sd.download(), {-3.0f, 3.0f, 0.0f}));
  EXPECT_TRUE(bits_equal(sf.download(), {1, 0, 0}));
  // Rebinding one name swaps that stream only.
  k.bind("a", sb).bind("b", sa);
  k.execute();
  EXPECT_TRUE(bits_equal(sd.download(), {3.0f, -3.0f, 0.0f}));
  expect_error([&] { k.bind("nope", sa); }, {"named", "nope"});
}

// ---- large streams --------------------------------------------------------------------------

// Read-backs of growing size, straight into the caller's memory (download_into) and into a
// new vector: backends that stage large read-backs (OpenCL's pinned buffer) grow the stage.
TEST_P(LaunchTest, LargeReadBacksOfGrowingSize) {
  Program p = program("indices", [] {
    Output<Int> idx("idx");
    idx = element_index() * 3;
  });
  Kernel k = compile(p);
  std::vector<int32_t> into;
  for (int64_t n : {int64_t{300000}, int64_t{1} << 21, int64_t{300001}}) {
    Stream<Int> out(n);
    k.outputs(out);
    k.execute();
    into.assign(static_cast<size_t>(n), -1);
    out.download_into(std::span(into));
    const std::vector<int32_t> fresh = out.download();
    for (int64_t i = 0; i < n; i += 997) {
      ASSERT_EQ(into[static_cast<size_t>(i)], i * 3) << n;
      ASSERT_EQ(fresh[static_cast<size_t>(i)], i * 3) << n;
    }
    EXPECT_EQ(into.back(), (n - 1) * 3);
    EXPECT_EQ(into, fresh);
  }
  Stream<Int> small(10);
  EXPECT_THROW(small.download_into(std::span(into)), rill::Error);  // sizes differ
}

// download_async (rill/ReadBack.h) reads the words of the moment it was called, even when
// the next launches write the stream before the transfer ends: OpenCL keeps a copy on the
// device for its transfer queue; the other backends copy at once. Under
// RILL_OPENCL_READBACK=late the transfer starts only at wait(), after both later launches
// have run, so a read-back that read the stream itself would get their words (3i + 3), not
// its own. A ReadBack destroyed unwaited has waited.
TEST_P(LaunchTest, AsyncReadBackKeepsTheWordsOfItsStart) {
  Uniform<Int> add(0, "add");
  Program p = program("indices_plus", [&] {
    Output<Int> idx("idx");
    idx = element_index() * 3 + add;
  });
  Kernel k = compile(p);
  const int64_t n = 300001;
  const size_t count = static_cast<size_t>(n);
  auto expect_words = [&](const std::vector<int32_t>& v, int32_t plus, const char* what) {
    ASSERT_EQ(v.size(), count) << what;
    for (size_t i = 0; i < count; ++i)
      ASSERT_EQ(v[i], static_cast<int32_t>(i) * 3 + plus) << what << ", element " << i;
  };
  for (const char* mode : {"overlap", "late"}) {
    SCOPED_TRACE(std::string("RILL_OPENCL_READBACK=") + mode);
    ASSERT_EQ(setenv("RILL_OPENCL_READBACK", mode, 1), 0);
    Stream<Int> out(n);
    k.outputs(out);
    std::vector<int32_t> first(count, -1), second(count, -1), third(count, -1);
    add.set(1);
    k.execute();
    ReadBack a = out.download_async(std::span(first));
    add.set(2);
    k.execute();  // writes the stream while `a` may be in flight
    ReadBack b = out.download_async(std::span(second));
    add.set(3);
    k.execute();
    { ReadBack c = out.download_async(std::span(third)); }  // destroyed unwaited: it waits
    expect_words(third, 3, "the read-back destroyed unwaited");
    a.wait();
    b.wait();
    a.wait();  // again: nothing in flight
    EXPECT_FALSE(a.in_flight());
    expect_words(first, 1, "the first read-back");
    expect_words(second, 2, "the second read-back");
    expect_words(out.download(), 3, "the stream now");
    std::vector<int32_t> small(10);
    EXPECT_THROW(out.download_async(std::span(small)), rill::Error);  // sizes differ
  }
  unsetenv("RILL_OPENCL_READBACK");
  if (backend_name() == "opencl") {
    ASSERT_EQ(setenv("RILL_OPENCL_READBACK", "soon", 1), 0);
    Stream<Int> out(n);
    k.outputs(out);
    k.execute();
    std::vector<int32_t> into(count);
    expect_error([&] { out.download_async(std::span(into)).wait(); },
                 {"RILL_OPENCL_READBACK='soon'", "overlap, late"});
    unsetenv("RILL_OPENCL_READBACK");
  }
}

TEST_P(LaunchTest, LargeStreamWithDiscards) {
  const int64_t n = 1000000;
  std::vector<float> xs(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) xs[static_cast<size_t>(i)] = static_cast<float>(i % 1000) - 10.5f;
  Program p = program("large", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> idx("idx");
    RILL_IF(x < 0.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    y = x * 3.0f + 1.0f;
    idx = element_index();
  });
  Kernel k = compile(p);
  Stream<Float> in(xs), y(n);
  Stream<Int> idx(n);
  y.fill(-1.0f);
  idx.fill(-1);
  k.inputs(in).outputs(y, idx);
  int64_t written = k.execute();
  std::vector<float> wy(xs.size());
  std::vector<int32_t> widx(xs.size());
  int64_t want = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    bool keep = !(xs[i] < 0.0f);
    want += keep;
    wy[i] = keep ? xs[i] * 3.0f + 1.0f : -1.0f;
    widx[i] = keep ? static_cast<int32_t>(i) : -1;
  }
  EXPECT_EQ(written, want);
  EXPECT_TRUE(bits_equal(y.download(), wy));
  EXPECT_TRUE(bits_equal(idx.download(), widx));
}

// ---- accuracy modes -------------------------------------------------------------------------

Program accuracy_program() {
  return program("accuracy", [] {
    Input<Float> a("a");
    Input<Float> b("b");
    Output<Float> arith("arith");
    Output<Float> trans("trans");
    Output<Float> cancel("cancel");
    arith = (a * b + a) / (b * b + 1.0f) - sqrt(abs(a)) * 0.5f;
    trans = exp(a * 0.1f) + sin(b) * cos(a) + log(abs(b) + 1.0f) + pow(abs(a) + 0.5f, 1.5f) +
            atan2(a, b) + tan(b * 0.1f) + exp2(b * 0.05f) + log2(abs(a) + 2.0f) + atan(a);
    cancel = (a * 1e8f + 1.0f) - a * 1e8f;  // 0 or 1 in binary32, exactly 1 in binary64
  });
}

double ref_arith(double a, double b) {
  return (a * b + a) / (b * b + 1.0) - std::sqrt(std::fabs(a)) * 0.5;
}
// The kernel's float constants, widened (0.1f is not 0.1).
double ref_trans(double a, double b) {
  const double k01 = 0.1f, k005 = 0.05f;
  return std::exp(a * k01) + std::sin(b) * std::cos(a) + std::log(std::fabs(b) + 1.0) +
         std::pow(std::fabs(a) + 0.5, 1.5) + std::atan2(a, b) + std::tan(b * k01) +
         std::exp2(b * k005) + std::log2(std::fabs(a) + 2.0) + std::atan(a);
}

TEST_P(LaunchTest, AccuracyFastIsClose) {
  if (!supports(Accuracy::Fast)) GTEST_SKIP() << "no fast mode";
  auto as = uniform_floats(11, 4000, -10.0f, 10.0f);
  auto bs = uniform_floats(12, 4000, -10.0f, 10.0f);
  Kernel k = compile(accuracy_program(), Accuracy::Fast);
  auto [arith, trans, cancel] = run_kernel<Float, Float, Float>(k, 4000, as, bs);
  std::vector<float> wa, wt;
  for (size_t i = 0; i < as.size(); ++i) {
    wa.push_back(static_cast<float>(ref_arith(as[i], bs[i])));
    wt.push_back(static_cast<float>(ref_trans(as[i], bs[i])));
  }
  Describe d = describe_inputs(as, bs);
  EXPECT_TRUE(close_to(arith, wa, 1e-5, 1e-5, d));
  EXPECT_TRUE(close_to(trans, wt, 1e-4, 1e-3, d));
  (void)cancel;
}

TEST_P(LaunchTest, AccuracyDoubleIsCloseAndUsesBinary64) {
  if (!supports(Accuracy::Double)) {
    expect_error([&] { compile(accuracy_program(), Accuracy::Double); }, {"double"});
    GTEST_SKIP() << "no double mode";
  }
  auto as = uniform_floats(13, 4000, -10.0f, 10.0f);
  auto bs = uniform_floats(14, 4000, -10.0f, 10.0f);
  as[0] = 3.0f;  // a * 1e8 + 1 is not representable in binary32
  Kernel k = compile(accuracy_program(), Accuracy::Double);
  auto [arith, trans, cancel] = run_kernel<Float, Float, Float>(k, 4000, as, bs);
  std::vector<double> wa, wt;
  std::vector<float> wc;
  for (size_t i = 0; i < as.size(); ++i) {
    wa.push_back(ref_arith(as[i], bs[i]));
    wt.push_back(ref_trans(as[i], bs[i]));
    wc.push_back(
        static_cast<float>((double{as[i]} * double{1e8f} + 1.0) - double{as[i]} * double{1e8f}));
  }
  Describe d = describe_inputs(as, bs);
  // Computed in binary64 and rounded once at the store: within an ulp or so.
  EXPECT_TRUE(within_ulps(arith, wa, 1, d));
  EXPECT_TRUE(within_ulps(trans, wt, 2, d));
  EXPECT_TRUE(bits_equal(cancel, wc, d)) << "double mode must not fold or compute in binary32";
  // simd runs its double kernels as scalar C (not in lanes) and says so, in the kernel's
  // compile information and in the backend's listing; no other mode or backend has a note.
  const std::string note = rill::backend(backend_name()).accuracy_note(Accuracy::Double);
  EXPECT_EQ(k.info().execution, note);
  EXPECT_EQ(note.find("scalar") != std::string::npos, backend_name() == "simd") << note;
  EXPECT_EQ(compile(accuracy_program()).info().execution, "");
}

TEST_P(LaunchTest, AccuracyStrictMatchesBinary32) {
  auto as = uniform_floats(15, 4000, -10.0f, 10.0f);
  auto bs = uniform_floats(16, 4000, -10.0f, 10.0f);
  as[0] = 3.0f;
  Kernel k = compile(accuracy_program());
  auto [arith, trans, cancel] = run_kernel<Float, Float, Float>(k, 4000, as, bs);
  auto ref = [](float a, float b) {
    float p = a * b;
    float n = p + a;
    float q = b * b;
    float dd = q + 1.0f;
    float r = n / dd;
    float s = std::sqrt(std::fabs(a));
    float h = s * 0.5f;
    return r - h;
  };
  Describe d = describe_inputs(as, bs);
  EXPECT_TRUE(bits_equal(arith, map(as, bs, ref), d));
  EXPECT_TRUE(bits_equal(cancel,
                         map(as, bs,
                             [](float a, float) {
                               float m = a * 1e8f;
                               float s = m + 1.0f;
                               return s - m;
                             }),
                         d));
  std::vector<double> wt;
  for (size_t i = 0; i < as.size(); ++i) wt.push_back(ref_trans(as[i], bs[i]));
  // A sum of nine functions: the error of each result, plus roundings of the sum.
  EXPECT_TRUE(
      close_to(trans, map(wt, [](double x) { return static_cast<float>(x); }), 1e-5, 1e-4, d));
}

// rill::strict routines called directly: close to the reference in every mode.
TEST_P(LaunchTest, StrictRoutinesInEveryMode) {
  auto xs = uniform_floats(17, 4000, -20.0f, 20.0f);
  Program p = program("strict_routines", [] {
    Input<Float> x("x");
    Output<Float4> y("y");
    y = Float4(strict::sin(x), strict::exp(x * 0.25f), strict::log(abs(x) + 0.5f),
               strict::atan2(x, 3.0f));
  });
  std::vector<double> want;
  for (float x : xs) {
    want.push_back(std::sin(double{x}));
    want.push_back(std::exp(double{x * 0.25f}));
    want.push_back(std::log(double{std::fabs(x) + 0.5f}));
    want.push_back(std::atan2(double{x}, 3.0));
  }
  // StrictMath.h: the routines' bounds hold in strict (and double) mode; in fast mode the
  // backend compiler may reassociate their arithmetic, so no bound is promised there.
  for (Accuracy a : {Accuracy::Strict, Accuracy::Double}) {
    if (!supports(a)) continue;
    Kernel k = compile(p, a);
    auto y = flatten(run_kernel<Float4>(k, static_cast<int64_t>(xs.size()), xs));
    EXPECT_TRUE(within_ulps(y, want, 8, describe_inputs(xs), 4)) << accuracy_name(a);
  }
}

// strict::pow_of_zero gives pow's bits for both zeros and every kind of exponent: odd and
// even integers of both signs, fractions, 2^24 and beyond, infinities, NaN. (The zeros are
// inputs, so no pow is folded away at compile time.)
TEST_P(LaunchTest, PowOfZeroIsPowAtBothZeros) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> ys{0.0f,         -0.0f,    1.0f,     2.0f,     3.0f,         -1.0f,
                              -2.0f,        -3.0f,    0.5f,     -0.5f,    40.0f,        41.0f,
                              1e-45f,       -1e-45f,  16777215, 16777216, 1e30f,        -1e30f,
                              -16777215.0f, 10000.0f, inf,      -inf,     std::nanf("")};
  std::vector<float> xs, yy;
  for (float x : {0.0f, -0.0f})
    for (float y : ys) {
      xs.push_back(x);
      yy.push_back(y);
    }
  Program p = program("pow_of_zero", [] {
    Input<Float> x("x"), y("y");
    Output<Float2> r("r");
    r = Float2(strict::pow(x, y), strict::pow_of_zero(x, y));
  });
  Kernel k = compile(p);
  const std::vector<glm::vec2> r = run_kernel<Float2>(k, static_cast<int64_t>(xs.size()), xs, yy);
  for (size_t i = 0; i < xs.size(); ++i) {
    EXPECT_EQ(std::bit_cast<uint32_t>(r[i].x), std::bit_cast<uint32_t>(r[i].y))
        << "pow(" << xs[i] << ", " << yy[i] << ") = " << r[i].x << ", pow_of_zero " << r[i].y;
    // C99's pow (std::pow) agrees, of the exponent the backend reads (a backend that flushes
    // denormals reads +-1e-45 as +-0).
    if (!std::isnan(yy[i])) {
      const float y = flushes_denormals() ? flush(yy[i]) : yy[i];
      EXPECT_EQ(std::bit_cast<uint32_t>(r[i].y), std::bit_cast<uint32_t>(std::pow(xs[i], y)))
          << "pow(" << xs[i] << ", " << yy[i] << ")";
    }
  }
}

// strict::pow_term_is_lost: wherever it says c + s * pow(x, y) is c, the sum computed with
// pow is c, bit for bit, over bases from tiny to above 1, exponents from 1 to 3e7 and sums
// from 1e-30 to 1e30; and it says so for most small terms (it is not vacuous).
TEST_P(LaunchTest, PowTermIsLostOnlyWhereTheSumIsUnchanged) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float ys[] = {1.0f, 2.0f, 5.0f, 20.0f, 40.0f, 60.0f, 1000.0f, 1e6f, 3e7f};
  std::vector<float> cs, ss, xs, yv;
  for (int i = 0; i < 20000; ++i) {
    // Bases spread evenly in log2 over [2^-8, 2) and linearly near 1, where the bound is
    // closest to the truth.
    const float x = i % 2 ? std::exp2(-8.0f + 9.0f * unit(rng)) : 0.5f + unit(rng);
    cs.push_back(std::exp2(-100.0f + 200.0f * unit(rng)) * (i % 7 == 0 ? 1.0f : unit(rng)));
    ss.push_back(i % 11 == 0 ? 0.0f : unit(rng));
    xs.push_back(x);
    yv.push_back(ys[i % 9]);
  }
  Program p = program("pow_term", [] {
    Input<Float> c("c"), s("s"), x("x"), y("y");
    Output<Float2> r("r");
    r = Float2(c + s * strict::pow(x, y),
               select(strict::pow_term_is_lost(c, s, x, y), Float(1.0f), Float(0.0f)));
  });
  Kernel k = compile(p);
  const std::vector<glm::vec2> r =
      run_kernel<Float2>(k, static_cast<int64_t>(xs.size()), cs, ss, xs, yv);
  int lost = 0, small = 0;
  for (size_t i = 0; i < xs.size(); ++i) {
    const bool says_lost = r[i].y == 1.0f;
    lost += says_lost;
    if (says_lost) {
      ASSERT_EQ(std::bit_cast<uint32_t>(r[i].x), std::bit_cast<uint32_t>(cs[i]))
          << cs[i] << " + " << ss[i] << " * pow(" << xs[i] << ", " << yv[i] << ")";
    }
    // A term below 2^-40 of the sum (in double) is lost by any measure.
    const double term = double(ss[i]) * std::pow(double(xs[i]), double(yv[i]));
    small += term < std::ldexp(double(cs[i]), -40);
  }
  EXPECT_GT(lost, small * 9 / 10) << "of " << small << " terms below 2^-40 of their sum";
  EXPECT_GT(small, 5000);
}

// ---- launch errors --------------------------------------------------------------------------

TEST_P(LaunchTest, LaunchErrors) {
  Program p = program("checked", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    y = x * to_float(n);
  });
  Kernel k = compile(p);
  Stream<Float> x10(10), y10(10), x5(5);
  Stream<Int> n10(10), n5(5);
  Stream<Float3> v10(10);

  // Wrong number of streams.
  expect_error([&] { k.inputs(x10); }, {"checked", "2 input", "1 stream"});
  expect_error([&] { k.outputs(y10, x10); }, {"checked", "1 output", "2 stream"});
  // Unbound.
  expect_error([&] { k.execute(); }, {"checked", "'y'", "not bound"});
  k.outputs(y10);
  expect_error([&] { k.execute(); }, {"checked", "'x'", "not bound"});
  // Wrong element type.
  k.inputs(n10, n10);
  expect_error([&] { k.execute(); }, {"checked", "input 'x'", "float", "int"});
  k.inputs(x10, n10).outputs(v10);
  expect_error([&] { k.execute(); }, {"checked", "output 'y'", "float3"});
  // Wrong size.
  k.inputs(x5, n10).outputs(y10);
  expect_error([&] { k.execute(); }, {"checked", "input 'x'", "5", "10"});
  k.inputs(x10, n5);
  expect_error([&] { k.execute(); }, {"checked", "input 'n'", "5", "10"});
  // Correct at last.
  k.inputs(x10, n10);
  EXPECT_EQ(k.execute(), 10);

  // Not compiled; unknown backend; empty program.
  Kernel none;
  expect_error([&] { none.execute(); }, {"compile"});
  expect_error([&] { rill::compile(p, "no-such-backend"); },
               {"no-such-backend", backend_name().c_str()});
  expect_error([&] { compile(Program()); }, {"empty"});
}

TEST_P(LaunchTest, OutputsOfDifferentSizes) {
  Program p = program("two_outputs", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> z("z");
    y = x;
    z = -x;
  });
  Kernel k = compile(p);
  Stream<Float> x(8), y(8), z(9);
  k.inputs(x).outputs(y, z);
  expect_error([&] { k.execute(); }, {"two_outputs", "'z'", "9", "8"});
}

// A kernel over a driver's limits is an error naming the kernel and the limit, not a driver
// crash or garbage: 40 arrays are more textures than GL contexts give a shader (llvmpipe
// and NVIDIA: 32), and 20 input streams more storage buffers than a compute shader gets
// (16). Backends without such limits run both kernels.
TEST_P(LaunchTest, KernelsOverADriversLimitsAreNamedErrors) {
  constexpr int kArrays = 40, kInputs = 20;
  std::vector<std::unique_ptr<Array<Float>>> arrays;
  for (int i = 0; i < kArrays; ++i)
    arrays.push_back(std::make_unique<Array<Float>>(std::vector<float>{static_cast<float>(i)},
                                                    "a" + std::to_string(i)));
  Program many_arrays = program("many_arrays", [&] {
    Output<Float> y("y");
    Float sum = 0.0f;
    for (auto& a : arrays) sum += (*a)[Int(0)];
    y = sum;
  });
  Program many_inputs = program("many_inputs", [&] {
    std::vector<std::unique_ptr<Input<Float>>> in;
    for (int i = 0; i < kInputs; ++i)
      in.push_back(std::make_unique<Input<Float>>("x" + std::to_string(i)));
    Output<Float> y("y");
    Float sum = 0.0f;
    for (auto& x : in) sum += *x;
    y = sum;
  });
  const bool gl = backend_name().rfind("glsl", 0) == 0;
  auto run_arrays = [&] {
    Kernel k = compile(many_arrays);
    Stream<Float> y(4);
    k.outputs(y).execute();
    return y.download()[3];
  };
  auto run_inputs = [&] {
    Kernel k = compile(many_inputs);
    std::vector<Stream<Float>> xs;
    for (int i = 0; i < kInputs; ++i) xs.emplace_back(std::vector<float>(4, 1.0f));
    Stream<Float> y(4);
    for (int i = 0; i < kInputs; ++i) k.bind("x" + std::to_string(i), xs[static_cast<size_t>(i)]);
    k.bind("y", y).execute();
    return y.download()[3];
  };
  // Vulkan: arrays are storage buffers, three more of which a kernel needs; the device's
  // limit is in the backend's description ("32 storage buffers" on lavapipe).
  bool vulkan_over = false;
  if (backend_name() == "vulkan") {
    const std::string d = rill::backend("vulkan").description();
    const size_t at = d.find(" storage buffers");
    ASSERT_NE(at, std::string::npos) << d;
    const size_t from = d.find_last_of(' ', at - 1) + 1;
    vulkan_over = std::stoi(d.substr(from, at - from)) < kArrays + 3;
  }
  if (gl)
    expect_error(run_arrays, {"many_arrays", "texture"});
  else if (vulkan_over)
    expect_error(run_arrays, {"many_arrays", "40 arrays", "maxPerStageDescriptorStorageBuffers"});
  else
    EXPECT_EQ(run_arrays(), 780.0f);  // 0 + 1 + ... + 39
  if (backend_name() == "glsl-compute")
    expect_error(run_inputs,
                 {"many_inputs", "20 input streams", "GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS"});
  else
    EXPECT_EQ(run_inputs(), static_cast<float>(kInputs));
}

RILL_BACKEND_TEST_SUITE(LaunchTest);

}  // namespace
}  // namespace rill::testing
