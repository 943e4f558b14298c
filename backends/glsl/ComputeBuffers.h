// The glsl-compute backend's device memory role: every stream and array lives in one GL
// buffer object holding the host's words as they are (uploads and read-backs are plain copies,
// of the stale words only), with a buffer texture over it once the data is gathered from.
#pragma once

#include <memory>

#include "GLBackend.h"
#include "rill/Stream.h"

namespace rill::glsl {

// The backend in messages, and its name.
inline constexpr const char* kComputeName = "glsl-compute";
inline constexpr const char* kComputeWho = "glsl-compute backend";

// A stream's or array's device copy: a buffer object, and a buffer texture over it once the
// data is gathered from.
struct Buffer : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  GLuint buf = 0, tex = 0;
  int64_t bytes = 0;  // allocated
  ~Buffer() override {
    if (!buf && !tex) return;
    std::lock_guard<std::recursive_mutex> lock(session->mutex);
    if (const GL* gl = session->current_if_alive()) {
      if (tex) gl->glDeleteTextures(1, &tex);
      if (buf) gl->glDeleteBuffers(1, &buf);
    }
  }
};

// The memory role itself: the device buffers of one backend, under its lock.
class ComputeBuffers {
 public:
  // owner: the backend whose buffers these are; its context is made current where another
  // backend's copy had to be read back first.
  ComputeBuffers(GLBackend& owner, std::shared_ptr<Session> session)
      : owner_(owner), session_(std::move(session)) {}
  // The buffer holding s, current with the host copy.
  Buffer& to_device(const GL& gl, detail::Storage& s);
  // The buffer texture over s's buffer, for gathers.
  GLuint texture_of(const GL& gl, detail::Storage& s);
  // Copies s's buffer to host (s.words() words): with glGetBufferSubData, or (staging) copied
  // on the device into a buffer the driver keeps in host memory (GL_STREAM_READ), then mapped.
  void read_back(const GL& gl, const detail::Storage& s, uint32_t* host);
  // The same, returning at once (Backend::read_back_async, rill/ReadBack.h): the device
  // copies s's buffer, in the order of the context's commands, into a staging buffer of the
  // read-back's own (GL_STREAM_READ: the driver keeps it in host memory), so that dispatches
  // launched next may write s; the wait maps it (which waits for the copy) and copies out.
  std::unique_ptr<PendingReadBack> read_back_async(const GL& gl, const detail::Storage& s,
                                                   uint32_t* host);
  struct StagingPool;  // staging buffers free for later read-backs, shared with those in flight
  // How read_back copies: RILL_GLSL_READBACK=get (default) or staging, for measuring which
  // the driver streams faster (issue 52 item 2). Throws for another value.
  static bool staging_from_environment();

 private:
  GLBackend& owner_;
  std::shared_ptr<Session> session_;
  int staging_ = -1;                   // staging_from_environment(), read at the first read-back
  Buffer staging_buffer_;              // grown to the largest read-back (staging only)
  std::shared_ptr<StagingPool> pool_;  // read_back_async's, made at its first use
};

}  // namespace rill::glsl
