// The simd backend (SimdBackend.h).
#include "SimdBackend.h"

#include <cstdlib>
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

// Whether strict kernels also get AVX-512 (F, VL, BW, DQ): 16 lanes in 512-bit registers
// (lockstep_lanes below; 8 in 256-bit ones with RILL_SIMD_LANES=8, where AVX-512VL still gives
// 32 registers instead of 16, mask registers and
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

// The lanes of a lockstep kernel: 16 (one AVX-512 register of binary32) for strict kernels
// where the CPU has AVX-512 (avx512_registers), else 8. RILL_SIMD_LANES=8 or 16 asks for
// one (16 is granted only where the rule above allows it; elsewhere 8), `auto` or unset
// is the rule; read per compile, so that a program can measure both.
int lockstep_lanes(Accuracy a) {
  const bool wide = avx512_registers(a);
  const char* v = std::getenv("RILL_SIMD_LANES");
  const std::string s = v ? v : "auto";
  if (s == "auto") return wide ? kWideLanes : kLockstepLanes;
  if (s == "8") return kLockstepLanes;
  if (s == "16") return wide ? kWideLanes : kLockstepLanes;
  throw Error("RILL_SIMD_LANES='" + s.substr(0, 40) + "': expected 8, 16 or auto");
}

class SimdBackend : public Backend {
 public:
  std::string name() const override { return "simd"; }
  // A bad RILL_SIMD_LANES makes the backend unavailable with the reason (rill-info lists it),
  // and compiling on it an error that says the same.
  std::string unavailable_reason() const override {
    try {
      lockstep_lanes(Accuracy::Strict);
    } catch (const Error& e) {
      return e.what();
    }
    return {};
  }
  std::string description() const override {
    const int strict = lockstep_lanes(Accuracy::Strict), fast = lockstep_lanes(Accuracy::Fast);
    std::string lanes = std::to_string(strict) + " lanes (" + vector_isa() + ")";
    if (avx512_registers(Accuracy::Strict))
      lanes = strict == fast
                  ? std::to_string(strict) + " lanes (AVX2; AVX-512VL registers in strict)"
                  : std::to_string(strict) + " lanes in strict (AVX-512), " + std::to_string(fast) +
                        " in fast (AVX2)";
    return cpu::host_backend_description(name(), "lockstep C, " + lanes + ", compiled by ");
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
    const int lanes = lockstep_lanes(o.accuracy);
    std::string source = emit_c_lockstep(f, o.accuracy, lanes, o.source_map);
    const double codegen_ms = stage.lap();
    std::vector<std::string> flags = cpu::compiler_flags(o.accuracy);
    if (vector_isa() == "AVX2") flags.push_back("-mavx2");
    if (avx512_registers(o.accuracy))
      flags.insert(flags.end(), {"-mavx512f", "-mavx512vl", "-mavx512bw", "-mavx512dq"});
    cpu::SharedObject so = codegen::reporting_user_lines(
        source, [&] { return emit_c_lockstep(f, o.accuracy, lanes, true); },
        [&] { return cpu::compile_shared_object(name(), f.name, source, flags, "rill_run"); });
    auto k = cpu::make_host_kernel(std::move(source), std::move(so), lanes);
    k->set_build_times(codegen_ms, stage.lap());
    return k;
  }
};

}  // namespace

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<SimdBackend>();
}

}  // namespace rill::simd
