// The Vulkan compute backend, `vulkan`: the GLSL compute emitter's kernels in its Vulkan
// dialect, compiled in-process to SPIR-V by glslang and run through the Vulkan API on the
// device RILL_VULKAN_DEVICE names (see VulkanBackend.cpp).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rill/Backend.h"

namespace rill::vk {

std::unique_ptr<Backend> make_backend();

// The Vulkan devices the loader sees, for rill-info and rill-trace info: a heading naming
// RILL_VULKAN_DEVICE, then one line per device (index, name, type, Vulkan version, subgroup
// size), the one the backend uses marked with the reason. Empty where the loader is missing
// or sees no device (the backend's own line says why).
std::vector<std::string> device_lines();

}  // namespace rill::vk
