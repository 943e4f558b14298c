// The OpenCL backend (OpenCLBackend.h): the Backend interface over its three roles, each in
// its own file: the compiler (ClCompiler.h: OpenCL C to a program, through Rill's disk cache),
// the device memory (ClMemory.h) and the launcher (ClLauncher.h), all on one Device
// (ClDevice.h), opened at the first use.
#include "OpenCLBackend.h"

#include <mutex>

#include "../codegen/SourceMap.h"
#include "ClCompiler.h"
#include "ClDevice.h"
#include "ClLauncher.h"
#include "ClMemory.h"
#include "OpenCLEmitter.h"
#include "rill/Stopwatch.h"

namespace rill::opencl {

namespace {

class OpenCLBackend : public Backend {
 public:
  std::string name() const override { return "opencl"; }

  std::string unavailable_reason() const override {
    try {
      const_cast<OpenCLBackend*>(this)->device();
      return {};
    } catch (const Error& e) {
      return e.what();
    }
  }

  // "PoCL", or the device's name on another platform.
  std::string driver_label() const override {
    if (!unavailable_reason().empty()) return {};
    const Device& d = const_cast<OpenCLBackend*>(this)->device();
    return is_pocl(d) ? "PoCL" : d.info.device_name;
  }

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return "opencl: unavailable: " + why;
    const Device& d = const_cast<OpenCLBackend*>(this)->device();
    std::string cache;
    try {
      cache = keeps_binaries(d) ? "program binaries"
              : is_pocl(d)      ? "the driver's own (PoCL's kernel cache; RILL_OPENCL_BINARIES=on "
                                  "for Rill's)"
                                : "none (RILL_OPENCL_BINARIES=off)";
    } catch (const Error& e) {
      cache = e.what();  // a bad setting, named; compiling then fails with the same message
    }
    return "opencl: " + d.info.platform_name + " / " + d.info.device_name + " (" + d.info.version +
           "); disk cache: " + cache;
  }

  bool runs_on_gpu() const override {
    return unavailable_reason().empty() && const_cast<OpenCLBackend*>(this)->device().info.gpu;
  }

  bool supports(Accuracy a) const override {
    if (a != Accuracy::Double) return true;
    return unavailable_reason().empty() && const_cast<OpenCLBackend*>(this)->device().info.fp64;
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    Device& d = device();
    if (o.accuracy == Accuracy::Double && !d.info.fp64)
      throw Error("OpenCL backend: device '" + d.info.device_name +
                  "' has no fp64 support (cl_khr_fp64)");
    check_launch_settings();
    Stopwatch stage;
    std::string source = emit_opencl(f, o.accuracy, o.source_map);
    const double codegen_ms = stage.lap();
    const BuiltKernel built = codegen::reporting_user_lines(
        source, [&] { return emit_opencl(f, o.accuracy, true); },
        [&] { return build_kernel(d, f.name, source, o.accuracy); });
    auto kernel = std::make_unique<ClKernel>(d, memory(), f, std::move(source), built);
    kernel->set_build_times(codegen_ms, stage.lap());
    return kernel;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override { memory().read_back(s, host); }
  std::unique_ptr<PendingReadBack> read_back_async(const detail::Storage& s,
                                                   uint32_t* host) override {
    return memory().read_back_async(s, host);
  }

  Device& device() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (dev_) return *dev_;
    if (!init_error_.empty()) throw Error(init_error_);
    try {
      auto d = open_device(spec_);
      memory_ = std::make_unique<ClMemory>(*this, *d);
      dev_ = std::move(d);
    } catch (const Error& e) {
      init_error_ = e.what();
      throw;
    }
    return *dev_;
  }

  ClMemory& memory() {
    device();
    return *memory_;
  }

  void set_spec(const std::string& spec) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (dev_)
      throw Error(
          "OpenCL backend: set_device() must be called before the first OpenCL kernel is compiled");
    spec_ = spec;
    init_error_.clear();
  }

 private:
  std::mutex mutex_;
  std::unique_ptr<Device> dev_;  // never released: buffers of live streams refer to it
  std::unique_ptr<ClMemory> memory_;
  std::string init_error_, spec_;
};

OpenCLBackend* g_backend = nullptr;

}  // namespace

std::vector<DeviceInfo> list_devices() {
  return enumerate_devices().infos;
}

void set_device(const std::string& spec) {
  backend("opencl");  // make sure the registry created it
  if (!g_backend) throw Error("OpenCL backend is not part of this build");
  g_backend->set_spec(spec);
}

std::unique_ptr<Backend> make_backend() {
  auto b = std::make_unique<OpenCLBackend>();
  g_backend = b.get();
  return b;
}

}  // namespace rill::opencl
