// Mesh files by their extension: OBJ (load_obj, Scene.h), PLY and glTF 2.0 (read with assimp,
// docs/scene-format.md, "Mesh files"). rill-trace's SCENE argument and the JSON files'
// `"file"` meshes load through here, so every mesh format is accepted wherever one is.
#pragma once

#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt {

// The extensions of the mesh files Rill reads (lower case): .obj, .ply, .gltf, .glb.
bool is_mesh_file(const std::string& path);
// True when this build reads PLY and glTF (assimp was found at configure time).
bool have_assimp();

// The mesh file at `path`, by its extension (case-insensitive): .ply, .gltf and .glb, and any
// other name an OBJ file (as JSON meshes' files always were). The options are OBJ's
// (ObjLoadOptions): the transform, a material that overrides the file's, the input rules and
// the computed normals. Throws SceneError naming the file: a PLY or glTF file in a build
// without assimp, or whatever its loader finds.
Scene load_mesh_file(const std::string& path, const ObjLoadOptions& opt = {});

// PLY (ASCII or binary): its faces in file order, polygons triangulated as OBJ's are
// (Triangulate.h), the file's vertex normals, else computed ones (VertexNormals.h). Every face
// gets `override_material`, else a default grey.
Scene load_ply(const std::string& path, const ObjLoadOptions& opt = {});
// glTF 2.0 (.gltf with its buffers and images, or .glb): the default scene's meshes placed by
// the node hierarchy, metallic-roughness materials on the ggx shader (GltfMaterial.h).
Scene load_gltf(const std::string& path, const ObjLoadOptions& opt = {});

}  // namespace rt
