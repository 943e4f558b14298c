// Vertex normals for a mesh that has none (an OBJ file without `vn`): each corner of a
// triangle gets the weighted mean of the face normals of the triangles that share its vertex
// and bend from its own face by at most the crease angle, so curved surfaces shade smooth and
// hard edges stay hard. The weights are the faces' angles at the vertex (the default), their
// areas, or both multiplied.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace rt {

// The default crease angle in degrees: faces meeting at a larger angle keep a hard edge
// between them. 60 smooths coarse curved meshes (a 12-sided cylinder's faces meet at 30
// degrees) and keeps a box's 90-degree edges sharp.
inline constexpr float kDefaultCreaseDegrees = 60.0f;

// How much each face counts in a vertex's normal. Angle (Thuermer and Wuethrich 1998): its
// interior angle at the vertex, so the normal depends neither on how a polygon was cut into
// triangles nor on the faces' sizes. Area: its area, so big faces dominate slivers (Gouraud's
// mean of cross products). AreaAngle: the product, Blender's "face area and angle".
enum class NormalWeighting { Angle, Area, AreaAngle };
// "angle", "area" or "area_angle"; throws std::invalid_argument naming the value and these.
NormalWeighting parse_normal_weighting(const std::string& s);

struct NormalMesh {
  // Three corners per triangle, in the triangles' order.
  std::span<const glm::vec3> positions;
  // Per corner: the vertex it is (the OBJ vertex index); corners with the same one share.
  std::span<const int32_t> vertex;
  // Per triangle: its smoothing group; triangles of different groups never share, and group
  // 0 stays flat (OBJ `s off`). Empty: all in one group.
  std::span<const uint32_t> group;
};

// Unit normals, three per triangle (the corners' order). A corner that shares with no other
// face gets its own face's normal; a triangle with no area (or a non-finite vertex) gets
// (0, 0, 0) at its corners and adds nothing to its neighbours'.
std::vector<glm::vec3> vertex_normals(const NormalMesh& mesh,
                                      float crease_degrees = kDefaultCreaseDegrees,
                                      NormalWeighting weighting = NormalWeighting::Angle);

// Copies a triangle's three computed normals (`computed`, from vertex_normals) into n and
// says whether the triangle stays flat: every corner got its own face normal (or none), as
// the faces of a box do. The loaders then add it without normals, so that a mesh of hard edges
// loads as it did without smoothing, and renders with the same kernel and bits.
bool keeps_flat(const glm::vec3 p[3], const glm::vec3* computed, glm::vec3 n[3]);

}  // namespace rt
