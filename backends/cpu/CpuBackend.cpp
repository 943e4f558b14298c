// The cpu backend (CpuBackend.h): scalar C, one element per iteration of the kernel's loop.
#include "CpuBackend.h"

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <memory>

#include "../codegen/SourceMap.h"
#include "CEmitter.h"
#include "HostKernel.h"
#include "Outline.h"
#include "SharedObjectCache.h"
#include "rill/Error.h"
#include "rill/Stopwatch.h"

namespace rill::cpu {

namespace {

class CpuBackend : public Backend {
 public:
  std::string name() const override { return "cpu"; }
  std::string description() const override {
    return host_backend_description(name(), "generated C compiled by ");
  }
  bool supports(Accuracy) const override { return true; }
  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    return compile_scalar_c(name(), f, o.accuracy, o.source_map);
  }
};

}  // namespace

std::vector<std::string> compiler_flags(Accuracy a) {
  std::vector<std::string> f{
      "-std=c99", "-O2", "-fPIC", "-shared", "-fno-math-errno", "-fwrapv", "-fno-strict-aliasing",
      // GCC 12.2 (Debian 12) miscompiles long chains of int max over selects with its SLP
      // vectorizer at -O2: the unrolled block fold of rill::any returned 0 for a block whose
      // first element was set (ReduceTest.IntegersWrapAndTruthValuesCount). Kernels are
      // scalar code per element, so SLP gains little; clang accepts the flag too.
      "-fno-tree-slp-vectorize", "-w"};
  if (a == Accuracy::Fast) {
    // -ffast-math's parts, spelled out: the option itself would also link crtfastmath.o,
    // which turns on flush-to-zero for the whole process, strict kernels included.
    // (-fcx-limited-range, the last part, concerns complex arithmetic, which kernels never
    // use, and clang 14 rejects it.)
    f.insert(f.end(),
             {"-fno-trapping-math", "-fno-signed-zeros", "-fassociative-math", "-freciprocal-math",
              "-ffinite-math-only", "-fno-rounding-math", "-ffp-contract=fast"});
#if defined(__x86_64__) || defined(__i386__)
    // No hardware reciprocal estimates: with the flags above clang computes 1 / sqrt(x) as
    // rsqrtss plus one Newton step (2.2 ulp measured, over the cpu column's 2 ulp bound in
    // conformance/Bounds.cpp), while GCC keeps sqrt and a division unless told otherwise.
    // Both accept -mrecip=none, so fast kernels mean the same with either compiler.
    f.push_back("-mrecip=none");
#endif
  } else {
    f.insert(f.end(), {"-fno-fast-math", "-ffp-contract=off", "-fexcess-precision=standard"});
  }
  return f;
}

bool has_sse41() {
  static const bool sse41 = __builtin_cpu_supports("sse4.1");
  return sse41;
}

CLayout c_layout() {
  CLayout layout{.outline_min_cost = kOutlineMinCost, .max_units = 4};
  layout.cold_units = true;
  const char* knob = std::getenv("RILL_CPU_OUTLINE");
  if (!knob || !*knob) return layout;
  const std::string v = knob;
  if (v == "off") return CLayout{};
  // COST or COST:UNIT_COST, both at least 1.
  auto bad = [&] {
    return Error(
        "RILL_CPU_OUTLINE: expected off, COST or COST:UNIT_COST (numbers of at least 1), "
        "got '" +
        v + "'");
  };
  auto number = [&](const char* from, char** end) {
    if (!std::isdigit(static_cast<unsigned char>(*from))) throw bad();
    errno = 0;
    const unsigned long long n = std::strtoull(from, end, 10);
    if (n == 0 || errno != 0) throw bad();
    return static_cast<size_t>(n);
  };
  char* end = nullptr;
  layout.outline_min_cost = number(knob, &end);
  if (*end == ':') layout.unit_cost = number(end + 1, &end);
  if (*end != 0) throw bad();
  return layout;
}

std::unique_ptr<CompiledKernel> compile_scalar_c(const std::string& backend, const ir::Function& f,
                                                 Accuracy a, bool source_map) {
  Stopwatch stage;
  CLayout layout = c_layout();
  layout.source_map = source_map;
  std::string source = emit_c(f, a, layout);
  const double codegen_ms = stage.lap();
  std::vector<std::string> flags = compiler_flags(a);
  // Scalar code gains from SSE4.1's roundss: floor and ceil (every 3D-DDA start and jump)
  // are then one exact instruction instead of a conversion sequence; 3-4% on a ray traced
  // frame (docs/benchmarks/2026-11-25-gpu-frame.md).
  if (has_sse41()) flags.push_back("-msse4.1");
  CLayout mapped = layout;
  mapped.source_map = true;
  SharedObject so = codegen::reporting_user_lines(
      source, [&] { return emit_c(f, a, mapped); },
      [&] {
        return compile_shared_object(backend, f.name, source, flags, "rill_run", c_units(source),
                                     c_cold_units(source));
      });
  auto k = make_host_kernel(std::move(source), std::move(so), 0);
  k->set_build_times(codegen_ms, stage.lap());
  return k;
}

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<CpuBackend>();
}

}  // namespace rill::cpu
