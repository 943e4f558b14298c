// Kernel::info(): the time of each compile stage and where the kernel came from, and
// compile_all(): concurrent compiles through the one kernel cache (Kernel.h).
#include <cstdlib>
#include <thread>

#include "TestUtil.h"

namespace rill {
namespace {

// A program no other test compiles: `tag` makes its IR (and so its cache keys) unique.
Program tagged(const std::string& name, float tag) {
  return program(name, [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float v = x;
    RILL_IF(v > 1.0f) {
      v = sqrt(v) + tag;
    }
    RILL_ENDIF;
    y = v * 2.0f + tag;
  });
}

std::vector<float> run_on(Kernel k, const std::vector<float>& xs) {
  Stream<Float> in(xs), out(static_cast<int64_t>(xs.size()));
  k.inputs(in).outputs(out);
  k.execute();
  return out.download();
}

TEST(CompileInfo, CaptureIsTimed) {
  Program p = tagged("captured", 1.0f);
  EXPECT_GT(p.capture_ms(), 0.0);
  Program q = tagged("captured_too", 2.0f);
  // A fused program's capture is both halves' and the fusion's.
  Program r = connect(p, program("after", [] {
                        Input<Float> y("y");
                        Output<Float> z("z");
                        z = y + 1.0f;
                      }));
  EXPECT_GT(r.capture_ms(), p.capture_ms());
  EXPECT_GT(q.capture_ms(), 0.0);
}

TEST(CompileInfoCpu, EveryStageThatRanIsTimed) {
  for (const char* be : {"cpu", "simd"}) {
    Program p = tagged("stages", 3.5f);
    clear_kernel_cache();
    Kernel k = compile(p, be);
    const CompileInfo& i = k.info();
    EXPECT_EQ(i.capture_ms, p.capture_ms()) << be;
    EXPECT_GT(i.optimize_ms, 0.0) << be;
    EXPECT_GT(i.codegen_ms, 0.0) << be;
    EXPECT_GT(i.backend_compile_ms, 0.0) << be;  // the C compiler, or loading the cached .so
    EXPECT_GE(i.driver_finish_ms, 0.0) << be;    // cpu defers nothing to the first launch
    EXPECT_GE(i.compile_ms,
              i.optimize_ms + i.codegen_ms + i.backend_compile_ms + i.driver_finish_ms)
        << be;
    EXPECT_FALSE(i.cache_hit) << be;
    EXPECT_EQ(i.origin, i.from_disk_cache ? KernelOrigin::DiskCache : KernelOrigin::Built) << be;
  }
}

TEST(CompileInfoCpu, AProcessCacheHitCostsNothingAndKeepsTheBuildsStages) {
  Program p = tagged("hit", 4.5f);
  Kernel a = compile(p);
  Program again = tagged("hit_again", 4.5f);  // identical IR, captured anew
  Kernel b = compile(again);
  EXPECT_EQ(b.info().origin, KernelOrigin::ProcessCache);
  EXPECT_TRUE(b.info().cache_hit);
  EXPECT_EQ(b.info().compile_ms, 0.0);
  EXPECT_EQ(b.info().capture_ms, again.capture_ms());  // its own program's capture
  EXPECT_EQ(b.info().optimize_ms, a.info().optimize_ms);
  EXPECT_EQ(b.info().codegen_ms, a.info().codegen_ms);
  EXPECT_EQ(b.info().backend_compile_ms, a.info().backend_compile_ms);
  EXPECT_STREQ(origin_name(b.info().origin), "process cache");
}

TEST(CompileAllCpu, GivesTheKernelsSequentialCompilesGive) {
  std::vector<Program> ps;
  for (int i = 0; i < 5; ++i) ps.push_back(tagged("all" + std::to_string(i), 10.0f + i));
  std::vector<CompileRequest> reqs;
  for (size_t i = 0; i < ps.size(); ++i) reqs.push_back({ps[i], i % 2 ? "simd" : "cpu"});
  CompileOptions fast;
  fast.accuracy = Accuracy::Fast;
  reqs.push_back({ps[0], "cpu", fast});

  clear_kernel_cache();
  std::vector<Kernel> together = compile_all(reqs);
  ASSERT_EQ(together.size(), reqs.size());
  std::vector<std::string> sources;
  for (const Kernel& k : together) sources.push_back(k.source());

  clear_kernel_cache();
  const std::vector<float> xs{-1.0f, 0.5f, 2.0f, 9.0f, 1e30f};
  for (size_t i = 0; i < reqs.size(); ++i) {
    Kernel alone = compile(reqs[i].program, reqs[i].backend, reqs[i].options);
    EXPECT_FALSE(alone.info().cache_hit) << i;
    EXPECT_EQ(together[i].program().name(), reqs[i].program.name()) << i;
    EXPECT_EQ(together[i].backend_name(), reqs[i].backend) << i;
    EXPECT_EQ(together[i].source(), alone.source()) << i;
    EXPECT_EQ(together[i].ir(), alone.ir()) << i;
    EXPECT_SAME_BITS(test::bits_of(run_on(together[i], xs)), test::bits_of(run_on(alone, xs)));
  }
}

TEST(CompileAllCpu, AnErrorNamesTheFailingProgram) {
  std::vector<CompileRequest> reqs{{tagged("fine", 20.0f), "cpu"},
                                   {tagged("misdirected", 21.0f), "no_such_backend"}};
  const std::string unknown = test::error_of([&] { compile_all(reqs); });
  EXPECT_HAS(unknown, "compile_all(): program 'misdirected' for backend 'no_such_backend'");
  EXPECT_HAS(unknown, "unknown backend 'no_such_backend'");

  // A failing compiler: the error is the backend's, prefixed with the program.
  const char* old = std::getenv("RILL_CC");
  std::string saved = old ? old : "";
  setenv("RILL_CC", "/nonexistent/rill-cc", 1);
  std::vector<CompileRequest> broken{{tagged("also_fine", 22.0f), "simd"},
                                     {tagged("uncompilable", 23.0f), "cpu"}};
  clear_kernel_cache();
  const std::string failed = test::error_of([&] { compile_all(broken); });
  EXPECT_HAS(failed, "compile_all(): program 'also_fine' for backend 'simd'");  // first in order
  EXPECT_HAS(failed, "the C compiler '/nonexistent/rill-cc' could not be run");
  if (old)
    setenv("RILL_CC", saved.c_str(), 1);
  else
    unsetenv("RILL_CC");
  // A failed build leaves no cache entry: the next compile builds it.
  Kernel k = compile(broken[1].program, "cpu");
  EXPECT_FALSE(k.info().cache_hit);
}

TEST(CompileAllCpu, ConcurrentCompilesOfOneProgramBuildItOnce) {
  Program p = tagged("once", 30.0f);
  clear_kernel_cache();
  std::vector<Kernel> ks = compile_all(std::vector<CompileRequest>(6, CompileRequest{p, "cpu"}));
  EXPECT_EQ(kernel_cache_stats().misses, 1);
  EXPECT_EQ(kernel_cache_stats().hits, 5);
  int built = 0;
  for (const Kernel& k : ks) {
    built += !k.info().cache_hit;
    EXPECT_EQ(&k.source(), &ks[0].source());  // one compiled kernel, shared
  }
  EXPECT_EQ(built, 1);

  // compile() from threads of the caller's own.
  clear_kernel_cache();
  std::vector<Kernel> mine(4);
  std::vector<std::thread> threads;
  for (Kernel& k : mine) threads.emplace_back([&k, &p] { k = compile(p, "simd"); });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(kernel_cache_stats().misses, 1);
  EXPECT_EQ(kernel_cache_stats().hits, 3);
  for (const Kernel& k : mine) EXPECT_EQ(&k.source(), &mine[0].source());
  EXPECT_SAME_BITS(test::bits_of(run_on(mine[3], {2.0f, 3.0f})),
                   test::bits_of(run_on(ks[0], {2.0f, 3.0f})));
}

}  // namespace
}  // namespace rill
