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
                                    const std::string& what) {
  Context& c = *session->context;
  bytes = std::max<int64_t>(16, (bytes + 3) / 4 * 4);
  if (static_cast<uint64_t>(bytes) > c.info.limits.maxStorageBufferRange)
    throw Error(std::string(kWho) + ": " + what + " holds " + std::to_string(bytes) +
                " bytes, over the device's limit for a storage buffer (maxStorageBufferRange, " +
                std::to_string(c.info.limits.maxStorageBufferRange) + " bytes on " + c.info.name +
                ")");
  auto b = std::make_unique<Buffer>();
  b->session = session;
  b->bytes = bytes;
  {
    std::lock_guard<std::recursive_mutex> lock(session->mutex);
    Buffer* raw = b.get();
    session->live[raw] = [raw](Context& ctx) { raw->release(ctx); };
  }
  auto bi = make<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
  bi.size = static_cast<VkDeviceSize>(bytes);
  bi.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(c.api.vkCreateBuffer(c.device, &bi, nullptr, &b->buf), "creating a buffer for " + what);
  VkMemoryRequirements req{};
  c.api.vkGetBufferMemoryRequirements(c.device, b->buf, &req);
  if (!(req.memoryTypeBits & (1u << c.info.memory_type)))
    throw Error(std::string(kWho) +
                ": the device's buffers cannot live in its host-visible "
                "memory type; Rill needs them to");
  auto ai = make<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = c.info.memory_type;
  check(c.api.vkAllocateMemory(c.device, &ai, nullptr, &b->mem),
        "allocating " + std::to_string(req.size) + " bytes for " + what);
  check(c.api.vkBindBufferMemory(c.device, b->buf, b->mem, 0), "binding memory for " + what);
  check(c.api.vkMapMemory(c.device, b->mem, 0, VK_WHOLE_SIZE, 0, &b->mapped),
        "mapping memory for " + what);
  return b;
}

Buffer& to_device(Backend& owner, const std::shared_ptr<Session>& session, detail::Storage& s,
                  const std::string& what) {
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
    auto fresh = make_buffer(session, bytes, what);
    b = fresh.get();
    s.set_device_buffer(&owner, std::move(fresh));
  }
  if (host != nullptr && end > first)
    std::memcpy(static_cast<uint32_t*>(b->mapped) + first, host + first, (end - first) * 4);
  s.mark_device_current(&owner);
  return *b;
}

void read_back(const Backend& owner, const detail::Storage& s, uint32_t* host) {
  auto* b = s.device_buffer<Buffer>(&owner);
  if (s.words() == 0 || !b) return;
  std::memcpy(host, b->mapped, s.words() * 4);
}

}  // namespace rill::vk
