// Surface shaders: what a material does where a ray hits it, written by users in Rill.
//
// A shader is a name, typed parameters and up to three DSL functions, which the tracer calls
// inside its kernels (both strategies, every backend):
//
//   emitted(sp)             light the surface gives without the light loop: emission and
//                           ambient. Called once per hit.
//   reflected(sp, light)    the light one point light sends towards the viewer, for each
//                           light the tracer found unshadowed (it traces the shadow rays).
//                           In a scene without lights, once with a headlight at the eye.
//   scatter(sp, weight)     how the path goes on: the share of the path weight that sees the
//                           local colour, and the weights and directions of a reflected and
//                           a transmitted ray (the tracer offsets their origins, traces
//                           them, and drops those below its minimum weight or depth).
//
// Under the path integrator (SceneOptions::integrator, docs/path-tracing.md) a shader is its
// BSDF instead, three more DSL functions (SurfaceShader::bsdf, below): eval, sample and pdf,
// after Mitsuba's and pbrt's. The built-in shaders have both interfaces; a shader without the
// BSDF is refused under "path", naming the material.
//
// The local colour is emitted + the sum of reflected over the lights; the pixel gains
// local_weight * local colour, as in the thesis's eq. 5.1. A missing function contributes
// nothing (scatter: the path ends, local_weight = weight).
//
//   rt::SurfaceShader toon;
//   toon.name = "toon";
//   toon.params = {{"color", rt::ParamType::Color, rt::ParamValue::of(glm::vec3(1, 0.3f, 0))},
//                  {"bands", rt::ParamType::Number, rt::ParamValue::of(3.0f)}};
//   toon.reflected = [](const rt::ShadingPoint& sp, const rt::LightSample& l) {
//     rill::Float n = sp.number("bands");
//     return sp.color("color") * floor(max(dot(sp.s.nf, l.L), 0.0f) * n) / n * l.color;
//   };
//   rt::register_shader(toon);                                 // shaders/Registry.h
//
// Parameters are numbers or colours; a colour parameter also takes a texture (a bitmap or a
// procedural texture, kernel/Textures.h), sampled at the hit when the shader reads it. Only
// the shaders a scene's materials use are generated into its kernels, and within a shader
// the host-side queries (ShadingPoint::may_be_nonzero) leave out code no material needs.
#pragma once

#include <rill/rill.h>

#include <functional>
#include <string>
#include <vector>

#include "rill/rt/kernel/Records.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

enum class ParamType {
  Number,  // a float
  Color,   // linear RGB, or a texture
};
const char* param_type_name(ParamType t);  // "number", "colour"

struct ShaderParam {
  std::string name;
  ParamType type = ParamType::Number;
  ParamValue default_value;  // of the same type
  std::string doc;           // one line, for docs and `rill-trace info`
  bool required = false;     // a material must give it (scene files: an error otherwise)
};

class MaterialTable;  // the device side of the materials (kernel/MaterialTable.h)

// What a shader sees at a hit: the surface record and its material's parameters. The
// accessors emit DSL code (reads from the material table, texture lookups) where they are
// called.
class ShadingPoint {
 public:
  ShadingPoint(const Surface& s, const MaterialTable& table, int shader,
               const std::vector<Float4>* slots = nullptr);
  const Surface& s;
  // A colour parameter (a texture bound to it is sampled at s.uv here).
  Float3 color(const std::string& name) const;
  Float number(const std::string& name) const;
  // Host side, while the kernel is generated: false when every material of the scene that
  // uses this shader has the parameter at zero (a number or a black colour, no texture), so
  // that the code it would weigh can be left out.
  bool may_be_nonzero(const std::string& name) const;
  // Host side: whether the scene has vertex colours (without, s.vertex_color is white and
  // multiplying by it can be left out).
  bool has_vertex_colors() const;
  // The scene's ambient light level (a uniform).
  Float ambient() const;

 private:
  const MaterialTable& table_;
  int shader_;
  const std::vector<Float4>* slots_;  // the material's parameters, read before (or null)
};

// One light as a shader sees it: the unit direction from the surface towards it and its
// colour. `headlight` is true (host side) for the light at the eye of a scene without lights.
struct LightSample {
  Float3 L;
  Float3 color;
  bool headlight = false;
};

