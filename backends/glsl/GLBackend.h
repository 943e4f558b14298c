// What the two GLSL backends share (`glsl`, GLSLBackend.cpp, and `glsl-compute`,
// ComputeBackend.cpp): the GL context, made at the first use and kept in a Session shared with
// the kernels and device buffers, whether there is one (unavailable_reason), the driver's
// description, and the lock and make-current every GL call goes through. Each backend adds its
// own set-up of a fresh context (limits, GL objects) in set_up(), its kernels and its memory.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "GLContext.h"
#include "GLSession.h"
#include "KernelTimer.h"
#include "rill/Backend.h"

namespace rill::glsl {

class GLBackend : public Backend, public SessionOwner {
 public:
  // An available context, or why there is none: the first failure is kept and repeated.
  std::string unavailable_reason() const override;
  bool supports(Accuracy a) const override { return a != Accuracy::Double; }
  // A hardware renderer (not llvmpipe or softpipe).
  bool runs_on_gpu() const override;
  // GL_RENDERER up to its details: "llvmpipe" of "llvmpipe (LLVM 15.0.7, 256 bits)".
  std::string driver_label() const override;
  // GL contexts are current on one thread at a time: launches go one after another.
  bool single_threaded() const override { return true; }

  // --- for the backend's kernels, under the lock --------------------------------------------

  std::recursive_mutex& mutex() { return session_->mutex; }
  // The context, made current on this thread (made first if there is none yet).
  const GL& current();
  const Driver& driver() const { return driver_; }
  // How long a launch's draws or dispatches ran on the device.
  const KernelTimer& timer() const { return timer_; }

 protected:
  // who: the backend in messages ("GLSL backend", "glsl-compute backend").
  explicit GLBackend(const char* who) : who_(who) {}
  // The context (locked), made at the first call: create_context(), describe_driver(), then
  // the backend's set_up(); an Error on the way is kept for every later call.
  GLContext& context();
  GLContext& context_locked();
  // The backend's own set-up of a fresh context, current on this thread, after driver_ is
  // known: its limits and GL objects. Throws Error when the context cannot serve.
  virtual void set_up(const GL& gl, GLContext& context) = 0;

  const char* who_;
  // The context and its lock, shared with kernels and buffers (see Session).
  std::shared_ptr<Session> session_ = std::make_shared<Session>();
  Driver driver_;
  KernelTimer timer_;

 private:
  bool started_ = false;  // a context was made (and, if session_ has none now, shut down)
  std::string init_error_;
};

// Asks a program where it takes the uniforms set_kernel_uniforms sets; at(name) gives the
// location of the uniform `name` (-1: the program does not use it).
template <class Locations, class At>
void locate_kernel_uniforms(Locations& loc, const At& at) {
  loc.count = at("rill_count");
  loc.width = at("rill_width");
  loc.u = at("rill_u");
  loc.k = at("rill_k");
  loc.one = at("rill_one");
  loc.shapes = at("rill_shapes");
}

// Sets the uniforms every generated GLSL kernel declares (GLSLEmitter.cpp), for a program
// whose locations are `loc` (-1: one the program does not use): the element count and launch
// width, the kernel's uniform words, its constants, the word of 1.0f the helpers read and
// the arrays' shapes.
template <class Locations>
void set_kernel_uniforms(const GL& gl, const Locations& loc, int64_t count, int64_t width,
                         const std::vector<uint32_t>& words, const std::vector<uint32_t>& constants,
                         const std::vector<GLint>& shapes) {
  if (loc.count >= 0) gl.glUniform1i(loc.count, static_cast<GLint>(count));
  if (loc.width >= 0) gl.glUniform1i(loc.width, static_cast<GLint>(width));
  if (!words.empty() && loc.u >= 0)
    gl.glUniform1uiv(loc.u, static_cast<GLsizei>(words.size()), words.data());
  if (!constants.empty() && loc.k >= 0)
    gl.glUniform1uiv(loc.k, static_cast<GLsizei>(constants.size()), constants.data());
  const GLuint one = 0x3f800000u;  // 1.0f, for the helpers (see GLSLEmitter.cpp)
  if (loc.one >= 0) gl.glUniform1uiv(loc.one, 1, &one);
  if (!shapes.empty() && loc.shapes >= 0)
    gl.glUniform1iv(loc.shapes, static_cast<GLsizei>(shapes.size()), shapes.data());
}

}  // namespace rill::glsl
