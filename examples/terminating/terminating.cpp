// The terminating kernel (thesis section 4.3): every element grows until it reaches 1.0.
//
//   rill-terminating [N] [BACKEND]      (exit status 77: the backend cannot run here)
//
// An element that has arrived discards: it writes nothing and is not counted, so the count
// execute() returns is the thesis's occlusion-query count, and Kernel::loop() re-runs the
// kernel until a pass writes nothing. The program checks both against a host simulation.
#include <rill/rill.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

using namespace rill;

// Passes in which element x is written, as the kernel below computes it.
static int64_t writes_until_one(float x, float rate) {
  int64_t k = 0;
  for (; x < 1.0f; ++k) x = std::min(x * rate, 1.0f);
  return k;
}

int main(int argc, char** argv) try {
  const int64_t n = argc > 1 ? std::atoll(argv[1]) : int64_t{1} << 20;
  const std::string backend_name = argc > 2 ? argv[2] : "cpu";
  if (n < 1) throw Error("N must be positive");
  if (std::string why = backend(backend_name).unavailable_reason(); !why.empty()) {
    std::fprintf(stderr, "rill-terminating: backend %s cannot run here: %s\n", backend_name.c_str(),
                 why.c_str());
    return 77;  // "skipped", for CTest
  }

  // --8<-- [README example]
  Uniform<Float> rate(2.0f, "rate");  // a host value: rate.set(3.0f) needs no recompile

  Program grow = program("grow", [&] {
    Input<Float> x("x");   // this element of the input stream
    Output<Float> y("y");  // this element of the output stream
    RILL_IF(x >= 1.0f) {
      RILL_DISCARD;  // arrived: write nothing, do not count
    }
    RILL_ENDIF;
    y = min(x * rate, 1.0f);
  });

  std::vector<float> start(static_cast<size_t>(n));
  for (int64_t i = 0; i < n; ++i) start[static_cast<size_t>(i)] = float(i + 1) / float(n);
  Stream<Float> values(start);

  Kernel k = compile(grow, backend_name);  // generated C, compiled and cached on disk
  k.inputs(values).outputs(values);        // in place: the output is also the next input
  int64_t passes = k.loop();               // re-run until a pass writes nothing
  std::printf("%lld elements reached 1.0 in %lld passes\n", (long long)n, (long long)passes);
  // --8<-- [end]

  // Expected: the slowest element's writes, plus the final pass that writes nothing.
  int64_t max_writes = 0;
  for (float x : start) max_writes = std::max(max_writes, writes_until_one(x, 2.0f));
  bool ok = passes == max_writes + 1;
  for (float v : values.download()) ok = ok && v == 1.0f;

  // The same loop by hand: execute() returns how many elements each pass wrote.
  rate.set(4.0f);  // faster growth, same compiled kernel
  values.upload(start);
  std::printf("by hand, rate 4: written per pass:");
  for (int64_t pass = 1;; ++pass) {
    int64_t written = k.execute();
    int64_t expected = 0;
    for (float x : start) expected += writes_until_one(x, 4.0f) >= pass ? 1 : 0;
    std::printf(" %lld", (long long)written);
    ok = ok && written == expected;
    if (written == 0 || pass > 1000) break;
  }
  std::printf("\ncompile %.1f ms (%s)\n", k.info().compile_ms,
              k.info().from_disk_cache ? "disk cache" : "compiled now");

  std::printf("%s\n", ok ? "OK" : "MISMATCH");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-terminating: %s\n", e.what());
  return 1;
}
