// Taking whole meshes out of a scene after it was built: a JSON file's prototype meshes
// (docs/scene-format.md, "instances") are loaded like any mesh, so that their instances copy
// them, and then removed, so that they render only through those copies.
#pragma once

#include <cstddef>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

// Triangles [first, first + count) of a scene.
struct TriangleRange {
  size_t first = 0, count = 0;
};

// Removes the triangles of `ranges` (which must not overlap) from `s`: their positions,
// normals, colours, texture coordinates and material indices. The triangles after them keep
// their order and move down (their primitive ids close up); an animated object inside a
// removed range goes with it, and the others' ranges are renumbered. Materials and textures
// stay. Throws SceneError for a range past the scene's end or an animated object that a
// range cuts in two.
void remove_triangles(Scene& s, std::vector<TriangleRange> ranges);

}  // namespace rt
