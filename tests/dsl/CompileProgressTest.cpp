// Kernel.h's compile observer and CompileProgressLine.h: what they report and print. No
// timing assertions: the line's delay is 0 or the test checks only what is never printed.
#include <cstdio>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "rill/CompileProgressLine.h"

namespace rill {
namespace {

// A program no other test compiles (the process cache would serve it silently).
Program unique_program(const std::string& name, float factor) {
  return program(name, [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float f = factor;
    y = x * f - 0.125f;
  });
}

// Records every report while it lives, and restores the observer it replaced.
struct Recorder {
  std::vector<CompileProgress> seen;
  CompileObserver previous =
      set_compile_observer([this](const CompileProgress& p) { seen.push_back(p); });
  ~Recorder() { set_compile_observer(std::move(previous)); }
};

std::string read_all(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  return s;
}

TEST(CompileProgressCpu, CompileAllReportsEachKernelAndTheEnd) {
  Recorder r;
  std::vector<Kernel> ks = compile_all({{unique_program("progress_a", 17.5f), "cpu"},
                                        {unique_program("progress_b", 18.5f), "cpu"},
                                        {unique_program("progress_c", 19.5f), "cpu"}});
  ASSERT_EQ(ks.size(), 3u);
  ASSERT_EQ(r.seen.size(), 5u);  // the start, three kernels, the end
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(r.seen[i].done, static_cast<int>(i));
    EXPECT_FALSE(r.seen[i].finished);
  }
  EXPECT_TRUE(r.seen[4].finished);
  EXPECT_EQ(r.seen[4].done, 3);
  for (const CompileProgress& p : r.seen) {
    EXPECT_EQ(p.total, 3);
    EXPECT_EQ(p.backend, "cpu");
  }
}

TEST(CompileProgressCpu, CompileIsABatchOfOneAndAProcessCacheHitReportsNothing) {
  Program p = unique_program("progress_single", 23.25f);
  Recorder r;
  compile(p, "cpu");
  ASSERT_EQ(r.seen.size(), 3u);
  EXPECT_EQ(r.seen[0].done, 0);
  EXPECT_EQ(r.seen[1].done, 1);
  EXPECT_TRUE(r.seen[2].finished);
  EXPECT_EQ(r.seen[2].total, 1);
  compile(p, "cpu");  // the in-process kernel cache: nothing to wait for
  EXPECT_EQ(r.seen.size(), 3u);
}

TEST(CompileProgressCpu, AFailedRequestStillEndsTheBatch) {
  Recorder r;
  EXPECT_THROW(compile_all({{unique_program("progress_ok", 29.5f), "cpu"},
                            {unique_program("progress_bad", 30.5f), "no-such-backend"}}),
               Error);
  ASSERT_FALSE(r.seen.empty());
  EXPECT_TRUE(r.seen.back().finished);
  EXPECT_EQ(r.seen.back().done, 2);
}

TEST(CompileProgressCpu, NothingIsPrintedWhereTheStreamIsNotATerminal) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    CompileProgressLine line(f, /*delay_ms=*/0);  // would draw at once on a terminal
    compile_all({{unique_program("progress_quiet_a", 31.5f), "cpu"},
                 {unique_program("progress_quiet_b", 32.5f), "cpu"}});
  }
  EXPECT_EQ(read_all(f), "");
  std::fclose(f);
  // It installed no observer, so there was none to restore or leave behind.
  CompileObserver none = set_compile_observer({});
  EXPECT_FALSE(none);
}

TEST(CompileProgressCpu, TheLineCountsKernelsAndEndsWithTheTotalTime) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Recorder r;  // the line passes reports on to the observer it replaced
  {
    CompileProgressLine line(f, /*delay_ms=*/0, CompileProgressLine::Where::Always);
    compile_all({{unique_program("progress_line_a", 33.5f), "cpu"},
                 {unique_program("progress_line_b", 34.5f), "cpu"}});
  }
  const std::string out = read_all(f);
  std::fclose(f);
  EXPECT_NE(out.find("compiling 2 kernels for cpu... 0/2"), std::string::npos) << out;
  EXPECT_NE(out.find("compiling 2 kernels for cpu... 2/2"), std::string::npos) << out;
  EXPECT_NE(out.find("compiled 2 kernels for cpu in "), std::string::npos) << out;
  EXPECT_EQ(out.back(), '\n');  // the line is finished, not left for the next output
  EXPECT_EQ(r.seen.size(), 4u);
}

TEST(CompileProgressCpu, TextNamesTheDriver) {
  CompileProgress p;
  p.backend = "opencl";
  p.driver = "PoCL";
  p.done = 3;
  p.total = 7;
  EXPECT_EQ(CompileProgressLine::text(p), "compiling 7 kernels for opencl (PoCL)... 3/7");
  p.finished = true;
  p.done = 7;
  p.elapsed_ms = 4210;
  EXPECT_EQ(CompileProgressLine::text(p), "compiled 7 kernels for opencl (PoCL) in 4.2 s");
  p.total = 1;
  p.driver.clear();
  EXPECT_EQ(CompileProgressLine::text(p), "compiled 1 kernel for opencl in 4.2 s");
}

}  // namespace
}  // namespace rill
