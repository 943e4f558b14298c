// The vulkan backend's device memory: every stream and array is one storage buffer in
// device-local memory (VkContext.h: DeviceInfo::stream_memory_type), holding the host's words
// as they are. Where the host maps that memory, uploads (of the stale words only) are copies
// through the mapping, else through an upload staging buffer and vkCmdCopyBuffer; read-backs
// are copies through the mapping only where the memory is host-cached, else the device
// copies the buffer to a host-cached staging buffer first (reads of write-combined memory
// across the bus are slow). The staging buffers grow as needed and are kept. Parameters and
// counters live in host-visible memory, mapped. Every launch and copy waits for its fence, so
// a read-back never races a kernel.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>

#include "VkContext.h"
#include "rill/Stream.h"

namespace rill::vk {

// The context and its lock, shared by the backend, its kernels and buffers: a kernel or
// buffer destroyed after the backend shut down (at exit) finds `context` null and skips its
// Vulkan calls. Destroying a device does not free what was made with it (the application
// must, and drivers such as lavapipe leak it otherwise), so every buffer and kernel alive
// registers in `live` what frees its objects, and the backend's shutdown runs those first.
struct Session {
  std::recursive_mutex mutex;  // recursive: replacing a buffer inside a launch frees the old one
  std::unique_ptr<Context> context;
  std::map<const void*, std::function<void(Context&)>> live;  // under the lock
  // Frees every live object's Vulkan objects, then the device and instance (at exit).
  void shut_down() noexcept;
};

// One buffer and its memory, mapped where the host can map it.
struct Buffer : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  VkBuffer buf = VK_NULL_HANDLE;
  VkDeviceMemory mem = VK_NULL_HANDLE;
  void* mapped = nullptr;  // null: device-only memory
  bool cached = false;     // mapped and fast for the host to read
  int64_t bytes = 0;
  ~Buffer() override;
  void release(Context& c) noexcept;  // frees buf and mem (under the session's lock)
};

// Where a buffer lives: Host (memory_type: parameters, counters, probes, upload staging),
// Streams (stream_memory_type), Readback (readback_memory_type).
enum class Memory { Host, Streams, Readback };

// A buffer of `bytes` (at least 16) for storage and copies; throws Error naming the size when
// the device's storage-buffer range or memory does not allow it.
std::unique_ptr<Buffer> make_buffer(const std::shared_ptr<Session>& session, int64_t bytes,
                                    const std::string& what, Memory where = Memory::Host);

// The staging buffers of copies to and from device-only memory, grown as needed, kept.
struct Staging {
  std::unique_ptr<Buffer> up, down;
};

// The buffer holding s on behalf of `owner`, current with the host copy.
Buffer& to_device(Backend& owner, const std::shared_ptr<Session>& session, Staging& staging,
                  detail::Storage& s, const std::string& what);
// Copies s's buffer to host (s.words() words).
void read_back(const Backend& owner, const std::shared_ptr<Session>& session, Staging& staging,
               const detail::Storage& s, uint32_t* host);
// Records into the command buffer being recorded a copy of `bytes` from `from` to `to`
// (offsets in bytes), after every earlier shader or transfer write and before later
// shader and transfer accesses.
void record_copy(Context& c, VkCommandBuffer cb, VkBuffer from, VkBuffer to, int64_t from_offset,
                 int64_t to_offset, int64_t bytes);

}  // namespace rill::vk
