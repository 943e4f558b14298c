#include "OpenCLBackend.h"

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "../cache/DiskCache.h"
#include "../codegen/SourceText.h"
#include "../codegen/Tiles.h"
#include "OpenCLEmitter.h"
#include "WarmUpLaunch.h"
#include "rill/Parameters.h"
#include "rill/Stopwatch.h"

namespace rill::opencl {

namespace {

std::string cl_error_name(cl_int e) {
  switch (e) {
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case CL_INVALID_HOST_PTR:
      return "CL_INVALID_HOST_PTR";
    case -1001:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "OpenCL error " + std::to_string(e);
  }
}

void check(cl_int e, const char* what) {
  if (e != CL_SUCCESS)
    throw Error(std::string("OpenCL backend: ") + what + " failed: " + cl_error_name(e));
}

std::string platform_string(cl_platform_id p, cl_platform_info what) {
  size_t n = 0;
  clGetPlatformInfo(p, what, 0, nullptr, &n);
  std::string s(n, '\0');
  clGetPlatformInfo(p, what, n, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string device_string(cl_device_id d, cl_device_info what) {
  size_t n = 0;
  clGetDeviceInfo(d, what, 0, nullptr, &n);
  std::string s(n, '\0');
  clGetDeviceInfo(d, what, n, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

struct Found {
  std::vector<DeviceInfo> infos;
  std::vector<cl_device_id> ids;
  std::string error;  // why there is none
};

Found enumerate() {
  Found f;
  cl_uint np = 0;
  cl_int e = clGetPlatformIDs(0, nullptr, &np);
  if (e != CL_SUCCESS || np == 0) {
    f.error = "no OpenCL platform found (" +
              (e == CL_SUCCESS ? std::string("0 platforms") : cl_error_name(e)) +
              "); install an ICD such as pocl-opencl-icd, or a GPU driver's";
    return f;
  }
  std::vector<cl_platform_id> platforms(np);
  clGetPlatformIDs(np, platforms.data(), nullptr);
  for (cl_uint p = 0; p < np; ++p) {
    cl_uint nd = 0;
    if (clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devs(nd);
    clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, nd, devs.data(), nullptr);
    for (cl_uint d = 0; d < nd; ++d) {
      DeviceInfo info;
      info.platform = static_cast<int>(p);
      info.device = static_cast<int>(d);
      info.platform_name = platform_string(platforms[p], CL_PLATFORM_NAME);
      info.device_name = device_string(devs[d], CL_DEVICE_NAME);
      info.version = device_string(devs[d], CL_DEVICE_VERSION);
      info.fp64 =
          device_string(devs[d], CL_DEVICE_EXTENSIONS).find("cl_khr_fp64") != std::string::npos;
      cl_device_type type = 0;
      clGetDeviceInfo(devs[d], CL_DEVICE_TYPE, sizeof type, &type, nullptr);
      info.gpu = (type & CL_DEVICE_TYPE_GPU) != 0;
      f.infos.push_back(info);
      f.ids.push_back(devs[d]);
    }
  }
  if (f.ids.empty()) f.error = "OpenCL platforms were found but none has a device";
  return f;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Picks a device by spec (see OpenCLBackend.h); returns its index in `found`.
size_t choose(const Found& found, const std::string& spec) {
  if (spec.empty()) return 0;
  int p = -1, d = -1;
  if (std::sscanf(spec.c_str(), "%d:%d", &p, &d) == 2) {
    for (size_t i = 0; i < found.infos.size(); ++i)
      if (found.infos[i].platform == p && found.infos[i].device == d) return i;
  } else {
    for (size_t i = 0; i < found.infos.size(); ++i) {
      std::string name = lower(found.infos[i].platform_name + " " + found.infos[i].device_name);
      if (name.find(lower(spec)) != std::string::npos) return i;
    }
  }
  std::string avail;
  for (const auto& i : found.infos)
    avail += "\n  " + std::to_string(i.platform) + ":" + std::to_string(i.device) + "  " +
             i.platform_name + " / " + i.device_name;
  throw Error("OpenCL backend: no device matches '" + spec +
              "' (RILL_OPENCL_DEVICE); available:" + avail);
}

// The device's context and queue, created on first use.
struct Device {
  DeviceInfo info;
  cl_device_id id = nullptr;
  cl_context context = nullptr;
  cl_command_queue queue = nullptr;
  size_t max_group = 64;
  cl_ulong max_alloc = 0;           // CL_DEVICE_MAX_MEM_ALLOC_SIZE: the largest buffer (0: unknown)
  bool max_alloc_from_env = false;  // lowered by RILL_OPENCL_MAX_ALLOC_MB
  std::string identity;             // the platform, device and driver, as disk cache key lines
};

// A buffer over the device's largest allocation is an error naming both sizes and the device,
// before the driver is asked (some drivers fail later, at the launch, or not at all).
void check_allocation(const Device& d, size_t bytes) {
  if (d.max_alloc == 0 || bytes <= d.max_alloc) return;
  auto mib = [](uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
  throw Error("OpenCL backend: a buffer of " + mib(bytes) + " is over the largest allocation of " +
              d.info.device_name + " (" +
              (d.max_alloc_from_env ? "RILL_OPENCL_MAX_ALLOC_MB" : "CL_DEVICE_MAX_MEM_ALLOC_SIZE") +
              ", " + mib(d.max_alloc) + ")");
}

// The device and driver lines of Rill's disk cache keys: a binary is only valid for the
// driver version that produced it.
std::string cache_identity(cl_device_id id) {
  cl_platform_id platform = nullptr;
  clGetDeviceInfo(id, CL_DEVICE_PLATFORM, sizeof platform, &platform, nullptr);
  return "platform=" + platform_string(platform, CL_PLATFORM_NAME) + " / " +
         platform_string(platform, CL_PLATFORM_VERSION) +
         "\ndevice=" + device_string(id, CL_DEVICE_NAME) + " / " +
         device_string(id, CL_DEVICE_VERSION) + "\ndriver=" + device_string(id, CL_DRIVER_VERSION) +
         "\n";
}

// A program built from the binary in Rill's disk cache, or null when there is none. A binary
// the driver refuses (CL_INVALID_BINARY, a failed build) is removed, and the caller builds
// from source and stores a fresh one.
cl_program program_from_cache(const Device& d, const std::string& key, const std::string& options) {
  std::optional<std::string> binary = cache::load("opencl", key);
  if (!binary) return nullptr;
  const auto* bytes = reinterpret_cast<const unsigned char*>(binary->data());
  const size_t len = binary->size();
  cl_int status = CL_SUCCESS, e = CL_SUCCESS;
  cl_program prog = clCreateProgramWithBinary(d.context, 1, &d.id, &len, &bytes, &status, &e);
  if (e == CL_SUCCESS && status == CL_SUCCESS &&
      clBuildProgram(prog, 1, &d.id, options.c_str(), nullptr, nullptr) == CL_SUCCESS)
    return prog;
  if (e == CL_SUCCESS) clReleaseProgram(prog);
  cache::remove("opencl", key);
  return nullptr;
}

// Stores a built program's binary in Rill's disk cache (nothing if the driver gives none).
void store_binary(cl_program prog, const std::string& key) {
  size_t size = 0;
  if (clGetProgramInfo(prog, CL_PROGRAM_BINARY_SIZES, sizeof size, &size, nullptr) != CL_SUCCESS ||
      size == 0)
    return;
  std::string binary(size, '\0');
  auto* ptr = reinterpret_cast<unsigned char*>(binary.data());
  if (clGetProgramInfo(prog, CL_PROGRAM_BINARIES, sizeof ptr, &ptr, nullptr) != CL_SUCCESS) return;
  cache::store("opencl", key, binary);
}

// Device memory for a stream or array.
struct ClBuffer : detail::DeviceBuffer {
  cl_mem mem = nullptr;
  size_t bytes = 0;
  ~ClBuffer() override {
    if (mem) clReleaseMemObject(mem);
  }
};

class OpenCLBackend;

// How launches are laid out, read once from the environment:
//   RILL_OPENCL_GROUP=N      work-items per group (default 64; the kernel's and the device's
//                            limits cap it)
//   RILL_OPENCL_TILES=on|off 2D launches in 8 x 4 tiles (default on)
struct LaunchTuning {
  size_t group = 64;
  bool tiles = true;
};

const LaunchTuning& launch_tuning() {
  static const LaunchTuning t = [] {
    LaunchTuning t;
    if (const char* g = std::getenv("RILL_OPENCL_GROUP"); g && *g) {
      char* end = nullptr;
      const long v = std::strtol(g, &end, 10);
      if (*end != '\0' || v < 1 || v > 1024)
        throw Error(std::string("RILL_OPENCL_GROUP='") + g + "' is not a group size in 1..1024");
      t.group = static_cast<size_t>(v);
    }
    if (const char* s = std::getenv("RILL_OPENCL_TILES"); s && *s) {
      const std::string v = s;
      if (v != "on" && v != "off")
        throw Error("RILL_OPENCL_TILES='" + v + "' is not one of on, off");
      t.tiles = v == "on";
    }
    return t;
  }();
  return t;
}

// A small table a kernel reads (array shapes, uniform words, mask values), kept in one device
// buffer across launches and written again only when its contents change.
template <class T>
struct ClTable {
  cl_mem mem = nullptr;
  size_t bytes = 0;
  std::vector<T> uploaded;  // what the buffer holds
  ~ClTable() {
    if (mem) clReleaseMemObject(mem);
  }
};

class ClKernel : public CompiledKernel {
 public:
  ClKernel(OpenCLBackend& be, const ir::Function& f, std::string source, cl_program program,
           cl_kernel kernel)
      : be_(be), fn_(f), source_(std::move(source)), program_(program), kernel_(kernel) {}
  // Where the program came from, and what building or loading it took.
  ~ClKernel() override {
    if (counter_) clReleaseMemObject(counter_);
    clReleaseKernel(kernel_);
    clReleaseProgram(program_);
  }
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // PoCL compiles the kernel at its first enqueue for the work-group size and for the class
  // of grid: up to 65535 work-items ("smallgrid": 32-bit ids) or more. Two launches over no
  // elements, with the usual group size and a grid of each class, do both now.
  void warm_up() override {
    WarmUpLaunch stand_ins(fn_);
    for (size_t grid : {size_t{1}, size_t{65536}}) {
      warm_up_grid_ = grid;
      run(stand_ins.args());
    }
  }

 private:
  // The device buffer holding `now`, written only when it differs from the last upload.
  template <class T>
  cl_mem table(ClTable<T>& t, const std::vector<T>& now);

  OpenCLBackend& be_;
  ir::Function fn_;
  std::string source_;
  cl_program program_;
  cl_kernel kernel_;
  size_t warm_up_grid_ = 1;  // work-items a warm-up launch spans (warm_up)
  // Launches reuse their buffers (run() is called one launch at a time: Kernel's run_mutex).
  // The counter is never reset: it keeps running totals of elements written and selected, and
  // a launch's counts are the difference from the totals after the previous one (unsigned
  // arithmetic, so the totals may wrap).
  cl_mem counter_ = nullptr;
  cl_uint totals_[2] = {0, 0};
  ClTable<cl_long> shapes_;
  ClTable<cl_uint> uniforms_;
  ClTable<cl_int> values_;
  std::vector<cl_long> shapes_now_;
  std::vector<cl_uint> uniforms_now_;
  size_t group_ = 0;  // work-group size, from the kernel and the device, asked once
};

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

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return "opencl: unavailable: " + why;
    const Device& d = const_cast<OpenCLBackend*>(this)->device();
    return "opencl: " + d.info.platform_name + " / " + d.info.device_name + " (" + d.info.version +
           ")";
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
    Stopwatch stage;
    std::string source = emit_opencl(f, o.accuracy);
    const double codegen_ms = stage.lap();
    std::string options = "-cl-std=CL1.2";
    if (o.accuracy == Accuracy::Fast)
      options += " -cl-fast-relaxed-math -cl-mad-enable";
    else
      options += " -cl-fp32-correctly-rounded-divide-sqrt";
    const std::string key =
        "backend=opencl\n" + d.identity + "options=" + options + "\n" + cache::source_line(source);
    cl_program prog = program_from_cache(d, key, options);
    const KernelOrigin origin = prog ? KernelOrigin::DiskCache : KernelOrigin::Built;
    cl_int e = CL_SUCCESS;
    if (!prog) {
      const char* text = source.c_str();
      size_t len = source.size();
      prog = clCreateProgramWithSource(d.context, 1, &text, &len, &e);
      check(e, "clCreateProgramWithSource");
      e = clBuildProgram(prog, 1, &d.id, options.c_str(), nullptr, nullptr);
      if (e != CL_SUCCESS) {
        size_t n = 0;
        clGetProgramBuildInfo(prog, d.id, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string log(n, '\0');
        clGetProgramBuildInfo(prog, d.id, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
        clReleaseProgram(prog);
        throw Error("OpenCL backend: the driver (" + d.info.device_name + ") rejected kernel '" +
                    f.name + "' (" + cl_error_name(e) + "):\n" + log + "\ngenerated source:\n" +
                    codegen::numbered(source));
      }
      store_binary(prog, key);
    }
    cl_kernel k = clCreateKernel(prog, "rill_run", &e);
    if (e != CL_SUCCESS) clReleaseProgram(prog);
    check(e, "clCreateKernel");
    auto kernel = std::make_unique<ClKernel>(*this, f, std::move(source), prog, k);
    kernel->set_origin(origin);
    kernel->set_build_times(codegen_ms, stage.lap());
    return kernel;
  }

  // Makes the device copy of s current and returns its buffer.
  cl_mem to_device(detail::Storage& s) {
    Device& d = device();
    auto* buf = s.device_buffer<ClBuffer>(this);
    if (buf && s.is_device_current(this)) return buf->mem;
    const uint32_t* host = s.host_data_for_read();
    size_t bytes = std::max<size_t>(4, s.words() * 4);
    // A buffer that is stale in some words only gets just those (Storage::stale_words).
    auto [first, end] = s.stale_words();
    if (!buf || buf->bytes != bytes) {
      first = 0;
      end = s.words();
      auto fresh = std::make_unique<ClBuffer>();
      cl_int e = CL_SUCCESS;
      check_allocation(d, bytes);
      fresh->mem = clCreateBuffer(d.context, CL_MEM_READ_WRITE, bytes, nullptr, &e);
      check(e, "clCreateBuffer");
      fresh->bytes = bytes;
      buf = fresh.get();
      s.set_device_buffer(this, std::move(fresh));
    }
    if (end > first)
      check(clEnqueueWriteBuffer(d.queue, buf->mem, CL_TRUE, first * 4, (end - first) * 4,
                                 host + first, 0, nullptr, nullptr),
            "clEnqueueWriteBuffer");
    s.mark_device_current(this);
    return buf->mem;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override {
    auto* buf = s.device_buffer<ClBuffer>(this);
    if (s.words() != 0)
      check(clEnqueueReadBuffer(device().queue, buf->mem, CL_TRUE, 0, s.words() * 4, host, 0,
                                nullptr, nullptr),
            "clEnqueueReadBuffer");
  }

  cl_mem scratch(size_t bytes, const void* data) {
    Device& d = device();
    cl_int e = CL_SUCCESS;
    // Kernels always get a buffer, even for an empty table; pad to 8 bytes.
    check_allocation(d, std::max<size_t>(bytes, 8));
    std::vector<unsigned char> copy(std::max<size_t>(bytes, 8), 0);
    if (bytes) std::memcpy(copy.data(), data, bytes);
    cl_mem m = clCreateBuffer(d.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, copy.size(),
                              copy.data(), &e);
    check(e, "clCreateBuffer");
    return m;
  }

  Device& device() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (dev_) return *dev_;
    if (!init_error_.empty()) throw Error(init_error_);
    try {
      Found found = enumerate();
      if (found.ids.empty()) throw Error(found.error);
      const char* env = std::getenv("RILL_OPENCL_DEVICE");
      size_t i = choose(found, spec_.empty() && env ? std::string(env) : spec_);
      auto d = std::make_unique<Device>();
      d->info = found.infos[i];
      d->id = found.ids[i];
      d->identity = cache_identity(d->id);
      cl_int e = CL_SUCCESS;
      d->context = clCreateContext(nullptr, 1, &d->id, nullptr, nullptr, &e);
      check(e, "clCreateContext");
      // Profiling on: each launch reports how long its kernel ran (LaunchResult::device_ms).
      d->queue = clCreateCommandQueue(d->context, d->id, CL_QUEUE_PROFILING_ENABLE, &e);
      check(e, "clCreateCommandQueue");
      clGetDeviceInfo(d->id, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof d->max_group, &d->max_group,
                      nullptr);
      clGetDeviceInfo(d->id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof d->max_alloc, &d->max_alloc,
                      nullptr);
      if (const char* m = std::getenv("RILL_OPENCL_MAX_ALLOC_MB"); m && *m) {
        char* end = nullptr;
        const unsigned long long mb = std::strtoull(m, &end, 10);
        if (*end != '\0' || mb < 1 || mb > (1ull << 30))
          throw Error(std::string("RILL_OPENCL_MAX_ALLOC_MB='") + m +
                      "' is not a size in MiB (1..1073741824)");
        const cl_ulong lower = static_cast<cl_ulong>(mb) << 20;
        if (d->max_alloc == 0 || lower < d->max_alloc) {
          d->max_alloc = lower;
          d->max_alloc_from_env = true;
        }
      }
      dev_ = std::move(d);
    } catch (const Error& e) {
      init_error_ = e.what();
      throw;
    }
    return *dev_;
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
  std::string init_error_, spec_;
};

OpenCLBackend* g_backend = nullptr;

template <class T>
cl_mem ClKernel::table(ClTable<T>& t, const std::vector<T>& now) {
  const size_t bytes = now.size() * sizeof(T);
  if (!t.mem || bytes > t.bytes) {
    if (t.mem) clReleaseMemObject(t.mem);
    t.mem = nullptr;
    t.bytes = std::max<size_t>(bytes, 8);  // kernels always get a buffer, even for an empty table
    t.mem = be_.scratch(bytes, now.data());
  } else if (now != t.uploaded && bytes != 0) {
    check(clEnqueueWriteBuffer(be_.device().queue, t.mem, CL_TRUE, 0, bytes, now.data(), 0, nullptr,
                               nullptr),
          "clEnqueueWriteBuffer");
  }
  t.uploaded = now;
  return t.mem;
}

LaunchResult ClKernel::run(const LaunchArgs& a) {
  Device& d = be_.device();
  cl_uint arg = 0;
  auto set_mem = [&](cl_mem m) {
    check(clSetKernelArg(kernel_, arg++, sizeof(cl_mem), &m), "clSetKernelArg");
  };
  for (auto* s : a.inputs) set_mem(be_.to_device(*s));
  for (auto* s : a.outputs) set_mem(be_.to_device(*s));
  shapes_now_.clear();
  for (auto* arr : a.arrays) {
    set_mem(be_.to_device(*arr));
    shapes_now_.insert(shapes_now_.end(), {arr->shape[0], arr->shape[1], arr->shape[2]});
  }
  uniforms_now_.clear();
  for (auto* u : a.uniforms)
    uniforms_now_.insert(uniforms_now_.end(), u->bits.begin(), u->bits.end());
  if (!counter_) {
    totals_[0] = totals_[1] = 0;
    counter_ = be_.scratch(sizeof totals_, totals_);
  }
  cl_long width = a.width, count = a.count;
  set_mem(table(shapes_, shapes_now_));
  set_mem(table(uniforms_, uniforms_now_));
  check(clSetKernelArg(kernel_, arg++, sizeof width, &width), "clSetKernelArg");
  check(clSetKernelArg(kernel_, arg++, sizeof count, &count), "clSetKernelArg");
  set_mem(counter_);
  // The mask (none: an empty set, and the values table stands in for the state stream).
  cl_mem values_buf = table(values_, a.mask_values);
  cl_int mask_count = a.mask ? static_cast<cl_int>(a.mask_values.size()) : 0;
  set_mem(a.mask ? be_.to_device(*a.mask) : values_buf);
  set_mem(values_buf);
  check(clSetKernelArg(kernel_, arg++, sizeof mask_count, &mask_count), "clSetKernelArg");
  // 2D launches run in 8 x 4 tiles (OpenCLEmitter.cpp) unless RILL_OPENCL_TILES=off.
  const LaunchTuning& tuning = launch_tuning();
  cl_int tiled = tuning.tiles && a.height > 1 && !a.warm_up ? 1 : 0;
  check(clSetKernelArg(kernel_, arg++, sizeof tiled, &tiled), "clSetKernelArg");

  cl_uint written[2] = {0, 0};
  double device_ms = 0;  // nothing ran
  if (a.count > 0 || a.warm_up) {
    if (group_ == 0) {
      size_t kernel_group = 0;
      clGetKernelWorkGroupInfo(kernel_, d.id, CL_KERNEL_WORK_GROUP_SIZE, sizeof kernel_group,
                               &kernel_group, nullptr);
      group_ = std::max<size_t>(
          1, std::min({tuning.group, kernel_group ? kernel_group : tuning.group, d.max_group}));
    }
    // A warm-up runs no element (count 0) but spans warm_up_grid_ work-items (warm_up()).
    size_t span = a.warm_up ? warm_up_grid_ : static_cast<size_t>(a.count);
    if (tiled) span = static_cast<size_t>(codegen::tiled_invocations(a.width, a.height));
    size_t global = (span + group_ - 1) / group_ * group_;
    cl_uint totals[2] = {0, 0};
    // The blocking read of the counter is the launch's only wait: it returns once the kernel
    // has run (the queue is in order).
    cl_event ran = nullptr;
    cl_int e =
        clEnqueueNDRangeKernel(d.queue, kernel_, 1, nullptr, &global, &group_, 0, nullptr, &ran);
    if (e == CL_SUCCESS)
      e = clEnqueueReadBuffer(d.queue, counter_, CL_TRUE, 0, sizeof totals, totals, 0, nullptr,
                              nullptr);
    device_ms = -1;
    if (ran) {
      cl_ulong start = 0, end = 0;
      if (e == CL_SUCCESS &&
          clGetEventProfilingInfo(ran, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr) ==
              CL_SUCCESS &&
          clGetEventProfilingInfo(ran, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr) ==
              CL_SUCCESS &&
          end >= start)
        device_ms = static_cast<double>(end - start) * 1e-6;
      clReleaseEvent(ran);
    }
    if (e != CL_SUCCESS) {
      // The totals are unknown now: the next launch starts a fresh counter.
      clReleaseMemObject(counter_);
      counter_ = nullptr;
      check(e, "running the kernel");
    }
    for (int i = 0; i < 2; ++i) {
      written[i] = totals[i] - totals_[i];
      totals_[i] = totals[i];
    }
  }
  const int64_t selected = a.mask ? written[1] : a.count;
  // The device wrote the outputs: their host copies are stale until read back.
  for (auto* s : a.outputs) s->mark_device_written(&be_);
  return {written[0], selected, device_ms};
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
  return enumerate().infos;
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
