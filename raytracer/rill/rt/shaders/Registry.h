// The process's surface shaders, by name: every shader is a plugin registered here. The
// built-in ones (phong, mirror, glass; Builtin.h) register through register_shader at the
// registry's first use, exactly as a user's shader does:
//
//   rt::register_shader(toon);            // a new name; throws if the name is taken
//   rt::replace_shader(my_phong);         // the shader of that name from now on
//
// A material names its shader (Material::shader); a Tracer resolves the names when it is
// built (resolve_shaders) and generates its kernels from those shaders. So registering or
// replacing a shader changes the tracers built after it, never one built before: that one
// keeps the shader it was built with until it is destroyed (the registry keeps a replaced
// shader alive for the process, so the pointers find_shader gave stay valid).
#pragma once

#include <string>
#include <vector>

#include "rill/rt/kernel/Shader.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// Adds a shader under shader.name. Throws std::invalid_argument for an empty or taken name,
// a parameter without a name, named "shader" or declared twice, or a default of the wrong
// type.
void register_shader(SurfaceShader shader);
// The same, but a taken name is no error: the shader replaces the one registered under it
// (a built-in one too) for the tracers and scene files loaded from now on.
void replace_shader(SurfaceShader shader);
// The shader registered under name now; null when there is none.
const SurfaceShader* find_shader(const std::string& name);
std::vector<std::string> shader_names();  // sorted

// The shader a material names; throws SceneError when none is registered under that name.
const SurfaceShader& material_shader(const Material& m);
// What is wrong with a material's values for its shader: a value of the wrong type, a
// required parameter missing, or what the shader's check says; empty when nothing.
std::string material_problem(const Material& m, const SurfaceShader& shader);
// The shaders of the scene's materials, one per material, each material checked
// (material_problem); throws SceneError "material 'NAME': ..." for the first bad one.
MaterialShaders resolve_shaders(const Scene& scene);

}  // namespace rt
