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

// glslang's front end on a compute shader in the GL dialect (glsl-compute's GLSL, as an
// OpenGL driver compiles it; no SPIR-V): its log when the shader does not compile and link,
// else empty. For tests of GLSL that the local GL driver cannot compile (an extension it
// lacks, GL_KHR_shader_subgroup on Mesa 22's llvmpipe).
std::string gl_compute_errors(const std::string& glsl);

// "glslang 12.0.0", for the disk cache's key and rill-info.
std::string spirv_compiler_version();

}  // namespace rill::vk
