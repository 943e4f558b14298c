// The GLSL compute backend, `glsl-compute`: kernels as OpenGL 4.3 compute shaders from the
// same emitter as the fragment stage (see ComputeBackend.cpp), on the same contexts
// (RILL_GL=osmesa|egl, RILL_EGL_DEVICE=index).
#pragma once

#include <memory>

#include "rill/Backend.h"

namespace rill::glsl {

std::unique_ptr<Backend> make_compute_backend();

}  // namespace rill::glsl
