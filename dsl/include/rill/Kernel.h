// Kernels: a program compiled for one backend, bound to streams, and launched.
//
//   rill::Kernel k = rill::compile(grow, "cpu");     // or grow with options
//   k.inputs(s).outputs(s);                          // the same stream may be both
//   int64_t written = k.execute();                   // elements not discarded
//   int64_t passes = k.loop();                       // until a pass writes nothing
//   k.execute(rill::where(state, 3));                // only where state == 3 (StateMask.h)
//
// Compiled kernels are cached by (IR hash, backend, options): compiling the same program
// twice, or an identical program defined again, costs nothing the second time.
#pragma once

#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "rill/Backend.h"
#include "rill/Program.h"
#include "rill/StateMask.h"
#include "rill/Stream.h"

namespace rill {

// What the last launch of a kernel did.
struct LaunchStats {
  int64_t processed = 0;  // elements the kernel ran on (all, or those selected by the mask)
  int64_t written = 0;    // elements not discarded (<= processed)
  // How long the kernel itself ran, as the device timed it (the launch's wall time less the
  // binding, transfers and driver calls around it); -1 where the backend cannot tell.
  double device_ms = -1;
};

// What compiling a kernel cost, stage by stage, in milliseconds, and where it came from.
// compile_ms is the whole compile() call: optimize_ms + codegen_ms + backend_compile_ms +
// driver_finish_ms, plus a little bookkeeping. capture_ms happened earlier, when the Program
// was defined, and is not part of it. On a process-cache hit the stages are those of the
// compile that built the shared kernel, and compile_ms is 0: this compile() cost nothing
// (or, when another thread was still building that kernel, the time spent waiting for it).
struct CompileInfo {
  double capture_ms = 0;          // building the program's IR (when the Program was defined)
  double optimize_ms = 0;         // the optimizer passes
  double codegen_ms = 0;          // emitting the backend's source
  double backend_compile_ms = 0;  // the backend's compiler, or loading a cached binary
  double driver_finish_ms = 0;    // work a driver defers to the first launch, done in compile()
  double compile_ms = 0;          // what this compile() call took in all (0 on a cache hit)
  // Built, ProcessCache, DiskCache. DriverCache is never reported today: neither PoCL nor
  // Mesa says whether a build came from its own cache (see docs/programming-model.md).
  KernelOrigin origin = KernelOrigin::Built;
  bool cache_hit = false;        // served from the in-process kernel cache (origin ProcessCache)
  bool from_disk_cache = false;  // the backend loaded a binary from Rill's disk cache (cpu
                                 // and simd with RILL_PROFILE_DIR: an earlier run's file)
  // How the kernel runs where that is not what its backend's name says: simd's double
  // kernels run as scalar C, one element at a time (Backend::accuracy_note); else empty.
  std::string execution;
};

class Kernel {
 public:
  Kernel() = default;

  // Binds streams to the program's inputs / outputs in declaration order.
  template <class... S>
  Kernel& inputs(const S&... s) {
    bind_all(true, {StreamRef(s)...});
    return *this;
  }
  template <class... S>
  Kernel& outputs(const S&... s) {
    bind_all(false, {StreamRef(s)...});
    return *this;
  }
  // Binds one input or output by the name it was declared with. A name declared both as an
  // input and as an output binds both (an in-place update). Unknown names and streams of
  // another element type are errors that name both sides.
  Kernel& bind(const std::string& name, StreamRef s);
  // Binds a stream of records (Record.h) field by field: the leaf "pos" of the stream binds
  // the kernel's "<name>.pos" (or "pos" when name is empty, for unnamed record parameters).
  template <class S>
  requires requires(const S& s) { s.leaves(); }
  Kernel& bind(const std::string& name, const S& s) {
    bind_record(name, s.name(), s.leaves(), false);
    return *this;
  }
  // Binds only the fields of a record stream that the kernel declares ("<name>.<field>", as
  // an input, an output or both), for kernels that read or write some of a record's fields:
  //   Input<Int> st("tr.state");  Output<Int3> v("tr.voxel");  ...  k.bind_fields("tr", tr);
  // A kernel that declares none of them is an error; a declared field left unbound is one at
  // launch, as always.
  template <class S>
  requires requires(const S& s) { s.leaves(); }
  Kernel& bind_fields(const std::string& name, const S& s) {
    bind_record(name, s.name(), s.leaves(), true);
    return *this;
  }

