// Kernel.h: compiled kernels are cached by (IR hash, backend, options).
#include "TestUtil.h"

namespace rill {
namespace {

Program scale(const std::string& name, float factor) {
  return program(name, [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float f = factor;
    y = x * f + 0.25f;
  });
}

TEST(KernelCacheCpu, CompilingTheSameProgramTwiceHits) {
  Program p = scale("cache_twice", 3.0f);
  CacheStats before = kernel_cache_stats();
  Kernel a = compile(p);
  CacheStats mid = kernel_cache_stats();
  EXPECT_EQ(mid.misses, before.misses + 1);
  EXPECT_EQ(mid.hits, before.hits);
  EXPECT_FALSE(a.info().cache_hit);
  Kernel b = compile(p);
  CacheStats after = kernel_cache_stats();
  EXPECT_EQ(after.hits, mid.hits + 1);
  EXPECT_EQ(after.misses, mid.misses);
  EXPECT_TRUE(b.info().cache_hit);
  EXPECT_EQ(b.info().compile_ms, 0.0);
  EXPECT_EQ(&a.source(), &b.source());  // one compiled kernel, shared
  EXPECT_EQ(b.backend_name(), "cpu");
}

TEST(KernelCacheCpu, AnIdenticalProgramDefinedAgainHits) {
  Kernel a = compile(scale("first_name", 5.0f));
  CacheStats mid = kernel_cache_stats();
  Kernel b = compile(scale("another_name", 5.0f));  // same IR; the name is not part of it
  CacheStats after = kernel_cache_stats();
  EXPECT_EQ(after.hits, mid.hits + 1);
  EXPECT_EQ(after.misses, mid.misses);
  EXPECT_TRUE(b.info().cache_hit);
  EXPECT_EQ(b.program().name(), "another_name");

  Stream<Float> in(std::vector<float>{1.0f, 2.0f});
  Stream<Float> out(2);
  b.inputs(in).outputs(out);
  b.execute();
  EXPECT_EQ(out.download(), (std::vector<float>{5.25f, 10.25f}));
}

// A kernel served from the cache shows its own program's IR, under its own name.
TEST(KernelCacheCpu, ACachedKernelShowsItsOwnName) {
  Kernel a = compile(scale("original", 6.0f));
  Kernel b = compile(scale("renamed", 6.0f));
  ASSERT_TRUE(b.info().cache_hit);
  EXPECT_EQ(test::lines(a.ir())[0].rfind("kernel original(", 0), 0u) << a.ir();
  EXPECT_EQ(test::lines(b.ir())[0].rfind("kernel renamed(", 0), 0u) << b.ir();
}

TEST(KernelCacheCpu, DifferentOptionsOrProgramsMiss) {
  Program p = scale("opts", 7.0f);
  compile(p);
  CacheStats base = kernel_cache_stats();
  CompileOptions no_fold;
  no_fold.passes.constant_folding = false;
  Kernel k1 = compile(p, "cpu", no_fold);
  EXPECT_FALSE(k1.info().cache_hit);
  CompileOptions fast;
  fast.accuracy = Accuracy::Fast;
  compile(p, "cpu", fast);
  CompileOptions dbl;
  dbl.accuracy = Accuracy::Double;
  compile(p, "cpu", dbl);
  compile(scale("opts", 7.5f));  // another constant, another kernel
  CacheStats after = kernel_cache_stats();
  EXPECT_EQ(after.misses, base.misses + 4);
  EXPECT_EQ(after.hits, base.hits);
  compile(p, "cpu", no_fold);  // and each of those is cached in turn
  EXPECT_EQ(kernel_cache_stats().hits, after.hits + 1);
}

TEST(KernelCacheCpu, ClearingEmptiesTheCacheAndItsCounts) {
  Program p = scale("clear", 9.0f);
  compile(p);
  clear_kernel_cache();
  EXPECT_EQ(kernel_cache_stats().hits, 0);
  EXPECT_EQ(kernel_cache_stats().misses, 0);
  Kernel k = compile(p);
  EXPECT_FALSE(k.info().cache_hit);
  EXPECT_EQ(kernel_cache_stats().misses, 1);
}

// Identical programs share compiled code, but each kernel reads its own program's uniforms.
TEST(KernelCacheCpu, ACachedKernelReadsItsOwnProgramsUniforms) {
  Uniform<Float> g1(2.0f, "gain"), g2(3.0f, "gain");
  auto make = [](const Uniform<Float>& g) {
    return program("gain", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = x * g;
    });
  };
  Kernel k1 = compile(make(g1));
  Kernel k2 = compile(make(g2));
  EXPECT_TRUE(k2.info().cache_hit);
  Stream<Float> in(std::vector<float>{1.0f, 10.0f});
  Stream<Float> o1(2), o2(2);
  k1.inputs(in).outputs(o1).execute();
  k2.inputs(in).outputs(o2).execute();
  EXPECT_EQ(o1.download(), (std::vector<float>{2.0f, 20.0f}));
  EXPECT_EQ(o2.download(), (std::vector<float>{3.0f, 30.0f}));
  g2.set(4.0f);  // no recompile needed
  k2.execute();
  EXPECT_EQ(o2.download(), (std::vector<float>{4.0f, 40.0f}));
}

// Two arrays with the same (default) name: programs that gather from different ones must
// not share a cache entry (see HashTest.GathersFromDifferentArraysWithTheSameName).
TEST(KernelCacheCpu, ProgramsGatheringFromSameNamedArraysGetTheirOwnCode) {
  Array<Float> a(std::vector<float>{1.0f, 2.0f, 3.0f});
  Array<Float> b(std::vector<float>{10.0f, 20.0f, 30.0f});
  auto make = [&](bool last_from_a) {
    return program("g", [&] {
      Input<Int> i("i");
      Output<Float> y("y");
      Float first = a[i];
      Float second = b[i];
      Int j = i + 1;
      Float third = last_from_a ? a[j] : b[j];
      y = first + second + third;
    });
  };
  auto ra = test::run_cpu<Float, Int>(make(true), {}, {0, 1});
  auto rb = test::run_cpu<Float, Int>(make(false), {}, {0, 1});
  EXPECT_EQ(ra, (std::vector<float>{1.0f + 10.0f + 2.0f, 2.0f + 20.0f + 3.0f}));
  EXPECT_EQ(rb, (std::vector<float>{1.0f + 10.0f + 20.0f, 2.0f + 20.0f + 30.0f}));
}

// The kernel's name ends up in generated code (a comment, a symbol name...); any name a
// user may pass to program() must still compile.
TEST(KernelCacheCpu, AnyKernelNameCompiles) {
  // Each program adds its own constant: identical IR would be served from the cache.
  float k = 1000.0f;
  for (const char* name :
       {"plain", "with space", "quote'n\"dq", "star */ slash", "new\nline", "back\\slash"}) {
    SCOPED_TRACE(name);
    k += 1.0f;
    Program p = program(name, [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = x + k;
    });
    std::string msg = test::error_of([&] {
      auto r = test::run_cpu<Float, Float>(p, {}, {1.0f});
      if (r[0] != k + 1.0f) throw Error("wrong result");
    });
    EXPECT_EQ(msg.substr(0, 300), "<no rill::Error thrown>");
  }
}

}  // namespace
}  // namespace rill
