// The OpenCL backend's compiler role: a kernel's OpenCL C (OpenCLEmitter.h) to a built program
// and its kernel, with the build options of its accuracy mode. A binary in Rill's disk cache
// (backends/cache) stands in for the build when its key matches: the device, the driver, the
// options and the source; on PoCL, whose own kernel cache does that job, Rill keeps none by
// default (keeps_binaries).
#pragma once

#include <string>

#include "ClDevice.h"
#include "rill/Backend.h"

namespace rill::opencl {

// A built program and its kernel (rill_run), and where the program came from.
struct BuiltKernel {
  cl_program program = nullptr;
  cl_kernel kernel = nullptr;
  KernelOrigin origin = KernelOrigin::Built;
};

// The build options of an accuracy mode: correctly rounded division and square root, except
// in `fast`.
std::string build_options(Accuracy a);

// Whether Rill's disk cache keeps this device's program binaries: RILL_OPENCL_BINARIES=on or
// off, or auto (the default, also when unset): on, except on PoCL with its kernel cache on
// (POCL_KERNEL_CACHE unset, or starting with 1 as PoCL reads it). Throws rill::Error naming a
// value that is none of these.
bool keeps_binaries(const Device& d);

// Builds `source` (the kernel named `name`, for errors) for device d. Throws rill::Error with
// the driver's build log and the numbered source when the driver rejects it.
BuiltKernel build_kernel(const Device& d, const std::string& name, const std::string& source,
                         Accuracy a);

}  // namespace rill::opencl
