// The glsl-compute backend's device memory role (ComputeBuffers.h).
#include "ComputeBuffers.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "GLSession.h"

namespace rill::glsl {

namespace {

// The buffer texture format of an element type (3-component formats exist for buffer
// textures since GL 4.0).
GLenum texel_format(ir::Type t) {
  const bool f = t.is_float();
  switch (t.width) {
    case 1:
      return f ? GL_R32F : GL_R32I;
    case 2:
      return f ? GL_RG32F : GL_RG32I;
    case 3:
      return f ? GL_RGB32F : GL_RGB32I;
    default:
      return f ? GL_RGBA32F : GL_RGBA32I;
  }
}

}  // namespace

Buffer& ComputeBuffers::to_device(const GL& gl, detail::Storage& s) {
  auto* b = s.device_buffer<Buffer>(&owner_);
  if (b && s.is_device_current(&owner_)) return *b;
  // The freshest copy may be another backend's, read back now: with the other GLSL
  // backend, through its own context, so this one is made current again.
  const uint32_t* host = s.words() > 0 ? s.host_data_for_read() : nullptr;
  owner_.current();
  b = s.device_buffer<Buffer>(&owner_);
  const int64_t bytes = std::max<int64_t>(16, static_cast<int64_t>(s.words()) * 4);
  // A buffer that is stale in some words only gets just those (Storage::stale_words).
  auto [first, end] = s.stale_words();
  if (!b || b->bytes != bytes) {
    first = 0;
    end = s.words();
    auto fresh = std::make_unique<Buffer>();
    fresh->session = session_;
    fresh->bytes = bytes;
    gl.glGenBuffers(1, &fresh->buf);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, fresh->buf);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_COPY);
    check(gl, "allocating a buffer", kComputeWho);
    b = fresh.get();
    s.set_device_buffer(&owner_, std::move(fresh));
    owner_.current();  // releasing another backend's copy may have made its context current
  }
  if (host != nullptr && end > first) {
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, b->buf);
    gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(first * 4),
                       static_cast<GLsizeiptr>((end - first) * 4), host + first);
    check(gl, "uploading a buffer", kComputeWho);
  }
  s.mark_device_current(&owner_);
  return *b;
}

GLuint ComputeBuffers::texture_of(const GL& gl, detail::Storage& s) {
  Buffer& b = to_device(gl, s);
  if (b.tex == 0) {
    gl.glGenTextures(1, &b.tex);
    gl.glBindTexture(GL_TEXTURE_BUFFER, b.tex);
    gl.glTexBuffer(GL_TEXTURE_BUFFER, texel_format(s.type()), b.buf);
    check(gl, "making a buffer texture", kComputeWho);
  }
  return b.tex;
}

bool ComputeBuffers::staging_from_environment() {
  const char* v = std::getenv("RILL_GLSL_READBACK");
  if (!v || !*v || std::string(v) == "get") return false;
  if (std::string(v) == "staging") return true;
  throw Error(std::string("RILL_GLSL_READBACK='") + v + "' is not one of get, staging");
}

void ComputeBuffers::read_back(const GL& gl, const detail::Storage& s, uint32_t* host) {
  auto* b = s.device_buffer<Buffer>(&owner_);
  if (s.words() == 0) return;
  const auto bytes = static_cast<GLsizeiptr>(s.words() * 4);
  if (staging_ < 0) staging_ = staging_from_environment() ? 1 : 0;
  gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (staging_ == 0) {
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, b->buf);
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, host);
    check(gl, "reading a buffer back", kComputeWho);
    return;
  }
  // The device copies into the staging buffer; mapping it waits for that copy.
  Buffer& st = staging_buffer_;
  if (st.bytes < bytes) {
    if (!st.buf) {
      st.session = session_;
      gl.glGenBuffers(1, &st.buf);
    }
    gl.glBindBuffer(GL_COPY_WRITE_BUFFER, st.buf);
    gl.glBufferData(GL_COPY_WRITE_BUFFER, bytes, nullptr, GL_STREAM_READ);
    check(gl, "allocating the read-back buffer", kComputeWho);
    st.bytes = bytes;
  }
  gl.glBindBuffer(GL_COPY_READ_BUFFER, b->buf);
  gl.glBindBuffer(GL_COPY_WRITE_BUFFER, st.buf);
  gl.glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, bytes);
  const void* mapped = gl.glMapBufferRange(GL_COPY_WRITE_BUFFER, 0, bytes, GL_MAP_READ_BIT);
  if (!mapped) {
    check(gl, "mapping the read-back buffer", kComputeWho);
    throw Error(std::string(kComputeWho) + ": mapping the read-back buffer failed");
  }
  std::memcpy(host, mapped, static_cast<size_t>(bytes));
  gl.glUnmapBuffer(GL_COPY_WRITE_BUFFER);
  check(gl, "reading a buffer back", kComputeWho);
}

