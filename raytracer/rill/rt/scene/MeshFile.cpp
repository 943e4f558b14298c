// Mesh files by their extension (MeshFile.h). PLY and glTF need assimp: a build without it
// (RILL_HAVE_ASSIMP undefined) still knows the extensions, so that it says what is missing
// instead of that the file is of an unknown kind.
#include "rill/rt/scene/MeshFile.h"

#include <cctype>
#include <filesystem>

namespace rt {

namespace {

std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

}  // namespace

bool is_mesh_file(const std::string& path) {
  const std::string ext = extension(path);
  return ext == ".obj" || ext == ".ply" || ext == ".gltf" || ext == ".glb";
}

bool have_assimp() {
#ifdef RILL_HAVE_ASSIMP
  return true;
#else
  return false;
#endif
}

Scene load_mesh_file(const std::string& path, const ObjLoadOptions& opt) {
  const std::string ext = extension(path);
  if (ext == ".ply" || ext == ".gltf" || ext == ".glb") {
    if (!have_assimp())
      throw SceneError(path + ": this Rill was built without assimp, which reads " +
                       (ext == ".ply" ? "PLY" : "glTF") +
                       " files (install libassimp-dev and configure again)");
    return ext == ".ply" ? load_ply(path, opt) : load_gltf(path, opt);
  }
  // Any other name is an OBJ file, as a JSON mesh's file always was (whatever its extension).
  return load_obj(path, opt);
}

#ifndef RILL_HAVE_ASSIMP
// Never called (load_mesh_file refuses first); defined so that the API links either way.
Scene load_ply(const std::string& path, const ObjLoadOptions&) {
  throw SceneError(path + ": this Rill was built without assimp, which reads PLY files");
}
Scene load_gltf(const std::string& path, const ObjLoadOptions&) {
  throw SceneError(path + ": this Rill was built without assimp, which reads glTF files");
}
#endif

}  // namespace rt
