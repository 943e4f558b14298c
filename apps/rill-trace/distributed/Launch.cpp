// How rill-trace was launched (Launch.h).
#include "distributed/Launch.h"

#include <cstdlib>

#include "rill/Backend.h"
#include "rill/rt/scene/Scene.h"

namespace rt::distributed {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v == nullptr ? std::string() : std::string(v);
}

}  // namespace

int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    const std::string v = env(name);
    if (v.empty()) continue;
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (end != v.c_str() && *end == '\0' && n > 0 && n < (1l << 24)) return static_cast<int>(n);
  }
  return 0;
}

std::string rank_backend(const std::string& cli_backend, bool cli_given) {
  if (cli_given) return cli_backend;
  const std::string v = env("RILL_TRACE_BACKEND");
  if (v.empty()) return cli_backend;
  // Named here: without --backend, a message about an unknown name would leave the user
  // looking for where it came from.
  std::string known;
  for (rill::Backend* b : rill::backends()) {
    if (b->name() == v) return v;
    known += (known.empty() ? "" : ", ") + b->name();
  }
  throw SceneError("RILL_TRACE_BACKEND='" + clipped(v) +
                   "': unknown backend (this build has: " + known + ")");
}

std::string rank_device(const std::string& cli_device, int local_rank) {
  std::string spec = cli_device.empty() ? env("RILL_TRACE_DEVICE") : cli_device;
  const std::string key = "{local_rank}";
  for (size_t at; (at = spec.find(key)) != std::string::npos;)
    spec.replace(at, key.size(), std::to_string(local_rank));
  return spec;
}

void use_device(const std::string& backend, const std::string& spec) {
  if (spec.empty()) return;
  const char* var = nullptr;
  if (backend == "opencl") var = "RILL_OPENCL_DEVICE";
  if (backend == "glsl" || backend == "glsl-compute") var = "RILL_EGL_DEVICE";
  if (backend == "vulkan") var = "RILL_VULKAN_DEVICE";
  if (var == nullptr)
    throw SceneError("--device (or RILL_TRACE_DEVICE) '" + clipped(spec) +
                     "' is for the opencl, glsl, glsl-compute and vulkan backends, not " + backend);
  setenv(var, spec.c_str(), 1);
}

}  // namespace rt::distributed