// Staging buffers of read-backs that ended, by size (a frame's outputs, two frames in flight:
// a few; the oldest go beyond that). Used under the session's lock.
struct ComputeBuffers::StagingPool {
  static constexpr size_t kKept = 16;
  std::vector<std::unique_ptr<Buffer>> free;
  void give_back(std::unique_ptr<Buffer> b) {
    free.push_back(std::move(b));
    if (free.size() > kKept) free.erase(free.begin());  // deleted by ~Buffer
  }
};

namespace {

// One read-back in flight: the staging buffer the device copies into.
class ComputePendingReadBack : public PendingReadBack {
 public:
  ComputePendingReadBack(std::shared_ptr<Session> session,
                         std::shared_ptr<ComputeBuffers::StagingPool> pool,
                         std::unique_ptr<Buffer> staging, uint32_t* host)
      : session_(std::move(session)),
        pool_(std::move(pool)),
        staging_(std::move(staging)),
        host_(host) {}
  ~ComputePendingReadBack() override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    if (staging_) pool_->give_back(std::move(staging_));
  }
  ComputePendingReadBack(const ComputePendingReadBack&) = delete;
  ComputePendingReadBack& operator=(const ComputePendingReadBack&) = delete;

  void wait() override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    const GL* gl = session_->current_if_alive();
    if (!gl)
      throw Error(std::string(kComputeWho) +
                  ": the context ended (or cannot be made current here) before a read-back did");
    const auto bytes = static_cast<GLsizeiptr>(staging_->bytes);
    gl->glBindBuffer(GL_COPY_WRITE_BUFFER, staging_->buf);
    const void* mapped = gl->glMapBufferRange(GL_COPY_WRITE_BUFFER, 0, bytes, GL_MAP_READ_BIT);
    if (!mapped) {
      check(*gl, "mapping the read-back buffer", kComputeWho);
      throw Error(std::string(kComputeWho) + ": mapping the read-back buffer failed");
    }
    std::memcpy(host_, mapped, static_cast<size_t>(bytes));
    gl->glUnmapBuffer(GL_COPY_WRITE_BUFFER);
    check(*gl, "reading a buffer back", kComputeWho);
    pool_->give_back(std::move(staging_));
  }

 private:
  std::shared_ptr<Session> session_;
  std::shared_ptr<ComputeBuffers::StagingPool> pool_;
  std::unique_ptr<Buffer> staging_;
  uint32_t* host_;
};

}  // namespace

std::unique_ptr<PendingReadBack> ComputeBuffers::read_back_async(const GL& gl,
                                                                 const detail::Storage& s,
                                                                 uint32_t* host) {
  auto* b = s.device_buffer<Buffer>(&owner_);
  if (s.words() == 0) return nullptr;
  const auto bytes = static_cast<int64_t>(s.words() * 4);
  if (!pool_) pool_ = std::make_shared<StagingPool>();
  std::unique_ptr<Buffer> st;
  for (auto it = pool_->free.begin(); it != pool_->free.end(); ++it)
    if ((*it)->bytes == bytes) {
      st = std::move(*it);
      pool_->free.erase(it);
      break;
    }
  if (!st) {
    st = std::make_unique<Buffer>();
    st->session = session_;
    gl.glGenBuffers(1, &st->buf);
    gl.glBindBuffer(GL_COPY_WRITE_BUFFER, st->buf);
    gl.glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_STREAM_READ);
    check(gl, "allocating a read-back buffer", kComputeWho);
    st->bytes = bytes;
  }
  gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.glBindBuffer(GL_COPY_READ_BUFFER, b->buf);
  gl.glBindBuffer(GL_COPY_WRITE_BUFFER, st->buf);
  gl.glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0,
                         static_cast<GLsizeiptr>(bytes));
  check(gl, "copying a buffer for its read-back", kComputeWho);
  return std::make_unique<ComputePendingReadBack>(session_, pool_, std::move(st), host);
}

}  // namespace rill::glsl
