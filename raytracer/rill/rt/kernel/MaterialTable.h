// The materials on the device, and the calls into their shaders (Shader.h).
//
// Each shader the scene uses gets a parameter layout: every colour parameter a slot of its
// own (rgb, and in w the index of a texture bound to it, or -1), then the numbers, four to a
// slot. A material's parameters are `stride` consecutive Float4 slots of one array, so the
// kernels read a parameter with one load at material * stride + slot. Only the shaders of
// the materials the scene's triangles use are generated; with one, it is called directly,
// with several, a chain of branches on the material's shader index picks one.
#pragma once

#include <rill/rill.h>

#include <map>
#include <string>
#include <vector>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/kernel/Textures.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

class MaterialTable {
 public:
  // Lays out and uploads the parameters of the materials the scene's usable triangles use,
  // and the scene's textures. Throws SceneError for a material whose shader is unknown.
  void upload(const Scene& scene, const Features& F, const MaterialShaders& shaders);

  // A surface's material parameters, read once (every slot of its row): the functions
  // below take them so that a light loop does not read the table once per light. Slots no
  // shader reads are dead code the compilers drop.
  using Slots = std::vector<Float4>;
  Slots load(const Surface& s) const;

  // The shaders' functions at a surface, dispatched on its material's shader; without
  // `slots`, each parameter is read from the table where the shader asks for it.
  Float3 emitted(const Surface& s, const Slots* slots = nullptr) const;
  Float3 reflected(const Surface& s, const LightSample& light, const Slots* slots = nullptr) const;
  Scatter scatter(const Surface& s, const Float& weight, const Slots* slots = nullptr) const;
  // The BSDF's functions (path tracing; Shader.h, Bsdf), dispatched the same way. Every used
  // shader must have them (the path integrator checks that first).
  Float3 bsdf_eval(const Surface& s, const Float3& wi, const Slots* slots = nullptr) const;
  BsdfSample bsdf_sample(const Surface& s, const Float3& u, const Slots* slots = nullptr) const;
  Float bsdf_pdf(const Surface& s, const Float3& wi, const Slots* slots = nullptr) const;
  // SurfaceShader::albedo (white where a shader has none).
  Float3 albedo(const Surface& s, const Slots* slots = nullptr) const;

  std::vector<std::string> used_shaders() const;  // in the order of their indices
  rill::Uniform<Float> ambient{0.1f, "ambient"};

  // ---- for ShadingPoint --------------------------------------------------------------------
  Float3 color(int shader, const std::string& name, const Surface& s, const Slots* slots) const;
  Float number(int shader, const std::string& name, const Surface& s, const Slots* slots) const;
  bool may_be_nonzero(int shader, const std::string& name) const;
  bool vertex_colors() const { return vertex_colors_; }
  const TextureTable& textures() const { return textures_; }  // the scene's (emission too)

 private:
  struct Param {
    ParamType type = ParamType::Number;
    int slot = 0, lane = 0;  // lane: the number's component (colours: 0, rgb)
    bool nonzero = false;    // some material's value is not zero (or is a texture)
    bool textured = false;   // some material binds a texture to it
  };
  struct Layout {
    const SurfaceShader* shader = nullptr;
    std::map<std::string, Param> params;
    int slots = 0;
  };
  const Param& param(int shader, const std::string& name, ParamType type) const;
  Float4 slot(const Surface& s, int slot, const Slots* slots) const;
  // Calls f(i) for the shader of s's material: directly with one shader, else in a branch
  // per shader.
  template <class F>
  void dispatch(const Surface& s, F&& f) const;
  template <class R, class Call>
  R call_bsdf(const Surface& s, const Slots* slots, R zero, Call&& call) const;

  std::vector<Layout> shaders_;
  int stride_ = 1;
  bool vertex_colors_ = false;
  rill::Array<Float4> params_{1, "mat_params"};
  rill::Array<Int> shader_of_{1, "mat_shader"};
  TextureTable textures_;
};

}  // namespace rt
