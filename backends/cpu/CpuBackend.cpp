#include "CpuBackend.h"

#include <dlfcn.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "CEmitter.h"
#include "LockstepEmitter.h"
#include "SharedObjectCache.h"
#include "rill/Parameters.h"
#include "rill/Stopwatch.h"

namespace rill::cpu {

namespace {

// RILL_THREADS=N caps the worker threads of the CPU backends (cpu, simd) for the whole
// process, through a oneTBB global_control kept until exit; unset, oneTBB's default (one per
// core). Results never depend on it (each element is computed alone); it is for sharing a
// machine and for the determinism tests.
void apply_thread_setting() {
  static const std::unique_ptr<tbb::global_control> limit =
      []() -> std::unique_ptr<tbb::global_control> {
    const char* v = std::getenv("RILL_THREADS");
    if (v == nullptr || *v == '\0') return nullptr;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (*end != '\0' || n < 1 || n > 4096)
      throw Error("RILL_THREADS='" + std::string(v).substr(0, 40) +
                  "' is not a thread count (1..4096)");
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                 static_cast<size_t>(n));
  }();
}

// Mirrors rill_launch in the generated C.
struct Launch {
  void* const* inputs;
  void* const* outputs;
  const uint32_t* uniforms;
  const void* const* arrays;
  const int64_t* array_shapes;
  int64_t count, width, height;
};
using RunFn = int64_t (*)(const Launch*, int64_t, int64_t);

// Masked launches run the unchanged kernel over each maximal run of consecutive selected
// elements, found here on the host: states are spatially coherent (neighbouring pixels tend
// to be in the same state), so runs are long, and the generated code pays nothing for the
// mask. (Testing the state inside the generated loop instead measured 5-10% slower on the
// multipass ray tracer than not masking at all; runs match it or beat it.)
struct Selection {
  const int32_t* mask;
  const std::vector<int32_t>& values;
  bool operator()(int64_t i) const {
    if (values.size() == 1) return mask[i] == values[0];
    for (int32_t v : values)
      if (mask[i] == v) return true;
    return false;
  }
};

class CpuKernel : public CompiledKernel {
 public:
  // lockstep: the kernel is emit_c_lockstep()'s, which indexes arrays with 32-bit lanes.
  CpuKernel(std::string source, SharedObject so, bool lockstep)
      : CompiledKernel(so.from_disk_cache),
        source_(std::move(source)),
        so_(std::move(so)),
        lockstep_(lockstep) {
    run_ = reinterpret_cast<RunFn>(so_.symbol);
  }
  ~CpuKernel() override { release(so_); }

  LaunchResult run(const LaunchArgs& a) override {
    // Members, so that launches reuse their memory (Kernel runs one launch at a time).
    auto& [in, out, arrays, shapes, uniforms] = scratch_;
    in.clear();
    out.clear();
    arrays.clear();
    shapes.clear();
    uniforms.clear();
    // The kernel only reads its inputs (rill_launch declares them void*, like the outputs).
    for (auto* s : a.inputs) in.push_back(const_cast<uint32_t*>(s->host_data_for_read()));
    for (auto* arr : a.arrays) {
      if (lockstep_ && arr->words() >= (size_t{1} << 31))
        throw Error("simd backend: array '" + arr->name + "' holds " +
                    std::to_string(arr->words()) +
                    " words; the lockstep kernels index arrays in 32 bits (under 2^31 words). Use "
                    "the cpu backend for arrays this large");
      arrays.push_back(arr->host_data_for_read());
      shapes.insert(shapes.end(), {arr->shape[0], arr->shape[1], arr->shape[2]});
    }
    const int32_t* mask = nullptr;
    if (a.mask) mask = reinterpret_cast<const int32_t*>(a.mask->host_data_for_read());
    // Here, not when the backend is made: a bad RILL_THREADS is an error of the launches that
    // would use it, not of the registry (which would take every backend down with it).
    apply_thread_setting();
    // Last, once nothing can throw before the kernel runs: asking for an output's host copy
    // to write makes its device copy stale. (A stream that is also an input was read back
    // above and stays current on the host.)
    for (auto* s : a.outputs) out.push_back(s->host_data_for_write());
    for (auto* u : a.uniforms) uniforms.insert(uniforms.end(), u->bits.begin(), u->bits.end());
    Launch L{in.data(),     out.data(), uniforms.data(), arrays.data(),
             shapes.data(), a.count,    a.width,         a.height};
    const Selection selected_at{mask, a.mask_values};

    // Ranges of about a thousand elements amortize the call and let TBB balance uneven work
    // (a Mandelbrot row inside the set costs far more than one outside). A small launch (a
    // 128 x 128 tile of a distributed render) gets smaller ranges, at least 16 per thread:
    // with 1024 a tile is 16 ranges, and 8 threads wait on its slowest few. Under a mask, each
    // range runs the kernel over its runs of selected elements (see Selection).
    struct Counts {
      int64_t written = 0, selected = 0;
    };
    const int64_t threads = std::max(1, tbb::this_task_arena::max_concurrency());
    const int64_t grain = std::clamp<int64_t>(a.count / (16 * threads), 64, 1024);
    // Ranges count units of `unit` elements: single elements, or, for the lockstep kernel on
    // an unmasked 2D stream, whole row pairs, which it runs in tiles of two rows
    // (rill_next_group).
    const bool row_pairs = lockstep_ && !mask && a.height >= 2 && a.width >= kLockstepLanes / 2 &&
                           a.count == a.width * a.height;
    const int64_t unit = row_pairs ? 2 * a.width : 1;
    const int64_t units = (a.count + unit - 1) / unit;
    const int64_t range_units = std::max<int64_t>(1, grain / unit);
    auto run_range = [&](const tbb::blocked_range<int64_t>& r, Counts acc) {
      if (!mask) {
        const int64_t begin = r.begin() * unit, end = std::min(r.end() * unit, a.count);
        acc.written += run_(&L, begin, end);
        acc.selected += end - begin;
        return acc;
      }
      for (int64_t i = r.begin(); i < r.end();) {
        while (i < r.end() && !selected_at(i)) ++i;
        int64_t j = i;
        while (j < r.end() && selected_at(j)) ++j;
        if (j > i) {
          acc.written += run_(&L, i, j);
          acc.selected += j - i;
        }
        i = j;
      }
      return acc;
    };
    // A launch of one range runs on the calling thread: TBB would only add its dispatch.
    const Stopwatch loop;
    if (units == 0) return {0, 0, 0.0};  // nothing ran
    if (units <= range_units) {
      const Counts c = run_range(tbb::blocked_range<int64_t>(0, units, range_units), Counts{});
      return {c.written, c.selected, loop.ms()};
    }
    Counts total =
        tbb::parallel_reduce(tbb::blocked_range<int64_t>(0, units, range_units), Counts{},
                             run_range, [](Counts x, Counts y) {
                               return Counts{x.written + y.written, x.selected + y.selected};
                             });
    return {total.written, total.selected, loop.ms()};
  }

