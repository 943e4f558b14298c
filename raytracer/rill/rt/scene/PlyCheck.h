// The structure of a PLY file, checked before assimp reads it: assimp's PLY reader takes a
// header's counts on trust (a file with fewer vertices than declared loads its face lines as
// vertices) and reads indices unchecked, so Rill walks the header and every element first and
// refuses a file whose data does not match its header, naming the element and the number.
#pragma once

#include <cstddef>
#include <string>

namespace rt {

struct PlyLayout {
  bool binary = false;
  size_t vertices = 0;   // the "vertex" element's count
  size_t faces = 0;      // the "face" element's count (0 without one)
  bool normals = false;  // the vertex element has nx, ny, nz
  bool colors = false;   // the vertex element has red, green, blue
};

// Checks `bytes` (the whole file; `path` names it in messages): the magic line "ply", the
// format (ascii 1.0, binary_little_endian 1.0 or binary_big_endian 1.0), known property types,
// a vertex element with x, y and z, a face element (if any) with a vertex_indices (or
// vertex_index) list, and data that is exactly what the header declares: every ASCII value a
// number, lists' counts >= 0, nothing missing, nothing but blanks after the last element.
// Throws SceneError "path: ...".
PlyLayout check_ply(const std::string& bytes, const std::string& path);

}  // namespace rt
