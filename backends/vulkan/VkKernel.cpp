// The vulkan backend's launcher role (VkKernel.h).
#include "VkKernel.h"

#include <algorithm>
#include <cstring>

#include "../codegen/Tiles.h"
#include "../glsl/GLSLEmitter.h"
#include "../glsl/GLSession.h"
#include "rill/Error.h"

namespace rill::vk {

void destroy_pass(Context& c, VulkanKernel::Pass& p) {
  if (p.pipeline) c.api.vkDestroyPipeline(c.device, p.pipeline, nullptr);
  if (p.layout) c.api.vkDestroyPipelineLayout(c.device, p.layout, nullptr);
  if (p.set_layout) c.api.vkDestroyDescriptorSetLayout(c.device, p.set_layout, nullptr);
  if (p.module) c.api.vkDestroyShaderModule(c.device, p.module, nullptr);
  p.pipeline = VK_NULL_HANDLE;
  p.layout = VK_NULL_HANDLE;
  p.set_layout = VK_NULL_HANDLE;
  p.module = VK_NULL_HANDLE;
}

void VulkanKernel::release(Context& c) noexcept {
  for (Pass& p : passes_) destroy_pass(c, p);
  if (pool_) c.api.vkDestroyDescriptorPool(c.device, pool_, nullptr);
  pool_ = VK_NULL_HANDLE;
}

VulkanKernel::~VulkanKernel() {
  std::lock_guard<std::recursive_mutex> lock(session_->mutex);
  session_->live.erase(this);
  if (Context* c = session_->context.get()) release(*c);
  for (Pass& p : passes_) p.params.reset();  // its own entry in `live`
}

LaunchResult VulkanKernel::run(const LaunchArgs& a) {
  if (a.count == 0 && !a.warm_up) return {0, 0, 0.0};  // nothing ran
  if (a.count > INT32_MAX)
    throw Error(std::string(kWho) + ": kernel '" + fn_.name + "': " + std::to_string(a.count) +
                " elements, over the 2^31 - 1 a launch can number");
  std::lock_guard<std::recursive_mutex> lock(session_->mutex);
  if (!session_->context) throw Error(std::string(kWho) + ": the device was shut down");
  Context& c = *session_->context;
  const std::string who = "kernel '" + fn_.name + "'";
  // Streams and arrays on the device. With several passes, an input that is also an output
  // is read from a copy taken before the first pass stores into it.
  // (The copies are the launch's first commands.)
  std::vector<std::unique_ptr<Buffer>> copies;
  std::vector<std::pair<VkBuffer, int64_t>> copied;  // each copy's source and size
  Staging& staging = *setup_.staging;
  auto readable = [&](detail::StreamState* s, const std::string& what) -> VkBuffer {
    Buffer& b = to_device(be_, session_, staging, *s, who + ": " + what);
    const bool also_output = std::find(a.outputs.begin(), a.outputs.end(), s) != a.outputs.end();
    if (!also_output || passes_.size() == 1) return b.buf;
    copies.push_back(make_buffer(session_, b.bytes, who + ": a copy of " + what, Memory::Streams));
    copied.emplace_back(b.buf, b.bytes);
    return copies.back()->buf;
  };
  std::vector<VkBuffer> inputs, arrays;
  for (size_t i = 0; i < a.inputs.size(); ++i)
    inputs.push_back(readable(a.inputs[i], "input " + std::to_string(i)));
  const VkBuffer mask = a.mask ? readable(a.mask, "the mask") : setup_.counter->buf;
  for (auto* arr : a.arrays)
    arrays.push_back(
        to_device(be_, session_, staging, *arr, who + ": array '" + arr->name + "'").buf);
  std::vector<VkBuffer> outputs;
  for (size_t o = 0; o < a.outputs.size(); ++o)
    outputs.push_back(
        to_device(be_, session_, staging, *a.outputs[o], who + ": output " + std::to_string(o))
            .buf);
  std::memset(setup_.counter->mapped, 0, 16);
  // Each pass's parameters and descriptor set (the last launch has finished: run() waits).
  const bool tiled = setup_.tiles && a.height > 1 && !a.warm_up;
  for (Pass& p : passes_) {
    words_.assign(glsl::kVulkanParamsHeader, 0);
    words_[0] = static_cast<uint32_t>(a.count);
    words_[1] = static_cast<uint32_t>(a.width);
    words_[2] = tiled ? 1u : 0u;
    words_[3] = a.mask ? static_cast<uint32_t>(a.mask_values.size()) : 0u;
    words_[4] = 0x3f800000u;  // rill_one: 1.0f
    for (size_t k = 0; a.mask && k < a.mask_values.size(); ++k)
      words_[5 + k] = static_cast<uint32_t>(a.mask_values[k]);
    words_.insert(words_.end(), p.constants.begin(), p.constants.end());
    for (auto* u : a.uniforms) words_.insert(words_.end(), u->bits.begin(), u->bits.end());
    for (auto* arr : a.arrays)
      for (int d = 0; d < 3; ++d) words_.push_back(static_cast<uint32_t>(arr->shape[d]));
    const int64_t bytes = static_cast<int64_t>(words_.size()) * 4;
    if (setup_.params_uniform && static_cast<uint64_t>(bytes) > c.info.limits.maxUniformBufferRange)
      throw Error(std::string(kWho) + ": " + who + ": its parameters take " +
                  std::to_string(bytes) + " bytes, over the device's uniform buffer range (" +
                  std::to_string(c.info.limits.maxUniformBufferRange) +
                  "); run without RILL_VULKAN_PARAMS=uniform");
    if (!p.params || p.params->bytes < bytes)
      p.params = make_buffer(session_, bytes, who + ": its parameters");
    std::memcpy(p.params->mapped, words_.data(), static_cast<size_t>(bytes));
    const glsl::ComputeBindings bind = glsl::compute_bindings(fn_, p.outputs.size());
    std::vector<VkDescriptorBufferInfo> infos(static_cast<size_t>(p.bindings));
    auto at = [&](int binding, VkBuffer b) {
      infos[static_cast<size_t>(binding)] = {b, 0, VK_WHOLE_SIZE};
    };
    for (size_t i = 0; i < inputs.size(); ++i) at(bind.inputs + static_cast<int>(i), inputs[i]);
    for (size_t k = 0; k < p.outputs.size(); ++k)
      at(bind.outputs + static_cast<int>(k), outputs[static_cast<size_t>(p.outputs[k])]);
    at(bind.counts, setup_.counter->buf);
    at(bind.mask, mask);
    for (size_t i = 0; i < arrays.size(); ++i) at(bind.arrays + static_cast<int>(i), arrays[i]);
    at(bind.params, p.params->buf);
    // The parameters are the last binding; a uniform buffer, a write of their own.
    const bool uniform = setup_.params_uniform;
    VkWriteDescriptorSet w[2];
    w[0] = make<VkWriteDescriptorSet>(VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    w[0].dstSet = p.set;
    w[0].dstBinding = 0;
    w[0].descriptorCount = static_cast<uint32_t>(infos.size()) - (uniform ? 1u : 0u);
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[0].pBufferInfo = infos.data();
    w[1] = w[0];
    w[1].dstBinding = static_cast<uint32_t>(bind.params);
    w[1].descriptorCount = 1;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w[1].pBufferInfo = &infos[static_cast<size_t>(bind.params)];
    c.api.vkUpdateDescriptorSets(c.device, uniform ? 2 : 1, w, 0, nullptr);
  }
  // The dispatches, timed by two timestamps where the queue has them.
  VkCommandBuffer cb = c.commands;
  check(c.api.vkResetCommandBuffer(cb, 0), "resetting the command buffer");
  auto begin = make<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(c.api.vkBeginCommandBuffer(cb, &begin), "recording a launch");
  for (size_t i = 0; i < copies.size(); ++i)
    record_copy(c, cb, copied[i].first, copies[i]->buf, 0, 0, copied[i].second);
  // The last launch's and copies' writes before this launch's reads.
  auto before = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  c.api.vkCmdPipelineBarrier(
      cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
  if (c.timer) {
    c.api.vkCmdResetQueryPool(cb, c.timer, 0, 2);
    c.api.vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, c.timer, 0);
  }
  const int64_t span = tiled ? codegen::tiled_invocations(a.width, a.height) : a.count;
  const int64_t groups = std::max<int64_t>(1, (span + setup_.local_size - 1) / setup_.local_size);
  const int64_t gx = std::min<int64_t>(groups, c.info.limits.maxComputeWorkGroupCount[0]);
  const int64_t gy = (groups + gx - 1) / gx;
  auto between = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  between.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  between.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT;
  for (size_t i = 0; i < passes_.size(); ++i) {
    Pass& p = passes_[i];
    if (i > 0)
      c.api.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                 VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &between, 0, nullptr,
                                 0, nullptr);
    c.api.vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    c.api.vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, p.layout, 0, 1, &p.set, 0,
                                  nullptr);
    c.api.vkCmdDispatch(cb, static_cast<uint32_t>(gx), static_cast<uint32_t>(gy), 1);
  }
  if (c.timer) c.api.vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, c.timer, 1);
  // The host reads the counts and outputs through its mappings once the fence signals.
  auto to_host = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  c.api.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                             0, 1, &to_host, 0, nullptr, 0, nullptr);
  check(c.api.vkEndCommandBuffer(cb), "recording a launch");
  c.submit_and_wait("running " + who);
  double device_ms = -1;
  if (c.timer) {
    uint64_t ticks[2] = {0, 0};
    if (c.api.vkGetQueryPoolResults(c.device, c.timer, 0, 2, sizeof ticks, ticks, sizeof ticks[0],
                                    VK_QUERY_RESULT_64_BIT) == VK_SUCCESS &&
        ticks[1] >= ticks[0])
      device_ms = static_cast<double>(ticks[1] - ticks[0]) * c.info.timestamp_ns * 1e-6;
  }
  uint32_t counts[3];
  std::memcpy(counts, setup_.counter->mapped, sizeof counts);
  for (auto* s : a.outputs) s->mark_device_written(&be_);
  c.check_validation("running " + who);
  if (counts[2] != 0) throw Error(glsl::loop_cut_message(kWho, fn_.name, c.info.name));
  return {counts[0], a.mask ? static_cast<int64_t>(counts[1]) : a.count, device_ms};
}

}  // namespace rill::vk
