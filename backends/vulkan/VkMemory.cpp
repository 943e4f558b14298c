// The vulkan backend's buffers (VkMemory.h).
#include "VkMemory.h"

#include <algorithm>
#include <cstring>

#include "rill/Error.h"

namespace rill::vk {

void Session::shut_down() noexcept {
  std::lock_guard<std::recursive_mutex> lock(mutex);
  if (context)
    for (auto& entry : live) entry.second(*context);
  live.clear();
  context.reset();
}

void Buffer::release(Context& c) noexcept {
  if (buf) c.api.vkDestroyBuffer(c.device, buf, nullptr);
  if (mem) c.api.vkFreeMemory(c.device, mem, nullptr);
  buf = VK_NULL_HANDLE;
  mem = VK_NULL_HANDLE;
  mapped = nullptr;
}

Buffer::~Buffer() {
  if (!session) return;
  std::lock_guard<std::recursive_mutex> lock(session->mutex);
  session->live.erase(this);
  if (Context* c = session->context.get()) release(*c);
}

std::unique_ptr<Buffer> make_buffer(const std::shared_ptr<Session>& session, int64_t bytes,
                                    const std::string& what, Memory where) {
  Context& c = *session->context;
  bytes = std::max<int64_t>(16, (bytes + 3) / 4 * 4);
  if (static_cast<uint64_t>(bytes) > c.info.limits.maxStorageBufferRange)
    throw Error(std::string(kWho) + ": " + what + " holds " + std::to_string(bytes) +
                " bytes, over the device's limit for a storage buffer (maxStorageBufferRange, " +
                std::to_string(c.info.limits.maxStorageBufferRange) + " bytes on " + c.info.name +
                ")");
  const uint32_t type = where == Memory::Streams    ? c.info.stream_memory_type
                        : where == Memory::Readback ? c.info.readback_memory_type
                                                    : c.info.memory_type;
  const bool map = where != Memory::Streams || c.info.streams_mapped;
  auto b = std::make_unique<Buffer>();
  b->session = session;
  b->bytes = bytes;
  b->cached = where == Memory::Streams    ? c.info.streams_cached
              : where == Memory::Readback ? true
                                          : false;
  {
    std::lock_guard<std::recursive_mutex> lock(session->mutex);
    Buffer* raw = b.get();
    session->live[raw] = [raw](Context& ctx) { raw->release(ctx); };
  }
  auto bi = make<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  bi.size = static_cast<VkDeviceSize>(bytes);
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
             VK_BUFFER_USAGE_TRANSFER_DST_BIT |
             (where == Memory::Host ? VkBufferUsageFlags{VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT} : 0u);
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(c.api.vkCreateBuffer(c.device, &bi, nullptr, &b->buf), "creating a buffer for " + what);
  VkMemoryRequirements req{};
  c.api.vkGetBufferMemoryRequirements(c.device, b->buf, &req);
  if (!(req.memoryTypeBits & (1u << type)))
    throw Error(std::string(kWho) + ": the device's buffers cannot live in its memory type " +
                std::to_string(type) + " (for " + what + "); Rill needs them to");
  auto ai = make<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = type;
  check(c.api.vkAllocateMemory(c.device, &ai, nullptr, &b->mem),
        "allocating " + std::to_string(req.size) + " bytes for " + what);
  check(c.api.vkBindBufferMemory(c.device, b->buf, b->mem, 0), "binding memory for " + what);
  if (map)
    check(c.api.vkMapMemory(c.device, b->mem, 0, VK_WHOLE_SIZE, 0, &b->mapped),
          "mapping memory for " + what);
  return b;
}

void record_copy(Context& c, VkCommandBuffer cb, VkBuffer from, VkBuffer to, int64_t from_offset,
                 int64_t to_offset, int64_t bytes) {
  auto before = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  before.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  c.api.vkCmdPipelineBarrier(cb,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0, nullptr);
  VkBufferCopy region{static_cast<VkDeviceSize>(from_offset), static_cast<VkDeviceSize>(to_offset),
                      static_cast<VkDeviceSize>(bytes)};
  c.api.vkCmdCopyBuffer(cb, from, to, 1, &region);
  auto after = make<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
  after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  after.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                        VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                        VK_ACCESS_HOST_READ_BIT;
  c.api.vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                                 VK_PIPELINE_STAGE_HOST_BIT,
                             0, 1, &after, 0, nullptr, 0, nullptr);
}

