#include "rill/Kernel.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <tuple>

#include "CompileProgress.h"
#include "DebugReport.h"
#include "PrintSlots.h"
#include "rill/Parameters.h"
#include "rill/Print.h"
#include "rill/Stopwatch.h"
#include "rill/ir/Printer.h"
#include "rill/ir/Verifier.h"
#include "rill/passes/Passes.h"

namespace rill {

struct Kernel::Shared {
  Backend* backend = nullptr;
  ir::Function optimized;
  std::unique_ptr<CompiledKernel> compiled;
  std::mutex run_mutex;      // a compiled kernel runs one launch at a time
  CompileInfo info;          // what building it cost
  passes::DebugTable debug;  // the debug mode's checks (CompileOptions::debug)
};

namespace {

using CacheKey = std::tuple<uint64_t, std::string, uint64_t>;

// A cache entry is made when its compile starts, so a second compile() of the same kernel
// meanwhile (compile_all, or user threads) waits for that one instead of building it again.
struct Entry {
  std::shared_future<std::shared_ptr<Kernel::Shared>> ready;
};

struct Cache {
  std::mutex mutex;
  std::map<CacheKey, std::shared_ptr<Entry>> entries;
  CacheStats stats;
};
Cache& cache() {
  static Cache c;
  return c;
}

// Optimizes and builds one kernel, timing each stage into shared->info.
std::shared_ptr<Kernel::Shared> build(const Program& p, Backend& be,
                                      const CompileOptions& options) {
  Stopwatch total, stage;
  auto shared = std::make_shared<Kernel::Shared>();
  CompileInfo& info = shared->info;
  shared->backend = &be;
  try {
    shared->optimized = passes::optimize(p.ir(), options.passes, options.accuracy);
    if (options.debug)
      shared->debug = passes::instrument_debug(shared->optimized, options.debug_nonfinite);
    info.optimize_ms = stage.lap();
    shared->compiled = be.compile(shared->optimized, options);
  } catch (const Error& e) {
    // Errors that name no line of the user's (a statement's own, or a driver message read
    // back through the source map: codegen/SourceMap.h) name where the program was defined.
    const std::string what = e.what();
    if (e.where().known() || what.find(" (generated line ") != std::string::npos ||
        !p.ir().defined_at.known())
      throw;
    throw Error(what, p.ir().defined_at);
  }
  stage.lap();
  // A warm-up that fails (a launch the backend cannot make, such as too many textures)
  // leaves the driver's work to the first launch, which reports the same problem with the
  // user's own streams; compile() itself has succeeded.
  try {
    shared->compiled->warm_up();
  } catch (const Error&) {
  }
  info.driver_finish_ms = stage.lap();
  const BuildReport& report = shared->compiled->report();
  info.codegen_ms = report.codegen_ms;
  info.backend_compile_ms = report.compile_ms;
  info.origin = report.origin;
  info.from_disk_cache = shared->compiled->from_disk_cache();
  info.execution = report.execution;
  info.compile_ms = total.ms();
  return shared;
}

// RILL_DEBUG=1 (gathers) or RILL_DEBUG=nonfinite (NaN and infinity too) turns the debug
// mode on for every compile of the process.
CompileOptions with_environment(CompileOptions o) {
  const char* env = std::getenv("RILL_DEBUG");
  if (env == nullptr || *env == '\0' || std::string(env) == "0") return o;
  o.debug = true;
  if (std::string(env) == "nonfinite") o.debug_nonfinite = true;
  return o;
}

std::string describe_param(const ir::Function& f, ir::VarId v, const char* dir) {
  return std::string(dir) + " '" + f.var(v).name + "' (" + f.var(v).type.str() + ")";
}

}  // namespace

CacheStats kernel_cache_stats() {
  std::lock_guard<std::mutex> lock(cache().mutex);
  return cache().stats;
}

void clear_kernel_cache() {
  std::lock_guard<std::mutex> lock(cache().mutex);
  cache().entries.clear();
  cache().stats = {};
}

Kernel compile(const Program& p, const std::string& backend_name, const CompileOptions& requested) {
  if (!p.valid()) throw Error("compile(): the program is empty (default-constructed)");
  CompileOptions options = with_environment(requested);
  if (const char* v = std::getenv("RILL_SOURCE_MAP")) {
    if (std::string(v) == "1")
      options.source_map = true;
    else if (std::string(v) != "0" && *v)
      throw Error("RILL_SOURCE_MAP='" + std::string(v).substr(0, 40) + "' is not 0 or 1");
  }
  // The cache exists before any backend starts its driver, so at exit it is destroyed after
  // the exit handlers the drivers register. Kernels destroyed then must not call into a
  // driver that has shut down: GLSL kernels check that their context still exists (Session
  // in GLSLBackend.cpp).
  Cache& c = cache();
  Backend& be = backend(backend_name);
  std::string why = be.unavailable_reason();
  if (!why.empty()) throw Error("backend '" + be.name() + "' is not available: " + why);
  if (!be.supports(options.accuracy))
    throw Error("backend '" + be.name() + "' does not support accuracy mode '" +
                    accuracy_name(options.accuracy) + "'",
                p.ir().defined_at);

  Kernel k;
  k.program_ = p;
  k.in_.resize(p.ir().inputs.size());
  k.out_.resize(p.ir().outputs.size());
  CacheKey key{p.hash(), be.name(), options.hash()};

  Stopwatch waited;
  std::unique_lock<std::mutex> lock(c.mutex);
  auto it = c.entries.find(key);
  if (it != c.entries.end()) {
    ++c.stats.hits;
    std::shared_ptr<Entry> entry = it->second;
    lock.unlock();
    const bool in_flight =
        entry->ready.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
    k.shared_ = entry->ready.get();  // rethrows the building thread's error
    k.info_ = k.shared_->info;
    // The wait for another thread's build of this kernel is what this call cost.
    k.info_.compile_ms = in_flight ? waited.ms() : 0;
    k.info_.cache_hit = true;
    k.info_.origin = KernelOrigin::ProcessCache;
    k.info_.capture_ms = p.capture_ms();
    k.out_.resize(k.shared_->optimized.outputs.size());  // the debug mode's outputs too
    return k;
  }
  ++c.stats.misses;
  std::promise<std::shared_ptr<Kernel::Shared>> promise;
  auto entry = std::make_shared<Entry>(Entry{promise.get_future().share()});
  c.entries.emplace(key, entry);
  lock.unlock();

  // A build is a batch of one for the compile observer, unless compile_all() reports this
  // compile as part of its own batch. Ends (finished) when this scope does, error or not.
  std::optional<detail::CompileBatch> batch;
  if (!detail::in_compile_batch()) batch.emplace(be.name(), be.driver_label(), 1);
  try {
    k.shared_ = build(p, be, options);
    if (batch) batch->done();
  } catch (...) {
    // Waiters get the error; the next compile() tries again.
    promise.set_exception(std::current_exception());
    lock.lock();
    auto mine = c.entries.find(key);
    if (mine != c.entries.end() && mine->second == entry) c.entries.erase(mine);
    throw;
  }
  promise.set_value(k.shared_);
  k.out_.resize(k.shared_->optimized.outputs.size());  // the debug mode's outputs too
  k.info_ = k.shared_->info;
  k.info_.capture_ms = p.capture_ms();
  return k;
}

void Kernel::bind_all(bool inputs, std::initializer_list<StreamRef> s) {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  const ir::Function& f = program_.ir();
  auto& slots = inputs ? in_ : out_;
  // The user's parameters only: print slots are bound by the kernel itself.
  std::vector<size_t> params;
  for (size_t i = 0; i < (inputs ? f.inputs : f.outputs).size(); ++i)
    if (inputs || !detail::is_hidden_output(f.var(f.outputs[i]).name)) params.push_back(i);
  if (s.size() != params.size())
    throw Error("kernel '" + f.name + "' has " + std::to_string(params.size()) +
                (inputs ? " input(s)" : " output(s)") + " but " + std::to_string(s.size()) +
                " stream(s) were bound");
  size_t i = 0;
  for (const StreamRef& r : s) slots[params[i++]] = r.shared();
}

namespace {

// "inputs x (float), y (float3); outputs out (float)": what a kernel can bind, for errors.
std::string describe_interface(const ir::Function& f) {
  auto list = [&](const std::vector<ir::VarId>& vs) {
    std::string out;
    for (ir::VarId v : vs)
      if (!detail::is_hidden_output(f.var(v).name))
        out += (out.empty() ? "" : ", ") + f.var(v).name + " (" + f.var(v).type.str() + ")";
    return out.empty() ? std::string("none") : out;
  };
  return "inputs " + list(f.inputs) + "; outputs " + list(f.outputs);
}

}  // namespace

Kernel& Kernel::bind(const std::string& name, StreamRef s) {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  const ir::Function& f = program_.ir();
  bool found = false;
  auto bind_to = [&](const std::vector<ir::VarId>& params, auto& slots, const char* dir) {
    for (size_t i = 0; i < params.size(); ++i) {
      if (f.var(params[i]).name != name) continue;
      if (s.state().type() != f.var(params[i]).type)
        throw Error("kernel '" + f.name + "': " + describe_param(f, params[i], dir) +
                    " cannot be bound to stream '" + s.state().name + "' of " +
                    s.state().type().str() + " elements");
      slots[i] = s.shared();
      found = true;
    }
  };
  bind_to(f.inputs, in_, "input");
  bind_to(f.outputs, out_, "output");
  if (!found)
    throw Error("kernel '" + f.name + "' has no input or output named '" + name + "' (it has " +
                describe_interface(f) + ")");
  return *this;
}

void Kernel::bind_record(const std::string& name, const std::string& stream,
                         const std::vector<std::pair<std::string, StreamRef>>& leaves,
                         bool partial) {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  const ir::Function& f = program_.ir();
  auto full = [&](const std::string& path) { return name.empty() ? path : name + "." + path; };
  auto declared = [&](const std::string& n) {
    for (const auto* params : {&f.inputs, &f.outputs})
      for (ir::VarId v : *params)
        if (f.var(v).name == n) return true;
    return false;
  };
  if (partial) {  // bind_fields: the fields the kernel declares
    bool any = false;
    for (const auto& [path, ref] : leaves)
      if (declared(full(path))) {
        bind(full(path), ref);
        any = true;
      }
    if (!any)
      throw Error("kernel '" + f.name + "' declares no field of record stream '" + stream +
                  "' as '" + (name.empty() ? std::string("(unnamed)") : name) +
                  ".<field>' (kernel " + describe_interface(f) + ")");
    return;
  }
  // Check the whole record first: a partial binding would leave the kernel half rebound.
  std::string missing, extra;
  for (const auto& [path, ref] : leaves)
    if (!declared(full(path))) missing += (missing.empty() ? "" : ", ") + full(path);
  if (!name.empty())
    for (const auto* params : {&f.inputs, &f.outputs})
      for (ir::VarId v : *params) {
        const std::string& n = f.var(v).name;
        if (n.rfind(name + ".", 0) != 0) continue;
        bool provided = false;
        for (const auto& [path, ref] : leaves) provided = provided || full(path) == n;
        if (!provided) extra += (extra.empty() ? "" : ", ") + n;
      }
  if (!missing.empty() || !extra.empty())
    throw Error("kernel '" + f.name + "': record stream '" + stream + "' does not match '" +
                (name.empty() ? std::string("(unnamed)") : name) + "'" +
                (missing.empty() ? "" : "; the kernel has no " + missing) +
                (extra.empty() ? "" : "; the stream has no field for " + extra) + " (kernel " +
                describe_interface(f) + ")");
  for (const auto& [path, ref] : leaves) bind(full(path), ref);
}

LaunchArgs Kernel::prepare() {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  // The compiled interface: the program's, and the debug mode's outputs and uniforms after
  // it. (Its name may be another identical program's: messages use this one's.)
  const ir::Function& f = shared_->optimized;
  const std::string& name = program_.name();
  LaunchArgs a;
  // Print slots and debug reports: fresh zeroed streams of the launch's shape, so that what
  // an element leaves there is this launch's (a masked launch skips some elements).
  const detail::StreamState* shape = nullptr;
  for (size_t i = 0; i < out_.size() && !shape; ++i)
    if (!detail::is_hidden_output(f.var(f.outputs[i]).name) && out_[i]) shape = out_[i].get();
  for (size_t i = 0; i < out_.size(); ++i) {
    const ir::Variable& v = f.var(f.outputs[i]);
    if (!detail::is_hidden_output(v.name) || !shape) continue;
    out_[i] = std::make_shared<detail::StreamState>();
    detail::init_stream(*out_[i], v.type, shape->width, shape->height, shape->dims, v.name);
  }
  std::string unbound;
  for (size_t i = 0; i < in_.size(); ++i)
    if (!in_[i]) unbound += (unbound.empty() ? "" : ", ") + describe_param(f, f.inputs[i], "input");
  for (size_t i = 0; i < out_.size(); ++i)
    if (!out_[i] && !detail::is_hidden_output(f.var(f.outputs[i]).name))
      unbound += (unbound.empty() ? "" : ", ") + describe_param(f, f.outputs[i], "output");
  if (!unbound.empty())
    throw Error("kernel '" + name + "': not bound to a stream: " + unbound +
                " (bind them with bind(name, stream), or inputs(...) and outputs(...))");
  if (!shape && out_.size() > 0 && !out_[0])
    throw Error("kernel '" + name +
                "' has no output of its own, which its prints need: they take the number of "
                "elements to print from the kernel's outputs (declare and write one)");
  auto check = [&](const std::shared_ptr<detail::StreamState>& s, ir::VarId v, const char* dir) {
    if (s->type() != f.var(v).type)
      throw Error("kernel '" + name + "': " + describe_param(f, v, dir) +
                  " is bound to a stream of " + s->type().str());
  };
  for (size_t i = 0; i < out_.size(); ++i) {
    check(out_[i], f.outputs[i], "output");
    if (i == 0) {
      a.count = out_[0]->count();
      a.width = out_[0]->width;
      a.height = out_[0]->height;
    } else if (out_[i]->count() != a.count) {
      throw Error("kernel '" + name + "': " + describe_param(f, f.outputs[i], "output") + " has " +
                  std::to_string(out_[i]->count()) + " elements but output '" +
                  f.var(f.outputs[0]).name + "' has " + std::to_string(a.count));
    }
    a.outputs.push_back(out_[i].get());
  }
  for (size_t i = 0; i < in_.size(); ++i) {
    check(in_[i], f.inputs[i], "input");
    if (in_[i]->count() != a.count)
      throw Error("kernel '" + name + "': " + describe_param(f, f.inputs[i], "input") + " has " +
                  std::to_string(in_[i]->count()) + " elements but the kernel runs over " +
                  std::to_string(a.count) + " (the size of its outputs)");
    a.inputs.push_back(in_[i].get());
  }
  for (const auto& u : program_.captured().uniforms) a.uniforms.push_back(u.get());
  // The debug mode's checks read each array's shape from a uniform of their own.
  const passes::DebugTable& debug = shared_->debug;
  shape_uniforms_.resize(debug.shape_uniforms.size());
  for (size_t i = 0; i < debug.shape_uniforms.size(); ++i) {
    if (debug.shape_uniforms[i] < 0) continue;
    if (!shape_uniforms_[i]) shape_uniforms_[i] = std::make_shared<detail::UniformState>();
    detail::UniformState& u = *shape_uniforms_[i];
    u.type = ir::int_type(3);
    const detail::ArrayState& arr = *program_.captured().arrays.at(i);
    for (int d = 0; d < 3; ++d)
      u.bits[static_cast<size_t>(d)] = static_cast<uint32_t>(static_cast<int32_t>(
          std::min<int64_t>(arr.shape[d], std::numeric_limits<int32_t>::max())));
  }
  for (size_t i = 0; i < debug.shape_uniforms.size(); ++i)
    if (debug.shape_uniforms[i] >= 0)
      a.uniforms.resize(
          std::max(a.uniforms.size(), static_cast<size_t>(debug.shape_uniforms[i]) + 1));
  for (size_t i = 0; i < debug.shape_uniforms.size(); ++i)
    if (debug.shape_uniforms[i] >= 0)
      a.uniforms[static_cast<size_t>(debug.shape_uniforms[i])] = shape_uniforms_[i].get();
  for (const auto& arr : program_.captured().arrays) {
    // A gather reads other elements than its own, which a launch may be rewriting in any
    // order: the result would depend on the schedule. (Reading the element's own value
    // through an input bound to the same stream is well defined, and allowed.)
    for (size_t i = 0; i < out_.size(); ++i)
      if (out_[i].get() == arr.get())
        throw Error("kernel '" + name + "' gathers from stream '" + arr->name +
                    "' while writing it as " + describe_param(f, f.outputs[i], "output") +
                    "; write to another stream (ping-pong between two), or read the element's "
                    "own value through an input bound to the same stream");
    a.arrays.push_back(arr.get());
  }
  return a;
}

int64_t Kernel::launch(LaunchArgs& a) {
  std::lock_guard<std::mutex> lock(shared_->run_mutex);
  const LaunchResult r = shared_->compiled->run(a);
  last_.written = r.written;
  last_.processed = a.mask ? r.selected : a.count;
  last_.device_ms = r.device_ms;
  after_launch(a);
  return last_.written;
}

Kernel& Kernel::print_limit(int64_t elements) {
  if (elements < 0)
    throw Error("kernel '" + program_.name() + "': print_limit(" + std::to_string(elements) +
                "): the limit is a number of elements, 0 or more");
  print_limit_ = elements;
  return *this;
}

int64_t Kernel::print_limit() const {
  if (print_limit_ >= 0) return print_limit_;
  static const int64_t from_env = [] {
    const char* env = std::getenv("RILL_PRINT_LIMIT");
    if (env == nullptr || *env == '\0') return int64_t{16};
    char* end = nullptr;
    const long long n = std::strtoll(env, &end, 10);
    if (*end != '\0' || n < 0)
      throw Error(std::string("RILL_PRINT_LIMIT='") + env +
                  "': expected a number of elements, 0 or more");
    return static_cast<int64_t>(n);
  }();
  return from_env;
}

// Formats the prints and checks the debug reports of the launch just made.
void Kernel::after_launch(const LaunchArgs& a) {
  const std::vector<detail::PrintSite>& prints = program_.captured().prints;
  const passes::DebugTable& debug = shared_->debug;
  if (prints.empty() && !debug.active()) return;
  std::vector<std::vector<uint32_t>> words(a.outputs.size());
  const detail::SlotReader slot = [&](int i) -> const uint32_t* {
    std::vector<uint32_t>& w = words.at(static_cast<size_t>(i));
    if (w.empty()) {
      detail::StreamState& s = *a.outputs[static_cast<size_t>(i)];
      w.resize(s.words());
      if (!w.empty()) s.read_into(w.data());
    }
    return w.data();
  };
  const std::string& name = program_.name();
  if (!prints.empty()) {
    last_print_ = detail::format_prints(prints, slot, a.count, print_limit(), name);
    if (std::ostream* os = print_output(); os && !last_print_.empty()) *os << last_print_;
  }
  if (debug.active()) {
    std::vector<std::array<int64_t, 3>> shapes;
    for (const detail::ArrayState* arr : a.arrays)
      shapes.push_back({arr->shape[0], arr->shape[1], arr->shape[2]});
    const std::string report = detail::debug_report(debug, slot, a.count, shapes, name);
    if (!report.empty()) throw Error(report.substr(0, report.size() - 1));
  }
}

int64_t Kernel::execute() {
  LaunchArgs a = prepare();
  return launch(a);
}

void Kernel::attach_mask(LaunchArgs& a, const StateMask& mask) const {
  const std::string& name = program_.name();
  detail::StreamState& s = mask.state().state();
  if (s.type() != ir::int_type(1))
    throw Error("kernel '" + name + "': the mask stream must be a Stream<Int>, not a stream of " +
                s.type().str());
  if (s.count() != a.count)
    throw Error("kernel '" + name + "': the mask stream has " + std::to_string(s.count()) +
                " elements but the kernel runs over " + std::to_string(a.count));
  if (mask.values().empty() || mask.values().size() > StateMask::kMaxValues)
    throw Error("kernel '" + name + "': a mask selects 1 to " +
                std::to_string(StateMask::kMaxValues) + " state values (got " +
                std::to_string(mask.values().size()) + ")");
  a.mask = &s;
  a.mask_values = mask.values();
}

int64_t Kernel::execute(const StateMask& mask) {
  LaunchArgs a = prepare();
  attach_mask(a, mask);
  return launch(a);
}

double Kernel::warm_up() {
  LaunchArgs a = prepare();
  return warm_up(a);
}

double Kernel::warm_up(const StateMask& mask) {
  LaunchArgs a = prepare();
  attach_mask(a, mask);
  return warm_up(a);
}

double Kernel::warm_up(LaunchArgs& a) {
  // The backend sees the bound streams (their shapes and formats are what a driver compiles
  // a variant for) but a count of 0, so no element runs and nothing is written or counted.
  a.count = 0;
  a.warm_up = true;
  Stopwatch watch;
  {
    std::lock_guard<std::mutex> lock(shared_->run_mutex);
    shared_->compiled->run(a);
  }
  const double ms = watch.ms();
  info_.driver_finish_ms += ms;
  return ms;
}

int64_t Kernel::loop(const StateMask& mask, int64_t max_passes) {
  int64_t passes = 0;
  while (passes < max_passes) {
    ++passes;
    if (execute(mask) == 0) return passes;
  }
  throw Error("kernel '" + program_.name() + "': loop() still wrote elements after " +
              std::to_string(max_passes) + " passes");
}

int64_t Kernel::loop(int64_t max_passes) {
  int64_t passes = 0;
  while (passes < max_passes) {
    ++passes;
    if (execute() == 0) return passes;
  }
  throw Error("kernel '" + program_.name() + "': loop() still wrote elements after " +
              std::to_string(max_passes) + " passes");
}

const std::string& Kernel::source() const {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  return shared_->compiled->source();
}

std::string Kernel::ir() const {
  if (!shared_) throw Error("this kernel was never compiled (use rill::compile)");
  // Identical programs share one compiled kernel; show this program's own name.
  ir::Function named = shared_->optimized;
  named.name = program_.name();
  return ir::print(named);
}

std::string Kernel::backend_name() const {
  return shared_ ? shared_->backend->name() : std::string();
}

}  // namespace rill
