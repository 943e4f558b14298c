// The GLSL backend's device memory role: a stream or array of n elements is a 2D texture of
// rows of min(n, 4096) texels (R32F, RG32F or RGBA32F; integer formats for Int data;
// 3-component data padded to 4), uploaded when the host or another backend has the freshest
// copy. Also the textures a launch borrows for copies of its outputs' previous values (pooled
// by format and shape) and the stencil buffers of masked launches.
#pragma once

#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "GLBackend.h"
#include "GLSLEmitter.h"
#include "rill/Stream.h"

namespace rill::glsl {

// A texture's GL format, and the channels of a texel.
struct Format {
  GLenum internal, format, type;
  int channels;
};

// The texture format of a value type.
Format format_of(ir::Type t);

// A texture's layout: texels per row, and rows.
struct Shape {
  int row = 1, rows = 1;
};
// The layout of count elements.
Shape shape_of(int64_t count);

// A stream's or array's texture (its device buffer), deleted with it, also after the backend
// and the context are gone.
struct Texture : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  GLuint tex = 0;
  Format fmt{};
  Shape shape;
  ~Texture() override;
};

// The memory role itself: the device buffers of one backend, under its lock.
class FragmentTextures {
 public:
  // owner: the backend whose buffers these are; its context is made current where another
  // backend's copy had to be read back first.
  FragmentTextures(GLBackend& owner, std::shared_ptr<Session> session)
      : owner_(owner), session_(std::move(session)) {}

  // The texture holding s, current with the host copy.
  Texture& to_device(const GL& gl, detail::Storage& s);
  // Copies s's texture to host (s.words() words).
  void read_back(const GL& gl, const detail::Storage& s, uint32_t* host);
  // A texture of this format and shape for a launch's copy of an output's previous values:
  // one from the pool, else a new one. give_back_copy() returns it.
  GLuint take_copy(const GL& gl, const Format& fmt, const Shape& shape);
  // Keeps the textures of small launches (up to kPooledTexels texels, a few per shape) for the
  // next launch, where allocating them would cost more than the kernel; deletes the others.
  void give_back_copy(const GL& gl, const Format& fmt, const Shape& shape, GLuint tex);
  // A depth-stencil renderbuffer of this size, for masked launches (kept for reuse).
  GLuint stencil(const GL& gl, const Shape& shape);
  // Deletes the pooled textures and stencil buffers (with gl null: the context is gone, and
  // they went with it).
  void release(const GL* gl) noexcept;

 private:
  GLuint new_texture(const GL& gl, const Format& fmt, const Shape& shape);

  GLBackend& owner_;
  std::shared_ptr<Session> session_;
  std::map<std::pair<int, int>, GLuint> stencils_;
  // Textures for copies of outputs, by (internal format, row, rows), for reuse.
  std::map<std::tuple<GLenum, int, int>, std::vector<GLuint>> copy_pool_;
};

}  // namespace rill::glsl
