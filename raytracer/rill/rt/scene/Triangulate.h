// Triangulation of an OBJ polygon face: a convex one is fanned around its first vertex (as Rill
// always did, so that its primitive ids stay those of docs/primitive-ids.md), a concave one is
// cut by ear clipping on its projection onto its best-fit plane.
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace rt {

// What triangulate() found about the polygon. Anything but Ok means the polygon was fanned
// (the only answer that exists for it), and the loader warns.
enum class PolygonShape {
  Ok,                // convex (fanned) or simple and concave (ear-clipped)
  Degenerate,        // no area: all its vertices on a line or a point (or not finite)
  SelfIntersecting,  // two of its edges cross, so it has no inside to cut
  TooLarge,          // concave with more than kMaxEarClipVertices vertices
};

// A concave polygon above this many vertices is fanned: ear clipping costs O(n^2) or more.
inline constexpr size_t kMaxEarClipVertices = 4096;

struct Triangulation {
  // The polygon's n - 2 triangles, as indices into its vertices, counter-clockwise seen from
  // the side the polygon's winding faces (as the fan's are).
  std::vector<std::array<uint32_t, 3>> triangles;
  PolygonShape shape = PolygonShape::Ok;
};

// `poly` holds the polygon's vertices in order (at least 3).
Triangulation triangulate(std::span<const glm::vec3> poly);

// The fan (v0, vk, vk+1), k = 1 .. n-2.
std::vector<std::array<uint32_t, 3>> fan(size_t n);

}  // namespace rt