  const std::string& source() const override { return source_; }

 private:
  std::string source_;
  SharedObject so_;
  RunFn run_ = nullptr;
  bool lockstep_;
  // The argument tables of a launch (see run()).
  struct Scratch {
    std::vector<void*> in, out;
    std::vector<const void*> arrays;
    std::vector<int64_t> shapes;
    std::vector<uint32_t> uniforms;
  } scratch_;
};

// `cpu` runs the scalar C of emit_c(), one element per iteration; `simd` runs the
// lockstep C of emit_c_lockstep(), kLockstepLanes elements per iteration in vector
// registers. Both give the same bits; which is faster depends on the kernel (see
// docs/backends.md).
class CpuBackend : public Backend {
 public:
  explicit CpuBackend(bool lockstep) : lockstep_(lockstep) {}

  std::string name() const override { return lockstep_ ? "simd" : "cpu"; }
  std::string description() const override {
    std::string what = lockstep_ ? "lockstep C, " + std::to_string(kLockstepLanes) + " lanes (" +
                                       vector_isa() + "), compiled by "
                                 : "generated C compiled by ";
    return name() + ": " + what + c_compiler() + ", " +
           std::to_string(
               tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)) +
           " threads (oneTBB), " +
           (profile_directory().empty()
                ? "cache " + cache_directory()
                : "profiling: kernels with debug information in " + profile_directory());
  }
  bool supports(Accuracy) const override { return true; }
  std::string accuracy_note(Accuracy a) const override {
    return lockstep_ && a == Accuracy::Double ? kScalarDouble : "";
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    // The double mode is the accuracy reference, not a speed mode: it runs as scalar C.
    const bool lockstep = lockstep_ && o.accuracy != Accuracy::Double;
    Stopwatch stage;
    std::string source = lockstep ? emit_c_lockstep(f, o.accuracy) : emit_c(f, o.accuracy);
    const double codegen_ms = stage.lap();
    std::vector<std::string> flags = compiler_flags(o.accuracy);
    if (lockstep && vector_isa() == "AVX2") flags.push_back("-mavx2");
    // Scalar code gains from SSE4.1's roundss: floor and ceil (every 3D-DDA start and jump)
    // are then one exact instruction instead of a conversion sequence; 3-4% on a ray traced
    // frame (docs/benchmarks/2026-11-25-gpu-frame.md).
    if (!lockstep && has_sse41()) flags.push_back("-msse4.1");
    SharedObject so = compile_shared_object(name(), f.name, source, flags, "rill_run");
    auto k = std::make_unique<CpuKernel>(std::move(source), std::move(so), lockstep);
    k->set_build_times(codegen_ms, stage.lap());
    if (lockstep_ && !lockstep) k->set_execution(kScalarDouble);
    return k;
  }

 private:
  // What simd's double mode is, until the lockstep code has binary64 lanes: the accuracy
  // reference, not a speed mode.
  static constexpr const char* kScalarDouble =
      "runs as scalar C, one element at a time, not in lanes (cpu's code)";
  // The widest vector instructions the lockstep code may use on this CPU. Only AVX2 is
  // asked for explicitly (8 binary32 lanes in one register); without it GCC splits each
  // vector into SSE2 halves. FMA is never enabled: contraction is off in strict mode anyway.
  static std::string vector_isa() {
    static const bool avx2 = __builtin_cpu_supports("avx2");
    return avx2 ? "AVX2" : "SSE2";
  }

  static bool has_sse41() {
    static const bool sse41 = __builtin_cpu_supports("sse4.1");
    return sse41;
  }

  bool lockstep_;
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

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<CpuBackend>(false);
}
std::unique_ptr<Backend> make_lockstep_backend() {
  return std::make_unique<CpuBackend>(true);
}

}  // namespace rill::cpu
