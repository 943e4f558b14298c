// Registers the backends this build includes (see CMakeLists.txt: RILL_WITH_*).
#include "cpu/CpuBackend.h"
#include "simd/SimdBackend.h"
#ifdef RILL_HAVE_OPENCL
#include "opencl/OpenCLBackend.h"
#endif
#ifdef RILL_HAVE_GLSL
#include "glsl/ComputeBackend.h"
#include "glsl/GLSLBackend.h"
#endif
#ifdef RILL_HAVE_VULKAN
#include "vulkan/VulkanBackend.h"
#endif
#include "rill/Backend.h"

namespace rill::detail {

void register_builtin_backends() {
  register_backend(cpu::make_backend());
  register_backend(simd::make_backend());
#ifdef RILL_HAVE_OPENCL
  register_backend(opencl::make_backend());
#endif
#ifdef RILL_HAVE_GLSL
  register_backend(glsl::make_backend());
  register_backend(glsl::make_compute_backend());
#endif
#ifdef RILL_HAVE_VULKAN
  register_backend(vk::make_backend());
#endif
}

}  // namespace rill::detail
