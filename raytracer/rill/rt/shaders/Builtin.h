// The built-in surface shaders, written through the same API as users' (kernel/Shader.h):
//
//   phong   Phong (1975): diffuse + specular highlights, plus mirror reflection of
//           strength `reflect` (the thesis's eq. 5.1). The default material.
//   mirror  a perfect mirror: the path reflects with weight `reflect`, no local colour.
//   glass   phong's local light, plus refraction with Schlick's Fresnel term and total
//           internal reflection (a share `transmit` of the light goes through).
//   diffuse a Lambertian surface.
//   ggx     GGX microfacet reflection: a conductor, or plastic with a diffuse base.
//
// Each also has a BSDF for the path integrator (eval, sample, pdf; Lobes.h), documented in
// its file and in docs/path-tracing.md.
//
// They are plugins like any user's shader: the registry (Registry.h) registers these through
// register_shader, and replace_shader replaces one by name. A classic material (MTL, a JSON
// material without "shader") is phong, or glass where it transmits (scene/ClassicMaterial.h).
#pragma once

#include <string>
#include <vector>

#include "rill/rt/kernel/Shader.h"

namespace rt {

SurfaceShader phong_shader();
SurfaceShader mirror_shader();
SurfaceShader glass_shader();
SurfaceShader diffuse_shader();
SurfaceShader ggx_shader();
std::vector<SurfaceShader> builtin_shaders();

}  // namespace rt
