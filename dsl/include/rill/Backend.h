// The interface every backend implements (the options a compile takes are in Options.h).
//
// A backend turns an optimized Function into something it can launch (CompiledKernel), and
// moves stream and array data between the host and its device. Backends register by name;
// rill::backend("cpu") finds one. A backend that cannot run on this machine (no OpenCL
// platform, no GL context) stays registered and says why in unavailable_reason().
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rill/Options.h"
#include "rill/Stream.h"
#include "rill/ir/IR.h"

namespace rill {

namespace detail {
struct UniformState;
}

// Everything a launch needs, resolved and checked by Kernel.
struct LaunchArgs {
  std::vector<detail::StreamState*> inputs;   // parallel to Function::inputs
  std::vector<detail::StreamState*> outputs;  // parallel to Function::outputs
  std::vector<const detail::UniformState*> uniforms;
  std::vector<detail::ArrayState*> arrays;
  int64_t count = 0;              // elements to run
  int64_t width = 0, height = 1;  // domain shape (of the first output)
  // A masked launch (StateMask.h): run only elements i whose mask value is in mask_values.
  // Null: every element. Checked by Kernel: an Int stream of `count` elements, 1 to
  // StateMask::kMaxValues values.
  detail::StreamState* mask = nullptr;
  std::vector<int32_t> mask_values;
  // A warm-up (CompiledKernel::warm_up): count is 0, yet the backend goes as far as the
  // driver's launch, so that the driver compiles what it defers to the first one.
  bool warm_up = false;
};

// What one run() did, returned to Kernel (which reports it as LaunchStats).
struct LaunchResult {
  int64_t written = 0;   // elements written (not discarded)
  int64_t selected = 0;  // elements run: those the mask selected, or count without a mask
  // How long the kernel ran, as the device timed it: OpenCL's profiling event, a GL timer
  // query, or the CPU backends' parallel loop. -1 where the backend cannot tell.
  double device_ms = -1;
};

// Where a compiled kernel came from (reported by Kernel::info().origin).
enum class KernelOrigin : uint8_t {
  Built,         // source generated and compiled by this process
  ProcessCache,  // an identical kernel compiled earlier in this process (Kernel.h)
  DiskCache,     // a binary Rill stored on disk in an earlier process
  DriverCache,   // compiled from source, but the driver served it from a cache of its own
};
const char* origin_name(KernelOrigin o);  // "built", "process cache", "disk cache", "driver cache"

// What a backend's compile() spent, in milliseconds, and where the kernel came from.
// Backends fill it in; rill::compile() adds capture, optimization and warm_up() (which it
// times itself) and reports it all as CompileInfo.
struct BuildReport {
  double codegen_ms = 0;  // emitting the backend's source
  double compile_ms = 0;  // the backend compile (C compiler, clBuildProgram, glLinkProgram),
                          // or loading a cached binary
  KernelOrigin origin = KernelOrigin::Built;
  // How the kernel runs where that is not what its backend's name says (simd's double
  // kernels: scalar C, one element at a time); empty otherwise.
  std::string execution;
};

class CompiledKernel {
 public:
  virtual ~CompiledKernel() = default;
  // Runs the kernel over all elements (or those args.mask selects).
  virtual LaunchResult run(const LaunchArgs& args) = 0;
  // The generated source (C, OpenCL C, GLSL...).
  virtual const std::string& source() const = 0;
  // Makes the driver finish whatever it defers to the first launch (PoCL and Mesa compile the
  // final machine code then), so that a compiled kernel is ready to run. Called once by
  // rill::compile(), which times it (CompileInfo::driver_finish_ms). Backends without such
  // work (cpu) keep the default.
  virtual void warm_up() {}
  const BuildReport& report() const { return report_; }
  // Set by the backend's compile() once the kernel exists: the time its two steps took.
  void set_build_times(double codegen_ms, double compile_ms) {
    report_.codegen_ms = codegen_ms;
    report_.compile_ms = compile_ms;
  }
  void set_origin(KernelOrigin origin) { report_.origin = origin; }
  void set_execution(std::string how) { report_.execution = std::move(how); }
  // Whether the backend reused a binary compiled earlier (a disk cache) instead of compiling.
  bool from_disk_cache() const { return report_.origin == KernelOrigin::DiskCache; }

 protected:
  CompiledKernel() = default;
  explicit CompiledKernel(bool from_disk_cache) {
    if (from_disk_cache) report_.origin = KernelOrigin::DiskCache;
  }
  BuildReport report_;
};

class Backend {
 public:
  virtual ~Backend() = default;
  virtual std::string name() const = 0;
  // Empty when the backend can run here; otherwise why not (shown to users and tests).
  virtual std::string unavailable_reason() const { return {}; }
  // Device and driver in one line, for `info` listings.
  virtual std::string description() const { return name(); }
  // The driver in a word or two ("PoCL", "llvmpipe"), for progress lines such as
  // "compiling 7 kernels for opencl (PoCL)"; empty where the backend's name says it all.
  virtual std::string driver_label() const { return {}; }
  virtual bool supports(Accuracy a) const { return a != Accuracy::Double; }
  // How a supported accuracy mode runs where it differs from the backend's other modes (simd's
  // double: scalar C, not in lanes), for `info` listings; empty when it does not.
  virtual std::string accuracy_note(Accuracy) const { return {}; }
  // Whether kernels run on a GPU rather than on the host's CPU cores (cpu, simd, PoCL,
  // llvmpipe): programs that tune for the device, like the ray tracer's grid settings, ask.
  // False when the backend cannot run here.
  virtual bool runs_on_gpu() const { return false; }
  // Whether compile() must stay on one thread: a GL context is current on one thread at a
  // time (EGL refuses to make it current on a second). compile_all() runs such a backend's
  // compiles on its calling thread, alongside the other backends' on oneTBB's workers.
  virtual bool single_threaded() const { return false; }
  virtual std::unique_ptr<CompiledKernel> compile(const ir::Function& optimized,
                                                  const CompileOptions& options) = 0;
  // Copies the device copy of a stream or array, which this backend holds, into `host`
  // (s.words() words). Called by Storage when its host copy is read while this backend's
  // copy is newer; Storage then marks the host copy current. Backends that keep no device
  // copies (cpu) need not implement it.
  virtual void read_back(const detail::Storage& /*s*/, uint32_t* /*host*/) {}
  // The same, returning at once where the backend can transfer while its later kernels run
  // (ReadBack.h): the words copied are the device copy's now, even if a kernel launched
  // afterwards writes it; `host` stays in place until the result's wait(). The default reads
  // back at once and returns null (nothing in flight): the CPU backends, whose read-back is a
  // copy on the cores that trace, would gain nothing.
  virtual std::unique_ptr<PendingReadBack> read_back_async(const detail::Storage& s,
                                                           uint32_t* host) {
    read_back(s, host);
    return nullptr;
  }
};

// Backends by name. The CPU backend is always present.
Backend& backend(const std::string& name);
std::vector<Backend*> backends();
void register_backend(std::unique_ptr<Backend> b);

}  // namespace rill
