// GLSL to SPIR-V in-process, for the vulkan backend: glslang (its Vulkan 1.1 / SPIR-V 1.3
// target), then the module checked by SPIRV-Tools' validator, so that a module the driver
// would be handed is valid SPIR-V for Vulkan 1.1.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rill::vk {

// The SPIR-V of a compute shader; throws Error with glslang's or the validator's log and the
// numbered source when it does not compile. `kernel` names the kernel in messages.
// `scalar_layout`: the module may use scalar block layouts (the device's scalarBlockLayout is
// enabled), which the validator then allows.
std::vector<uint32_t> compile_compute_spirv(const std::string& glsl, const std::string& kernel,
                                            bool scalar_layout = false);

// "glslang 12.0.0", for the disk cache's key and rill-info.
std::string spirv_compiler_version();

}  // namespace rill::vk
