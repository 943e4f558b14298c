// A headless OpenGL context and the GL functions loaded from it.
//
// Two kinds, chosen by RILL_GL (or the default order):
//   osmesa  Mesa's software renderer (llvmpipe) through libOSMesa: any machine, no display.
//   egl     a GPU through EGL_EXT_platform_device (NVIDIA, Mesa drivers), no display.
// Unset: osmesa, falling back to egl. Libraries are opened at run time, so a machine
// without one of them still runs the other backends; a missing one is a clear message.
#pragma once

#define GL_GLEXT_PROTOTYPES 0
#include <GL/glcorearb.h>

#include <memory>
#include <string>

namespace rill::glsl {

struct GL {
#define GL_FN(ret, name, params) ret(APIENTRY* name) params = nullptr;
#include "GLFunctions.def"
#undef GL_FN
};

class GLContext {
 public:
  // Destroys the context and, with it, every GL object made in it. GLSLBackend.cpp does this
  // explicitly, before the GL library's own exit handlers run (see Session there).
  virtual ~GLContext() = default;
  // Makes the context current on the calling thread.
  virtual void make_current() = 0;
  virtual std::string kind() const = 0;
  const GL& gl() const { return gl_; }
  std::string renderer;  // GL_RENDERER and GL_VERSION

 protected:
  GL gl_;
};

// Creates the context RILL_GL asks for (see above); throws rill::Error saying what is
// missing when none can be made.
std::unique_ptr<GLContext> create_context();

}  // namespace rill::glsl
