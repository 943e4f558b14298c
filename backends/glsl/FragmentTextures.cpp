// The GLSL backend's device memory role (FragmentTextures.h).
#include "FragmentTextures.h"

#include <algorithm>

namespace rill::glsl {

namespace {

constexpr int64_t kMaxRow = kTextureRow;  // GLSLEmitter.h

}  // namespace

Format format_of(ir::Type t) {
  bool f = t.is_float();
  switch (t.width) {
    case 1:
      return {GLenum(f ? GL_R32F : GL_R32I), GLenum(f ? GL_RED : GL_RED_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 1};
    case 2:
      return {GLenum(f ? GL_RG32F : GL_RG32I), GLenum(f ? GL_RG : GL_RG_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 2};
    default:
      return {GLenum(f ? GL_RGBA32F : GL_RGBA32I), GLenum(f ? GL_RGBA : GL_RGBA_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 4};
  }
}

Shape shape_of(int64_t count) {
  Shape s;
  s.row = static_cast<int>(std::clamp<int64_t>(count, 1, kMaxRow));
  s.rows = static_cast<int>(std::max<int64_t>(1, (count + s.row - 1) / s.row));
  return s;
}

// Destroyed with its stream or array, possibly after the backend and the context are gone.
Texture::~Texture() {
  if (!tex) return;
  std::lock_guard<std::recursive_mutex> lock(session->mutex);
  if (const GL* gl = session->current_if_alive()) gl->glDeleteTextures(1, &tex);
}

Texture& FragmentTextures::to_device(const GL& gl, detail::Storage& s) {
  auto* t = s.device_buffer<Texture>(&owner_);
  if (t && s.is_device_current(&owner_)) return *t;
  // The freshest copy may be another backend's, read back now: with the other GLSL
  // backend, through its own context, so this one is made current again.
  const uint32_t* host = s.host_data_for_read();
  owner_.current();
  t = s.device_buffer<Texture>(&owner_);
  Format fmt = format_of(s.type());
  Shape shape = shape_of(s.count());
  if (!t || t->fmt.internal != fmt.internal || t->shape.row != shape.row ||
      t->shape.rows != shape.rows) {
    auto fresh = std::make_unique<Texture>();
    fresh->session = session_;
    fresh->fmt = fmt;
    fresh->shape = shape;
    fresh->tex = new_texture(gl, fmt, shape);
    t = fresh.get();
    s.set_device_buffer(&owner_, std::move(fresh));
    owner_.current();  // releasing another backend's copy may have made its context current
  }
  std::vector<uint32_t> padded(static_cast<size_t>(shape.row) * static_cast<size_t>(shape.rows) *
                               static_cast<size_t>(fmt.channels));
  int w = s.type().width;
  for (int64_t i = 0; i < s.count(); ++i)
    for (int c = 0; c < w; ++c)
      padded[static_cast<size_t>(i * fmt.channels + c)] = host[static_cast<size_t>(i * w + c)];
  gl.glBindTexture(GL_TEXTURE_2D, t->tex);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, shape.row, shape.rows, fmt.format, fmt.type,
                     padded.data());
  glsl::check(gl, "uploading a texture");
  s.mark_device_current(&owner_);
  return *t;
}

GLuint FragmentTextures::new_texture(const GL& gl, const Format& fmt, const Shape& shape) {
  GLuint tex = 0;
  gl.glGenTextures(1, &tex);
  gl.glBindTexture(GL_TEXTURE_2D, tex);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(fmt.internal), shape.row, shape.rows, 0,
                  fmt.format, fmt.type, nullptr);
  glsl::check(gl, "allocating a texture");
  return tex;
}

GLuint FragmentTextures::take_copy(const GL& gl, const Format& fmt, const Shape& shape) {
  auto it = copy_pool_.find({fmt.internal, shape.row, shape.rows});
  if (it == copy_pool_.end() || it->second.empty()) return new_texture(gl, fmt, shape);
  GLuint tex = it->second.back();
  it->second.pop_back();
  return tex;
}
void FragmentTextures::give_back_copy(const GL& gl, const Format& fmt, const Shape& shape,
                                      GLuint tex) {
  constexpr int64_t kPooledTexels = int64_t{1} << 20;
  constexpr size_t kPerShape = 4;
  std::vector<GLuint>& pool = copy_pool_[{fmt.internal, shape.row, shape.rows}];
  if (int64_t{shape.row} * shape.rows <= kPooledTexels && pool.size() < kPerShape)
    pool.push_back(tex);
  else
    gl.glDeleteTextures(1, &tex);
}

GLuint FragmentTextures::stencil(const GL& gl, const Shape& shape) {
  GLuint& rb = stencils_[{shape.row, shape.rows}];
  if (rb == 0) {
    gl.glGenRenderbuffers(1, &rb);
    gl.glBindRenderbuffer(GL_RENDERBUFFER, rb);
    gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, shape.row, shape.rows);
    glsl::check(gl, "allocating a stencil buffer");
  }
  return rb;
}

void FragmentTextures::read_back(const GL& gl, const detail::Storage& s, uint32_t* host) {
  auto* t = s.device_buffer<Texture>(&owner_);
  std::vector<uint32_t> padded(static_cast<size_t>(t->shape.row) *
                               static_cast<size_t>(t->shape.rows) *
                               static_cast<size_t>(t->fmt.channels));
  gl.glBindTexture(GL_TEXTURE_2D, t->tex);
  gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.glGetTexImage(GL_TEXTURE_2D, 0, t->fmt.format, t->fmt.type, padded.data());
  glsl::check(gl, "reading a texture back");
  int w = s.type().width;
  for (int64_t i = 0; i < s.count(); ++i)
    for (int c = 0; c < w; ++c)
      host[static_cast<size_t>(i * w + c)] = padded[static_cast<size_t>(i * t->fmt.channels + c)];
}

void FragmentTextures::release(const GL* gl) noexcept {
  if (gl) {
    for (auto& [size, rb] : stencils_) gl->glDeleteRenderbuffers(1, &rb);
    for (auto& [key, pool] : copy_pool_)
      if (!pool.empty()) gl->glDeleteTextures(static_cast<GLsizei>(pool.size()), pool.data());
  }
  stencils_.clear();
  copy_pool_.clear();
}

}  // namespace rill::glsl
