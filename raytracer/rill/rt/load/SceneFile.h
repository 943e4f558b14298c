// Loading a scene from a file or a name: JSON scene files (format: docs/scene-format.md) and
// rill-trace's SCENE argument. The JSON reader checks each material against the shader it
// names (shaders/Registry.h: its parameters, their types, the shader's own checks), so this
// layer sits above the shaders, as a scene parser sits above the plugins it makes in pbrt and
// Mitsuba; OBJ files and the built-in scenes (scene/Scene.h) need no shader to load.
#pragma once

#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt {

// How deeply a scene file's objects and arrays may nest (the scene object is level 1); a file
// nested deeper is an error naming it and the limit, found as it is read, so that a hostile
// file of nested brackets costs no more memory than a scene does. Real scenes nest 5 deep.
inline constexpr int kMaxJsonDepth = 256;

// A JSON scene file. The mesh files it names (OBJ, PLY, glTF) are read with `input`.
Scene load_json(const std::string& path, const InputOptions& input = {});
Scene parse_json_scene(const std::string& text, const std::string& base_dir,
                       const std::string& name = "scene", const InputOptions& input = {});

// SCENE argument of rill-trace: "builtin:NAME", a .json file or a mesh file (.obj, .ply, .gltf,
// .glb: framed by the default camera, lit by the framing light).
Scene load_scene(const std::string& spec, const InputOptions& input = {});

}  // namespace rt
