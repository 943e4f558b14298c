// The vulkan backend's device memory: every stream and array is one storage buffer in
// host-visible coherent memory, mapped for its lifetime, holding the host's words as they are.
// Uploads (of the stale words only) and read-backs are copies through the mapping; every
// launch waits for its dispatches, so a read-back never races a kernel.
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

// One buffer and its memory, mapped.
struct Buffer : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  VkBuffer buf = VK_NULL_HANDLE;
  VkDeviceMemory mem = VK_NULL_HANDLE;
  void* mapped = nullptr;
  int64_t bytes = 0;
  ~Buffer() override;
  void release(Context& c) noexcept;  // frees buf and mem (under the session's lock)
};

// A buffer of `bytes` (at least 16) for storage; throws Error naming the size when the
// device's storage-buffer range or memory does not allow it.
std::unique_ptr<Buffer> make_buffer(const std::shared_ptr<Session>& session, int64_t bytes,
                                    const std::string& what);

// The buffer holding s on behalf of `owner`, current with the host copy.
Buffer& to_device(Backend& owner, const std::shared_ptr<Session>& session, detail::Storage& s,
                  const std::string& what);
// Copies s's buffer to host (s.words() words).
void read_back(const Backend& owner, const detail::Storage& s, uint32_t* host);

}  // namespace rill::vk
