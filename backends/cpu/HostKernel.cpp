// The host launcher of the CPU backends (HostKernel.h): a kernel's shared object, run over
// ranges of elements on oneTBB's worker threads.
#include "HostKernel.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_arena.h>

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

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
// The lockstep kernel's compacted entry: positions [begin, end) of a list of element indices.
using RunListFn = int64_t (*)(const Launch*, const int64_t*, int64_t, int64_t);

// RILL_SIMD_COMPACT=off runs the simd backend's masked launches over runs of the mask, as
// before compaction (for comparing the two; the images are the same either way).
bool compaction_enabled() {
  static const bool on = [] {
    const char* v = std::getenv("RILL_SIMD_COMPACT");
    if (v == nullptr || *v == '\0' || std::string(v) == "on") return true;
    if (std::string(v) == "off") return false;
    throw Error("RILL_SIMD_COMPACT='" + std::string(v).substr(0, 40) + "': expected on or off");
  }();
  return on;
}

// Masked launches run the unchanged kernel over each maximal run of consecutive selected
// elements, found here on the host: states are spatially coherent (neighbouring pixels tend
// to be in the same state), so runs are long, and the generated code pays nothing for the
// mask. (Testing the state inside the generated loop instead measured 5-10% slower on the
// multipass ray tracer than not masking at all; runs match it or beat it.)
// The lockstep kernels (simd) compact instead: a run shorter than the lanes leaves lanes idle
// and pays a call, and after a few bounces of the wavefront the live paths are scattered in
// short runs. Each range collects its selected elements' indices into a dense list and the
// kernel's lanes take them RILL_W at a time (rill_run_list). Every element still computes
// exactly its own operations, so the results are bit for bit those of the runs.
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

class HostKernel : public CompiledKernel {
 public:
  // lanes: 0 for scalar C (emit_c), else the lockstep kernel's lanes (simd's
  // emit_c_lockstep, which runs unmasked 2D launches in tiles and indexes arrays with
  // 32-bit lanes).
  HostKernel(std::string source, SharedObject so, int lanes)
      : CompiledKernel(so.from_disk_cache),
        source_(std::move(source)),
        so_(std::move(so)),
        lanes_(lanes) {
    run_ = reinterpret_cast<RunFn>(so_.symbol);
    // Absent for a kernel with group operations (LockstepEmitter.cpp) and for scalar C.
    if (lanes_ > 0) run_list_ = reinterpret_cast<RunListFn>(dlsym(so_.handle, "rill_run_list"));
  }
  ~HostKernel() override { release(so_); }

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
      if (lanes_ > 0 && arr->words() >= (size_t{1} << 31))
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
    const RunListFn run_list = mask && run_list_ && compaction_enabled() ? run_list_ : nullptr;
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
    // an unmasked 2D stream, whole tile rows (lockstep_tile_rows rows), which it runs in tiles
    // (rill_next_group, which checks the same condition).
    const int tile_rows = lockstep_tile_rows(lanes_);
    const bool tiled = lanes_ > 0 && !mask && a.height >= 2 && a.width >= lanes_ / tile_rows &&
                       a.count == a.width * a.height;
    const int64_t unit = tiled ? tile_rows * a.width : 1;
    const int64_t units = (a.count + unit - 1) / unit;
    const int64_t range_units = std::max<int64_t>(1, grain / unit);
    auto run_range = [&](const tbb::blocked_range<int64_t>& r, Counts acc) {
      if (!mask) {
        const int64_t begin = r.begin() * unit, end = std::min(r.end() * unit, a.count);
        acc.written += run_(&L, begin, end);
        acc.selected += end - begin;
        return acc;
      }
      if (run_list) {
        // One list per thread, reused by its ranges (a range is at most `grain` elements).
        thread_local std::vector<int64_t> list;
        list.clear();
        for (int64_t i = r.begin(); i < r.end(); ++i)
          if (selected_at(i)) list.push_back(i);
        if (!list.empty()) {
          const auto n = static_cast<int64_t>(list.size());
          acc.written += run_list(&L, list.data(), 0, n);
          acc.selected += n;
        }
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
  RunListFn run_list_ = nullptr;
  int lanes_;
  // The argument tables of a launch (see run()).
  struct Scratch {
    std::vector<void*> in, out;
    std::vector<const void*> arrays;
    std::vector<int64_t> shapes;
    std::vector<uint32_t> uniforms;
  } scratch_;
};

}  // namespace

std::unique_ptr<CompiledKernel> make_host_kernel(std::string source, SharedObject so, int lanes) {
  return std::make_unique<HostKernel>(std::move(source), std::move(so), lanes);
}

std::string host_backend_description(const std::string& name, const std::string& what) {
  return name + ": " + what + c_compiler() + ", " +
         std::to_string(
             tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)) +
         " threads (oneTBB), " +
         (profile_directory().empty()
              ? "cache " + cache_directory()
              : "profiling: kernels with debug information in " + profile_directory());
}

}  // namespace rill::cpu
