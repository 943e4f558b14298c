// The OpenCL backend: kernels as OpenCL C on any OpenCL 1.2 device, PoCL by default.
//
// The platform and device are chosen by RILL_OPENCL_DEVICE (or set_device()):
//   unset            the first device of the first platform (PoCL on a machine without GPUs)
//   "P:D"            device D of platform P (indices as listed by list_devices())
//   "text"           the first device whose platform or device name contains text
//                    (case-insensitive), e.g. "nvidia" or "pthread"
// Streams and arrays live in device buffers and move only when the host or another backend
// needs them. Uniforms are kernel arguments. The written count comes from the device: each
// work-group counts its written elements in local memory and adds them to a global counter.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rill/Backend.h"

namespace rill::opencl {

struct DeviceInfo {
  int platform = 0, device = 0;
  std::string platform_name, device_name, version;
  bool fp64 = false;
  bool gpu = false;  // CL_DEVICE_TYPE_GPU
};

// Every OpenCL device on this machine (empty when there is no platform).
std::vector<DeviceInfo> list_devices();
// Chooses the device for kernels compiled from now on (same syntax as RILL_OPENCL_DEVICE).
void set_device(const std::string& spec);

std::unique_ptr<Backend> make_backend();

}  // namespace rill::opencl
