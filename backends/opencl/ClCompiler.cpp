// The OpenCL backend's compiler role (ClCompiler.h).
#include "ClCompiler.h"

#include <cstdlib>

#include "../cache/DiskCache.h"
#include "../codegen/SourceText.h"

namespace rill::opencl {

namespace {

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

}  // namespace

// PoCL's kernel cache already keeps each program's bitcode and work-group functions, keyed on
// the source and the options, for any process; handing out a binary makes PoCL compile one more
// work-group function per kernel (a generic one, for any group size), a quarter to a third of
// a cold compile. With its cache on, a second compile of the same source in a new process takes
// 0.1-0.2 s there, as Rill's cache does.
bool keeps_binaries(const Device& d) {
  const char* env = std::getenv("RILL_OPENCL_BINARIES");
  const std::string v = env ? env : "";
  if (v == "on") return true;
  if (v == "off") return false;
  if (!v.empty() && v != "auto")
    throw Error("RILL_OPENCL_BINARIES='" + v + "' is not one of auto, on, off");
  if (!is_pocl(d)) return true;
  // PoCL reads a boolean setting as on when its value starts with 1 (pocl_get_bool_option),
  // so 0, off or an empty value turn its cache off.
  const char* pocl_cache = std::getenv("POCL_KERNEL_CACHE");
  return pocl_cache && pocl_cache[0] != '1';
}

std::string build_options(Accuracy a) {
  std::string options = "-cl-std=CL1.2";
  if (a == Accuracy::Fast)
    options += " -cl-fast-relaxed-math -cl-mad-enable";
  else
    options += " -cl-fp32-correctly-rounded-divide-sqrt";
  return options;
}

BuiltKernel build_kernel(const Device& d, const std::string& name, const std::string& source,
                         Accuracy a) {
  const std::string options = build_options(a);
  const std::string key =
      "backend=opencl\n" + d.identity + "options=" + options + "\n" + cache::source_line(source);
  const bool binaries = keeps_binaries(d);
  cl_program prog = binaries ? program_from_cache(d, key, options) : nullptr;
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
                  name + "' (" + cl_error_name(e) + "):\n" + log + "\ngenerated source:\n" +
                  codegen::numbered(source));
    }
    if (binaries) store_binary(prog, key);
  }
  cl_kernel k = clCreateKernel(prog, "rill_run", &e);
  if (e != CL_SUCCESS) clReleaseProgram(prog);
  check(e, "clCreateKernel");
  return BuiltKernel{prog, k, origin};
}

}  // namespace rill::opencl
