// The Phong model's local light, shared by the phong and glass shaders: ambient times the
// diffuse colour, and per light a Lambert term plus a specular highlight (Phong 1975).
// Vertex colours multiply the diffuse colour.
#pragma once

#include "rill/rt/kernel/Shader.h"

namespace rt {

// The diffuse colour at the hit: the parameter (or its texture) times the vertex colour.
Float3 phong_diffuse(const ShadingPoint& sp);
Float3 phong_emitted(const ShadingPoint& sp);
// The headlight (a scene without lights) gives no highlight.
Float3 phong_reflected(const ShadingPoint& sp, const LightSample& light);
// The parameters both shaders declare: diffuse, specular, shininess, reflect.
std::vector<ShaderParam> phong_params();

}  // namespace rt
