// The GLSL backend: kernels as fragment shaders over float textures (see GLSLBackend.cpp),
// on OSMesa by default or a GPU through EGL (RILL_GL=osmesa|egl, RILL_EGL_DEVICE=index).
#pragma once

#include <memory>

#include "rill/Backend.h"

namespace rill::glsl {

std::unique_ptr<Backend> make_backend();

}  // namespace rill::glsl
