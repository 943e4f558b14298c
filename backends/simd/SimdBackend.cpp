// The simd backend (SimdBackend.h).
#include "SimdBackend.h"

#include <memory>
#include <string>
#include <vector>

#include "../codegen/SourceMap.h"
#include "../cpu/CpuBackend.h"
#include "../cpu/HostKernel.h"
#include "../cpu/SharedObjectCache.h"
#include "LockstepEmitter.h"
#include "rill/Stopwatch.h"

namespace rill::simd {

namespace {

// What the double mode is here, until the lockstep code has binary64 lanes.
constexpr const char* kScalarDouble =
    "runs as scalar C, one element at a time, not in lanes (cpu's code)";

// The widest vector instructions the lockstep code may use on this CPU. Only AVX2 is asked
// for explicitly (8 binary32 lanes in one register); without it GCC splits each vector into
// SSE2 halves. FMA is never enabled: contraction is off in strict mode anyway.
std::string vector_isa() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2 ? "AVX2" : "SSE2";
}

// Whether strict kernels also get AVX-512 (F, VL, BW, DQ). The lanes stay 8 binary32 in
// 256-bit registers, but AVX-512VL gives 32 of them instead of 16, mask registers and
// three-input logic: a lockstep kernel keeps hundreds of vectors live, and the ray tracer's
// traversal spilled a third fewer of them (docs/benchmarks/2026-12-07-simd-gathers.md).
// The same IEEE operations in the same order, so the same bits. Not for `fast`: with
// AVX-512F GCC contracts a * b + c into FMA under -ffp-contract=fast, and FMA stays off.
bool avx512_registers(Accuracy a) {
  static const bool have = vector_isa() == "AVX2" && __builtin_cpu_supports("avx512f") &&
                           __builtin_cpu_supports("avx512vl") &&
                           __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
  return have && a == Accuracy::Strict;
}

class SimdBackend : public Backend {
 public:
  std::string name() const override { return "simd"; }
  std::string description() const override {
    const std::string isa =
        vector_isa() +
        (avx512_registers(Accuracy::Strict) ? "; AVX-512VL registers in strict" : "");
    return cpu::host_backend_description(name(), "lockstep C, " + std::to_string(kLockstepLanes) +
                                                     " lanes (" + isa + "), compiled by ");
  }
  bool supports(Accuracy) const override { return true; }
  std::string accuracy_note(Accuracy a) const override {
    return a == Accuracy::Double ? kScalarDouble : "";
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    if (o.accuracy == Accuracy::Double) {
      auto k = cpu::compile_scalar_c(name(), f, o.accuracy, o.source_map);
      k->set_execution(kScalarDouble);
      return k;
    }
    Stopwatch stage;
    std::string source = emit_c_lockstep(f, o.accuracy, kLockstepLanes, o.source_map);
    const double codegen_ms = stage.lap();
    std::vector<std::string> flags = cpu::compiler_flags(o.accuracy);
    if (vector_isa() == "AVX2") flags.push_back("-mavx2");
    if (avx512_registers(o.accuracy))
      flags.insert(flags.end(), {"-mavx512f", "-mavx512vl", "-mavx512bw", "-mavx512dq"});
    cpu::SharedObject so = codegen::reporting_user_lines(
        source, [&] { return emit_c_lockstep(f, o.accuracy, kLockstepLanes, true); },
        [&] { return cpu::compile_shared_object(name(), f.name, source, flags, "rill_run"); });
    auto k = cpu::make_host_kernel(std::move(source), std::move(so), kLockstepLanes);
    k->set_build_times(codegen_ms, stage.lap());
    return k;
  }
};

}  // namespace

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<SimdBackend>();
}

}  // namespace rill::simd
