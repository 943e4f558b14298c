// The Phong model's local light, shared by the phong and glass shaders: ambient times the
// diffuse colour, and per light a Lambert term plus a specular highlight (Phong 1975).
// Vertex colours multiply the diffuse colour. Also the mirror lobe that phong and mirror share.
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
// Mirror reflection of strength r (eq. 5.1): the surface keeps 1 - r of the path weight, the
// reflected ray carries r. Phong's and the mirror shader's scatter.
Scatter mirror_scatter(const ShadingPoint& sp, const Float& weight, const Float& r);
// The checks of the parameters they share (SurfaceShader::check): reflect in [0, 1], and
// shininess in [0, 10000]; empty when the value is fine.
std::string reflect_problem(float reflect);
// Path tracing (Lobes.h): the diffuse lobe of phong_diffuse's colour with probability (and
// share of the light) p, and the perfect mirror with probability and reflectance p.
struct Lobe;
Lobe diffuse_lobe(const ShadingPoint& sp, const Float& p);
Lobe mirror_lobe(const ShadingPoint& sp, const Float& p);
std::string shininess_problem(float shininess);

}  // namespace rt
