// The vulkan backend's launcher role: a kernel's compute pipelines (one per group of outputs
// that fits the device's storage-buffer bindings, as on glsl-compute) and their launch.
// A launch writes each pass's parameter buffer (count, width, tiling, mask values, strict
// constants, uniforms, array shapes: GLSLEmitter.h, VulkanTarget), points each pass's
// descriptor set at its streams, arrays, counters and parameters, records the dispatches
// (one invocation per element, work groups of the device's local size over a 2D grid, 2D
// launches in 8 x 4 tiles) with barriers between passes, submits them and waits, then reads
// the counts of elements written and selected. The command buffer and fence are the
// context's, reused by every launch; descriptor sets are the kernel's, made at compile time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "VkMemory.h"
#include "WarmUpLaunch.h"
#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::vk {

// What launches need from the backend: the device's launch layout and the counter buffer.
struct LaunchSetup {
  int local_size = 64;  // invocations per work group (RILL_VULKAN_LOCAL_SIZE)
  bool tiles = true;    // 2D launches in 8 x 4 tiles
  bool loop_guard = false;
  Buffer* counter = nullptr;    // written, selected, loops cut
  Staging* staging = nullptr;   // uploads to device-only memory
  bool params_uniform = false;  // the parameters are a uniform buffer (RILL_VULKAN_PARAMS)
};

class VulkanKernel : public CompiledKernel {
 public:
  // One dispatch: every element computes the whole kernel and stores these outputs.
  struct Pass {
    std::vector<int> outputs;
    std::vector<uint32_t> constants;  // strict constants, rill_k[]
    VkShaderModule module = VK_NULL_HANDLE;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
    VkDescriptorSet set = VK_NULL_HANDLE;
    std::unique_ptr<Buffer> params;
    int bindings = 0;
  };
  VulkanKernel(Backend& be, std::shared_ptr<Session> session, const LaunchSetup& setup,
               ir::Function f, std::vector<Pass> passes, VkDescriptorPool pool, std::string source)
      : be_(be),
        session_(std::move(session)),
        setup_(setup),
        fn_(std::move(f)),
        passes_(std::move(passes)),
        pool_(pool),
        source_(std::move(source)) {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    session_->live[this] = [this](Context& c) { release(c); };
  }
  ~VulkanKernel() override;
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // Mesa's lavapipe compiles a pipeline's machine code at its first dispatch: a launch over no
  // elements (one group whose invocations return at once) has it do so now.
  void warm_up() override { run(WarmUpLaunch(fn_).args()); }

 private:
  void release(Context& c) noexcept;  // frees the passes' objects and the pool
  Backend& be_;
  std::shared_ptr<Session> session_;
  const LaunchSetup& setup_;  // the backend's, which outlives run()
  ir::Function fn_;
  std::vector<Pass> passes_;
  VkDescriptorPool pool_;
  std::string source_;
  std::vector<uint32_t> words_;  // per launch, kept to reuse their memory
};

// Destroys a pass's Vulkan objects (for compile() failing half way, and the kernel).
void destroy_pass(Context& c, VulkanKernel::Pass& p);

}  // namespace rill::vk