  // Runs once over every element; returns the number of elements written.
  int64_t execute();
  // Runs until a pass writes nothing; returns the number of passes, the last (empty) one
  // included. Throws if max_passes pass without termination.
  int64_t loop(int64_t max_passes = std::numeric_limits<int64_t>::max());
  // Masked launch (see StateMask.h): runs only on the elements the mask selects; the others
  // keep their outputs and are not counted. The mask's stream must be a Stream<Int> of as
  // many elements as the kernel runs over. loop(mask) re-evaluates the mask every pass.
  int64_t execute(const StateMask& mask);
  int64_t loop(const StateMask& mask, int64_t max_passes = std::numeric_limits<int64_t>::max());
  // Does, without running any element, the work a driver would do at the first launch with
  // the streams bound now, and returns its time in milliseconds (also added to
  // info().driver_finish_ms). compile() already warms a kernel up for the usual case; this
  // covers what that cannot know: llvmpipe compiles a shader variant per class of texture
  // shape (power-of-two sides or not) and another for masked launches. Call it after
  // binding, when the first launch's latency matters (an interactive frame).
  double warm_up();
  double warm_up(const StateMask& mask);
  // Elements processed and written by the last execute() of this Kernel object.
  const LaunchStats& last_launch() const { return last_; }
  // What the kernel's rill::print statements wrote in the last launch (Print.h), also sent
  // to print_output(); empty when it has none.
  const std::string& last_print() const { return last_print_; }
  // How many elements' prints a launch shows: the first that printed, in element order (16
  // by default, or RILL_PRINT_LIMIT from the environment).
  Kernel& print_limit(int64_t elements);
  int64_t print_limit() const;

  const std::string& source() const;  // generated code
  std::string ir() const;             // optimized IR text
  // Writes ir() to `os` (standard error by default), for debugging: k.dump();
  void dump(std::ostream& os = std::cerr) const { os << ir(); }
  const CompileInfo& info() const { return info_; }
  const Program& program() const { return program_; }
  std::string backend_name() const;

  struct Shared;  // compiled code, shared by every Kernel made from the same cache entry

 private:
  friend Kernel compile(const Program&, const std::string&, const CompileOptions&);
  void bind_all(bool inputs, std::initializer_list<StreamRef> s);
  void bind_record(const std::string& name, const std::string& stream,
                   const std::vector<std::pair<std::string, StreamRef>>& leaves, bool partial);
  LaunchArgs prepare();
  void attach_mask(LaunchArgs& a, const StateMask& mask) const;
  int64_t launch(LaunchArgs& a);
  double warm_up(LaunchArgs& a);

  std::shared_ptr<Shared> shared_;
  Program program_;
  std::vector<std::shared_ptr<detail::StreamState>> in_, out_;
  CompileInfo info_;
  LaunchStats last_;
  std::string last_print_;
  int64_t print_limit_ = -1;  // -1: the default
  // Print slots and debug reports: hidden outputs, bound by the kernel itself (fresh zeroed
  // streams each launch); the arrays' shapes for the debug mode's checks.
  std::vector<std::shared_ptr<detail::UniformState>> shape_uniforms_;
  void after_launch(const LaunchArgs& a);
};

Kernel compile(const Program& p, const std::string& backend = "cpu",
               const CompileOptions& options = {});

// One kernel for compile_all().
struct CompileRequest {
  Program program;
  std::string backend = "cpu";
  CompileOptions options = {};
};

// Compiles several kernels concurrently (oneTBB) and returns them in the order asked:
//   std::vector<Kernel> ks = compile_all({{grow, "cpu"}, {shade, "simd", opt}});
// Each is what compile() would return (the same kernel cache; identical requests build once).
// The cpu and simd compilers run as separate processes, so they overlap fully; GLSL builds
// share one GL context and run one at a time on the calling thread, alongside the others.
// If any fails, every other still finishes, and the first failure in request order is
// thrown, naming its program and backend.
std::vector<Kernel> compile_all(const std::vector<CompileRequest>& requests);

// How far a compile has got, for a progress line (CompileProgressLine.h draws one on a
// terminal). A batch is one compile_all() call, or one compile() that missed the in-process
// kernel cache (compile() served from it reports nothing). The observer is called at the
// batch's start (done == 0), as each kernel is ready (built, or served from a cache), and
// once more with finished set. Calls come from the compiling threads, one at a time.
struct CompileProgress {
  std::string backend;  // the backend's name (the first request's in a mixed compile_all)
  std::string driver;   // Backend::driver_label(): "PoCL", "llvmpipe"; may be empty
  int done = 0;         // kernels ready so far
  int total = 0;        // kernels in the batch
  bool finished = false;
  double elapsed_ms = 0;  // since the batch started
};
using CompileObserver = std::function<void(const CompileProgress&)>;
// Installs a process-wide observer (an empty one removes it) and returns the one it replaces,
// so a scope can restore it. Embedders show their own progress through it.
CompileObserver set_compile_observer(CompileObserver observer);

// Writes the optimized IR (ir()): std::cout << kernel;
inline std::ostream& operator<<(std::ostream& os, const Kernel& k) {
  return os << k.ir();
}

// The in-process kernel cache.
struct CacheStats {
  int64_t hits = 0, misses = 0;
};
CacheStats kernel_cache_stats();
void clear_kernel_cache();

}  // namespace rill
