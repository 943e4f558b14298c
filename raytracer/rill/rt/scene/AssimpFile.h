// A PLY or glTF file read by assimp (Debian's libassimp 5.2) under Rill's rules for input
// files: every file assimp opens (the mesh, a glTF's .bin buffers and images) is read with
// read_input_file (InputFile.h: regular files only, the size limit, recorded for rill-trace's
// check that no output overwrites an input), and assimp's errors become SceneErrors naming
// the file. assimp's warnings (it drops faces with out-of-range indices with only a warning) are
// kept for the loader, never lost. No post-processing step runs: Rill triangulates polygons
// (Triangulate.h) and computes missing normals (VertexNormals.h) itself, as for OBJ files.
#pragma once

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <string>
#include <vector>

namespace rt {

class AssimpFile {
 public:
  // `kind` names the format in messages ("PLY", "glTF").
  AssimpFile(const std::string& path, const std::string& kind);
  const aiScene& scene() const { return *scene_; }
  // What assimp's log said at warning level and above while reading, one line each.
  const std::vector<std::string>& log() const { return log_; }

 private:
  Assimp::Importer importer_;
  const aiScene* scene_ = nullptr;
  std::vector<std::string> log_;
};

}  // namespace rt
