// The OpenCL device role (ClDevice.h).
#include "ClDevice.h"

#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "rill/Error.h"

namespace rill::opencl {

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

namespace {

// A string property of a platform or device: get is clGetPlatformInfo or clGetDeviceInfo,
// asked for the size first, without the terminating NULs.
template <class Get, class Id, class Info>
std::string info_string(Get get, Id id, Info what) {
  size_t n = 0;
  get(id, what, 0, nullptr, &n);
  std::string s(n, '\0');
  get(id, what, n, s.data(), nullptr);
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

std::string platform_string(cl_platform_id p, cl_platform_info what) {
  return info_string(clGetPlatformInfo, p, what);
}

std::string device_string(cl_device_id d, cl_device_info what) {
  return info_string(clGetDeviceInfo, d, what);
}

}  // namespace

Found enumerate_devices() {
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

namespace {

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

}  // namespace

bool is_pocl(const Device& d) {
  return d.info.platform_name.find("Portable Computing Language") != std::string::npos;
}

std::unique_ptr<Device> open_device(const std::string& spec) {
  Found found = enumerate_devices();
  if (found.ids.empty()) throw Error(found.error);
  const char* env = std::getenv("RILL_OPENCL_DEVICE");
  size_t i = choose(found, spec.empty() && env ? std::string(env) : spec);
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
  clGetDeviceInfo(d->id, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof d->max_alloc, &d->max_alloc, nullptr);
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
  return d;
}

void check_allocation(const Device& d, size_t bytes) {
  if (d.max_alloc == 0 || bytes <= d.max_alloc) return;
  auto mib = [](uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
  throw Error("OpenCL backend: a buffer of " + mib(bytes) + " is over the largest allocation of " +
              d.info.device_name + " (" +
              (d.max_alloc_from_env ? "RILL_OPENCL_MAX_ALLOC_MB" : "CL_DEVICE_MAX_MEM_ALLOC_SIZE") +
              ", " + mib(d.max_alloc) + ")");
}

}  // namespace rill::opencl
