// How long a launch's draws or dispatches ran on the GPU (LaunchResult::device_ms), from a
// GL_TIME_ELAPSED query around them: one query object per context, made with it.
#pragma once

#include "GLContext.h"

namespace rill::glsl {

class KernelTimer {
 public:
  void create(const GL& gl) { gl.glGenQueries(1, &query_); }
  void destroy(const GL& gl) {
    if (query_) gl.glDeleteQueries(1, &query_);
    query_ = 0;
  }

  // The query, begun around the commands to time; it ends with end_ms() or, if the launch
  // throws first, when it goes out of scope (so the next launch can begin it again).
  class Running {
   public:
    Running(const GL& gl, GLuint query) : gl_(gl), query_(query) {
      gl_.glBeginQuery(GL_TIME_ELAPSED, query_);
    }
    ~Running() {
      if (open_) gl_.glEndQuery(GL_TIME_ELAPSED);
    }
    Running(const Running&) = delete;
    Running& operator=(const Running&) = delete;
    // Ends the query and waits for its result: call once the commands' results are needed
    // anyway (the launch has read its counts back).
    double end_ms() {
      open_ = false;
      gl_.glEndQuery(GL_TIME_ELAPSED);
      GLuint64 ns = 0;
      gl_.glGetQueryObjectui64v(query_, GL_QUERY_RESULT, &ns);
      return static_cast<double>(ns) * 1e-6;
    }

   private:
    const GL& gl_;
    GLuint query_;
    bool open_ = true;
  };
  // On the context that made the query.
  Running start(const GL& gl) const { return Running(gl, query_); }

 private:
  GLuint query_ = 0;
};

}  // namespace rill::glsl