// How the path goes on from a hit (see the top of this file). Directions need not be
// normalized beyond what the shader computes; a weight of 0 sends no ray.
struct Scatter {
  Float local_weight = 0.0f;
  Float reflect_weight = 0.0f;
  Float3 reflect_dir{0.0f};
  Float transmit_weight = 0.0f;
  Float3 transmit_dir{0.0f};
};

// Host side: which rays a material with these parameter values may send. The tracer
// generates reflection code, refraction code and the ray stack only where some material
// needs them.
struct Lobes {
  bool reflect = false;
  bool transmit = false;
};

// A material's parameter values as the host sees them (defaults filled in).
class MaterialParams {
 public:
  MaterialParams(const Material& m, const std::vector<ShaderParam>& decl) : m_(m), decl_(decl) {}
  // The value of parameter `name` (the material's, else the declared default); throws
  // std::out_of_range for a name the shader does not declare.
  ParamValue get(const std::string& name) const;
  float number(const std::string& name) const { return get(name).number; }
  // True unless the value is exactly zero (0, or black without a texture).
  bool nonzero(const std::string& name) const;

 private:
  const Material& m_;
  const std::vector<ShaderParam>& decl_;
};

// ---- Path tracing: the BSDF -------------------------------------------------------------
// Directions are unit vectors pointing away from the surface: wo = sp.s.V (back along the
// ray that arrived), wi towards where the light comes from (the next ray's direction). Both
// may lie on either side: a wi below the surface (dot(wi, sp.s.ngf) < 0) is transmission.

// A direction the BSDF chose, and what it weighs.
struct BsdfSample {
  Float3 wi{0.0f};
  // eval(wi) / pdf(wi): the factor the path's throughput takes on. For a delta lobe (a
  // perfect mirror or refraction, which eval and pdf cannot express) its reflectance or
  // transmittance divided by the probability of choosing the lobe. 0: the path ends.
  Float3 weight{0.0f};
  Float pdf = 0.0f;    // the solid-angle density of wi; for a delta lobe the lobe's probability
  Bool delta = false;  // wi comes from a delta lobe: no light sampling can reach it
};

struct Bsdf {
  // f(wo, wi) |dot(nf, wi)|: the BSDF times the cosine at wi (as Mitsuba's eval), without
  // the delta lobes (they are 0 for every wi drawn from elsewhere).
  std::function<Float3(const ShadingPoint&, const Float3& wi)> eval;
  // Draws wi from u, three uniform numbers in [0, 1) (the first usually picks a lobe, the other
  // two place the direction).
  std::function<BsdfSample(const ShadingPoint&, const Float3& u)> sample;
  // The density with which sample() draws wi, over solid angle, without the delta lobes (and
  // times the probability of choosing the smooth lobes where there are delta ones too).
  std::function<Float(const ShadingPoint&, const Float3& wi)> pdf;
  // Host side: whether a material with these values has a smooth (non-delta) lobe. Light
  // sampling (next-event estimation) happens only at such surfaces. Missing: true.
  std::function<bool(const MaterialParams&)> smooth;
  explicit operator bool() const { return eval && sample && pdf; }
};

struct SurfaceShader {
  std::string name;
  std::string doc;  // one line
  std::vector<ShaderParam> params;
  std::function<Float3(const ShadingPoint&)> emitted;
  std::function<Float3(const ShadingPoint&, const LightSample&)> reflected;
  std::function<Scatter(const ShadingPoint&, const Float& weight)> scatter;
  std::function<Lobes(const MaterialParams&)> lobes;
  // Host side: what is wrong with a material's values beyond their types (a range, a sum of
  // two parameters), or empty. The JSON reader and the Tracer's constructor report it as
  // "material 'NAME': " and the text.
  std::function<std::string(const MaterialParams&)> check;
  // Path tracing (above): the BSDF. Empty for a shader that has only the Whitted functions.
  Bsdf bsdf;
  // The surface's reflectance as a denoiser wants it (the path integrator's albedo AOV at the
  // camera ray's hit: the colour that multiplies the light, roughly its directional albedo).
  // Missing: white.
  std::function<Float3(const ShadingPoint&)> albedo;
};

// The shaders of a scene's materials, one per material (shaders/Registry.h, resolve_shaders):
// what a tracer's kernels are generated from.
using MaterialShaders = std::vector<const SurfaceShader*>;

}  // namespace rt
