// Emits a kernel as a GLSL fragment or compute shader (see GLSLEmitter.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "DivSqrt.h"
#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::glsl {

// The stages the GLSL backends run kernels in: `glsl` and `glsl-compute`, and the compute
// stage in the Vulkan dialect (backend `vulkan`, VulkanTarget below).
enum class Stage { Fragment, Compute, Vulkan };

// The fragment stage's textures hold a stream or array of n elements in rows of
// min(n, kTextureRow) texels, so element g is texel (g % kTextureRow, g / kTextureRow) for
// every n (a row shorter than kTextureRow is the only row).
constexpr int kTextureRowBits = 12;
constexpr int kTextureRow = 1 << kTextureRowBits;

// How many state values a masked compute launch can select (StateMask::kMaxValues).
constexpr int kMaskValues = 8;

// What the generated code does differently per driver (found by the conformance suite).
struct DriverRules {
  DivSqrt divsqrt = DivSqrt::Native;  // strict / and sqrt (DivSqrt.h)
  bool fused_fma = false;             // their residual by one fma (DivSqrt.h, fused_fma_mode)
  bool lean = true;             // with fused_fma: the lean correction (DivSqrt.h, lean_fused_mode)
  bool native_compare = false;  // strict float comparisons: the driver's, or on bits
  // Mesa's llvmpipe ends every loop of a shader once a batch of lanes has run 65535 loop
  // iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS), silently. With the guard an element
  // checks, where it ends, whether that limit was spent (GLSLEmitter.cpp, loop_check), and
  // sets a word the backend reads after the launch (the fragment stage's rill_guard buffer,
  // binding kGuardBinding; the compute stage's counters) and reports as an error.
  bool loop_guard = false;
  // The compute stages (glsl-compute, vulkan): lane-group ops (rill/Group.h) as
  // GL_KHR_shader_subgroup operations, where the device has basic, vote, ballot, arithmetic
  // and shuffle operations in compute shaders (glsl/Subgroups.h, vk::DeviceInfo::group_ops).
  // Else, and always on the fragment stage, a group of one.
  bool subgroups = false;
};
// The fragment stage's storage buffer for DriverRules::loop_guard.
constexpr int kGuardBinding = 0;

struct GLSLShader {
  std::string source;
  std::vector<uint32_t> constants;  // bits of uniform uint rill_k[] (strict mode)
};

// The fragment shader computing `optimized` and writing the outputs listed (indices into
// Function::outputs), at draw-buffer locations 0, 1, ... in that order.
// Strict kernels divide, take square roots and compare as `rules` says.
// `source_map`: comments naming the user's lines (codegen/SourceMap.h), here and below.
GLSLShader emit_glsl(const ir::Function& optimized, Accuracy accuracy,
                     const std::vector<int>& outputs, const DriverRules& rules = {},
                     bool source_map = false);
// The compute shader computing `optimized` over `local_size` invocations per work group and
// storing the outputs listed (indices into Function::outputs; a kernel with more outputs
// than the driver has storage buffers runs in several passes, as on the fragment stage).
// `counts`: this pass counts the elements written and selected (the first pass does).
// Storage buffer bindings are compute_bindings(); array i is a buffer texture on unit i.
// `flushes_denormals`: whether the driver's compute arithmetic flushes denormals (then
// comparisons treat them as zero too, as on the fragment stage).
// The Vulkan dialect of the compute shader (GLSL 4.50 for glslang, descriptor set 0): arrays
// are storage buffers read word by word, and what GL passes as loose uniforms (the launch's
// count, width, tiling and mask values, strict constants, the kernel's uniforms, array
// shapes) is one read-only std430 storage buffer at ComputeBindings::params, laid out as
// vulkan_params_layout() says.
struct VulkanTarget {
  bool ballot = false;  // GL_KHR_shader_subgroup_ballot in compute shaders (else one atomic each)
  // Lines placed after #version: GL_EXT_spirv_intrinsics float-controls execution modes.
  std::string execution_modes;
  // The parameters as a uniform buffer in scalar layout (GL_EXT_scalar_block_layout) rather
  // than a read-only storage buffer (RILL_VULKAN_PARAMS=uniform, for measuring).
  bool params_uniform = false;
};
GLSLShader emit_glsl_compute(const ir::Function& optimized, Accuracy accuracy,
                             const std::vector<int>& outputs, bool counts, const DriverRules& rules,
                             bool flushes_denormals, int local_size,
                             const VulkanTarget* vulkan = nullptr, bool source_map = false);
// The Vulkan dialect's parameter buffer, in 4-byte words: count, width, tiled, nvalues, one,
// values[kMaskValues], then the pass's strict constants, the kernel's uniform words (4 per
// uniform) and array shapes (3 per array).
constexpr int kVulkanParamsHeader = 5 + kMaskValues;
// Where a compute pass's storage buffers are bound: inputs from `inputs` on, the pass's
// outputs from `outputs` on, then the two counters (elements written, selected) and the
// mask's states. The Vulkan dialect adds the arrays from `arrays` on (storage buffers, not
// buffer textures) and the launch's parameters at `params` (VulkanTarget).
struct ComputeBindings {
  int inputs = 0, outputs = 0, counts = 0, mask = 0, arrays = 0, params = 0;
  int total() const { return mask + 1; }
};
ComputeBindings compute_bindings(const ir::Function& f, size_t pass_outputs);

// The vertex shader every kernel is drawn with.
std::string vertex_shader();

// The rill_* helpers every generated GLSL kernel starts with (the division and square root
// of the driver's rules, then the op table's HELPER forms), for the completeness test.
std::string glsl_helpers(const ir::Function& f, Accuracy accuracy, const DriverRules& rules,
                         bool flushes_denormals);

}  // namespace rill::glsl
