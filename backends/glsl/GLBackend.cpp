// The GLSL backends' shared context handling (GLBackend.h).
#include "GLBackend.h"

namespace rill::glsl {

std::string GLBackend::unavailable_reason() const {
  try {
    const_cast<GLBackend*>(this)->context();
    return {};
  } catch (const Error& e) {
    return e.what();
  }
}

bool GLBackend::runs_on_gpu() const {
  return unavailable_reason().empty() &&
         !is_software_renderer(const_cast<GLBackend*>(this)->context().renderer);
}

std::string GLBackend::driver_label() const {
  if (!unavailable_reason().empty()) return {};
  const std::string& r = driver_.renderer;
  return r.substr(0, r.find(" ("));
}

const GL& GLBackend::current() {
  GLContext& c = context_locked();
  c.make_current();
  return c.gl();
}

GLContext& GLBackend::context() {
  std::lock_guard<std::recursive_mutex> lock(mutex());
  return context_locked();
}

GLContext& GLBackend::context_locked() {
  Session& ss = *session_;
  if (ss.context) return *ss.context;
  if (!init_error_.empty()) throw Error(init_error_);
  if (started_)
    throw Error(std::string(who_) + ": the OpenGL context was shut down (the process is exiting)");
  try {
    auto c = create_context();
    const GL& gl = c->gl();
    driver_ = describe_driver(gl, c->renderer);
    set_up(gl, *c);
    timer_.create(gl);
    check(gl, "setting up the context", who_);
    ss.context = std::move(c);
    started_ = true;
    // The GL library is loaded now: an exit handler registered after it runs before the
    // library's own (see GLSession.h).
    shut_down_at_exit(this);
  } catch (const Error& e) {
    init_error_ = e.what();
    throw;
  }
  return *ss.context;
}

}  // namespace rill::glsl