namespace {

// The staging buffer `b`, grown to hold `bytes` at least.
Buffer& staging_buffer(const std::shared_ptr<Session>& session, std::unique_ptr<Buffer>& b,
                       int64_t bytes, Memory where, const char* what) {
  if (!b || b->bytes < bytes) {
    b.reset();  // before the new one: the old one's memory back first
    b = make_buffer(session, std::max<int64_t>(bytes, 1 << 16), what, where);
  }
  return *b;
}

// One copy between buffers, recorded, submitted and waited for (the context's command
// buffer and fence, reused: no launch is being recorded while a stream moves).
void copy_now(Context& c, VkBuffer from, VkBuffer to, int64_t from_offset, int64_t to_offset,
              int64_t bytes, const std::string& what) {
  check(c.api.vkResetCommandBuffer(c.commands, 0), "resetting the command buffer");
  auto begin = make<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(c.api.vkBeginCommandBuffer(c.commands, &begin), "recording a copy of " + what);
  record_copy(c, c.commands, from, to, from_offset, to_offset, bytes);
  check(c.api.vkEndCommandBuffer(c.commands), "recording a copy of " + what);
  c.submit_and_wait("copying " + what);
}

}  // namespace

Buffer& to_device(Backend& owner, const std::shared_ptr<Session>& session, Staging& staging,
                  detail::Storage& s, const std::string& what) {
  auto* b = s.device_buffer<Buffer>(&owner);
  if (b && s.is_device_current(&owner)) return *b;
  // The freshest copy may be another backend's: read back (to the host) first.
  const uint32_t* host = s.words() > 0 ? s.host_data_for_read() : nullptr;
  b = s.device_buffer<Buffer>(&owner);
  const int64_t bytes = std::max<int64_t>(16, static_cast<int64_t>(s.words()) * 4);
  auto [first, end] = s.stale_words();  // only the stale words of a buffer that exists
  if (!b || b->bytes != bytes) {
    first = 0;
    end = s.words();
    auto fresh = make_buffer(session, bytes, what, Memory::Streams);
    b = fresh.get();
    s.set_device_buffer(&owner, std::move(fresh));
  }
  if (host != nullptr && end > first) {
    const int64_t n = static_cast<int64_t>(end - first) * 4;
    if (b->mapped) {
      std::memcpy(static_cast<uint32_t*>(b->mapped) + first, host + first, static_cast<size_t>(n));
    } else {
      Buffer& up =
          staging_buffer(session, staging.up, n, Memory::Host, "the upload staging buffer");
      std::memcpy(up.mapped, host + first, static_cast<size_t>(n));
      copy_now(*session->context, up.buf, b->buf, 0, static_cast<int64_t>(first) * 4, n, what);
    }
  }
  s.mark_device_current(&owner);
  return *b;
}

void read_back(const Backend& owner, const std::shared_ptr<Session>& session, Staging& staging,
               const detail::Storage& s, uint32_t* host) {
  auto* b = s.device_buffer<Buffer>(&owner);
  if (s.words() == 0 || !b) return;
  const int64_t n = static_cast<int64_t>(s.words()) * 4;
  if (b->cached) {
    std::memcpy(host, b->mapped, static_cast<size_t>(n));
    return;
  }
  if (!session->context) throw Error(std::string(kWho) + ": the device was shut down");
  Buffer& down =
      staging_buffer(session, staging.down, n, Memory::Readback, "the read-back staging buffer");
  copy_now(*session->context, b->buf, down.buf, 0, 0, n, "a stream to the host");
  std::memcpy(host, down.mapped, static_cast<size_t>(n));
}

}  // namespace rill::vk
