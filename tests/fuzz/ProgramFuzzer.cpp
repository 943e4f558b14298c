// libFuzzer target: the capture, verify, optimize and interpret pipeline, on random programs
// from the differential tests' generator (tests/differential/Generator.h).
//
// Input bytes: the first 8 are the program's seed (little-endian; fewer are zero-padded).
// Each following pair of bytes is an edit the shrinker could make: the first byte's low bit
// says whether to drop a statement or to generate an expression as a leaf, and the second
// picks which (modulo the count). So mutating the seed gives a new program, and mutating the
// rest gives smaller programs made of the same parts, which libFuzzer's coverage feedback
// can tell apart.
//
// The oracle: capture and every pass must not throw, the optimized program must verify, and
// the reference interpreter must give the same bits for the program optimized, with every
// pass off, and lowered for lockstep lanes (the simd backend's lowering). Any failure aborts
// with the harness's report (the seed, the IR and the first difference).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include "../differential/Harness.h"

using namespace rill::difftest;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  ProgramSpec spec;
  for (size_t i = 0; i < 8 && i < size; ++i) spec.seed |= uint64_t{data[i]} << (8 * i);
  if (size > 8) {
    std::vector<GenTrace> traces;
    build_program({spec}, &traces);
    const GenTrace& t = traces.at(0);
    for (size_t i = 8; i + 1 < size; i += 2) {
      const bool leaf = (data[i] & 1) != 0;
      const std::vector<uint64_t>& ids = leaf ? t.exprs : t.stmts;
      if (ids.empty()) continue;
      (leaf ? spec.edits.leaves : spec.edits.dropped).insert(ids[data[i + 1] % ids.size()]);
    }
  }
  Options opt;  // no targets: the reference alone, and its cross-checks
  opt.check_unoptimized = true;
  opt.check_lockstep = true;
  Stats stats;
  const std::vector<Failure> failures = run_batch({spec}, opt, stats);
  if (!failures.empty()) {
    std::fprintf(stderr, "%s\n%s\n", failures[0].title().c_str(),
                 report_failure({spec}, failures[0], opt, /*shrink=*/false, 0, stats, "").c_str());
    std::abort();
  }
  return 0;
}
