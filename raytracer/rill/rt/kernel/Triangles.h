// The scene's triangles as the kernels see them, in Rill arrays indexed by primitive id:
// Moller-Trumbore's form (v0, e1 = v1 - v0, e2 = v2 - v0), the unit geometric normal, and
// what the scene and the knobs call for: the vertices themselves (the watertight test),
// vertex normals, colours and texture coordinates, and the material index.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/Options.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

struct Triangles {
  rill::Array<rill::Float3> v0{1, "tri_v0"}, e1{1, "tri_e1"}, e2{1, "tri_e2"}, ng{1, "tri_ng"};
  // The watertight test needs the vertices themselves: v0 + e1 rounds, and a shared edge
  // must be computed from the same bits in both of its triangles.
  rill::Array<rill::Float3> v1{1, "tri_v1"}, v2{1, "tri_v2"};
  rill::Array<rill::Float3> n0{1, "tri_n0"}, n1{1, "tri_n1"}, n2{1, "tri_n2"};
  rill::Array<rill::Float3> c0{1, "tri_c0"}, c1{1, "tri_c1"}, c2{1, "tri_c2"};
  // Texture coordinates, three entries per triangle (one array: on GLSL each is a texture
  // unit, and the multipass kernels are near the limit).
  rill::Array<rill::Float2> uv{1, "tri_uv"};
  rill::Array<rill::Int> material{1, "tri_mat"};

  // Uploads what F and the knobs need. Missing vertex normals (colours) where F forces them
  // on are the geometric normal (white).
  void upload(const Scene& scene, const TracerOptions& K, const Features& F);
  // Only what moves with the vertices (positions, edges, normals): each frame of a dynamic
  // scene. Colours, texture coordinates and materials stay as upload() left them.
  void upload_geometry(const Scene& scene, const TracerOptions& K, const Features& F);
  // The same for triangles first .. end - 1 only, after upload(): the others keep their
  // values on the host and the device (a backend uploads only the words that changed).
  void update_geometry(const Scene& scene, const TracerOptions& K, const Features& F, size_t first,
                       size_t end);
};

}  // namespace rt
