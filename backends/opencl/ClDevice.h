// The OpenCL backend's device role: the platforms and devices of the machine, the one chosen
// (RILL_OPENCL_DEVICE or set_device(), OpenCLBackend.h) with its context, in-order queue and
// limits, and OpenCL's error codes as Rill errors. The compiler (ClCompiler.h), the device
// memory (ClMemory.h) and the launcher (ClLauncher.h) work on one Device; OpenCLBackend.cpp
// ties the three to the Backend interface.
#pragma once

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <memory>
#include <string>
#include <vector>

#include "OpenCLBackend.h"

namespace rill::opencl {

// The name of an OpenCL error code ("CL_OUT_OF_RESOURCES", else "OpenCL error N").
std::string cl_error_name(cl_int e);
// Throws rill::Error "OpenCL backend: <what> failed: <name>" unless e is CL_SUCCESS.
void check(cl_int e, const char* what);

// The chosen device: its context, queue and limits. The backend opens it at first use and never
// closes it (buffers of live streams refer to it).
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

// Every device of every platform; error says why there is none.
struct Found {
  std::vector<DeviceInfo> infos;
  std::vector<cl_device_id> ids;
  std::string error;
};
Found enumerate_devices();

// Opens the device that spec names (the syntax of RILL_OPENCL_DEVICE; empty: that variable,
// else the first device) with its context and queue. Throws rill::Error naming the devices
// there are when none matches, or why there is none.
std::unique_ptr<Device> open_device(const std::string& spec);

// Whether the device is PoCL's (its platform name), whose kernel cache and deferred
// work-group compiles the backend allows for.
bool is_pocl(const Device& d);

// A buffer over the device's largest allocation is an error naming both sizes and the device,
// before the driver is asked (some drivers fail later, at the launch, or not at all).
void check_allocation(const Device& d, size_t bytes);

}  // namespace rill::opencl
