// rill-trace's SCENE argument (SceneFile.h): a built-in scene, a JSON file or a mesh file (OBJ,
// PLY, glTF: scene/MeshFile.h).
#include <cctype>
#include <filesystem>

#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Framing.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/MeshFile.h"

namespace rt {

Scene load_scene(const std::string& spec, const InputOptions& input) {
  namespace fs = std::filesystem;
  if (spec.rfind("builtin:", 0) == 0) return builtin_scene(spec.substr(8));
  std::string ext = fs::path(spec).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  std::error_code ec;
  if (!fs::exists(spec, ec)) {
    for (const std::string& n : builtin_scene_names())
      if (n == spec) return builtin_scene(spec);
    throw SceneError(spec + ": no such file (built-in scenes are named builtin:NAME)");
  }
  // A folder or a device: say so, rather than that its (empty) extension is unknown.
  if (ext != ".json" && !is_mesh_file(spec))
    check_input_file(spec, "a scene (.json, .obj, .ply, .gltf or .glb)");
  if (ext == ".json") return load_json(spec, input);
  if (is_mesh_file(spec)) {
    ObjLoadOptions o;
    o.input = input;
    Scene s = load_mesh_file(spec, o);
    s.camera = default_camera(s);
    s.has_camera = true;
    s.camera_framed = true;
    // One white light, off the view axis so that the shapes' shadows show (Framing.h).
    s.framing_light = static_cast<int>(s.lights.size());
    s.lights.push_back(Light{framing_light_position(s.camera), glm::vec3(1.0f)});
    return s;
  }
  throw SceneError(spec + ": unknown scene type '" + ext +
                   "' (expected .json, .obj, .ply, .gltf or .glb)");
}

}  // namespace rt
