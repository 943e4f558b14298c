// The list of built-in shaders (Builtin.h).
#include "rill/rt/shaders/Builtin.h"

namespace rt {

std::vector<SurfaceShader> builtin_shaders() {
  return {phong_shader(), mirror_shader(), glass_shader(), diffuse_shader(), ggx_shader()};
}

}  // namespace rt
