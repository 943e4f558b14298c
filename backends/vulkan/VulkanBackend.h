// The Vulkan compute backend, `vulkan`: the GLSL compute emitter's kernels in its Vulkan
// dialect, compiled in-process to SPIR-V by glslang and run through the Vulkan API on the
// device RILL_VULKAN_DEVICE names (see VulkanBackend.cpp).
#pragma once

#include <memory>

#include "rill/Backend.h"

namespace rill::vk {

std::unique_ptr<Backend> make_backend();

}  // namespace rill::vk
