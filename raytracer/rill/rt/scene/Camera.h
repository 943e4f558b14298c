// The camera of docs/camera.md, exactly: every quantity in float32, in the documented
// order, so that another renderer can cast the same rays.
//
//   forward = normalize(look_at - eye); right = normalize(cross(forward, up));
//   true_up = cross(right, forward); a = W / H;
//   t = tan(fov_y * 0.5f * 0.0174532924f)  (argument in float32, tangent in double, rounded once)
//   sx = ((i + 0.5) / W * 2 - 1) * t * a;  sy = (1 - (j + 0.5) / H * 2) * t;
//   dir = normalize(forward + sx * right + sy * true_up);  origin = eye
//
// normalize(v) is v / sqrt(dot(v, v)) with dot(a, b) = (a.x*b.x + a.y*b.y) + a.z*b.z, as in
// the DSL. The host part (frame, t, a) is computed here once; the per-pixel part runs in the
// kernel (kernel/CameraRays.cpp) and, for tests, in camera_ray() below.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

struct CameraFrame {
  glm::vec3 eye, forward, right, up;
  float tan_half = 0;  // t; an orthographic camera's half height h = height * 0.5f
  float aspect = 0;    // a = W / H
  float width = 0, height = 0;
  CameraKind kind = CameraKind::Pinhole;
  float lens_radius = 0;  // thin lens: R, the aperture
  float lens_k = 0;       // thin lens: k = R / focus_distance
};

// The kernel variant a camera needs.
CameraKind camera_kind(const Camera& c);
// "pinhole", "orthographic" or "thin lens", for messages.
const char* camera_kind_name(CameraKind k);

// float32 helpers with the DSL's evaluation order.
float dot3(const glm::vec3& a, const glm::vec3& b);
glm::vec3 cross3(const glm::vec3& a, const glm::vec3& b);
glm::vec3 normalize3(const glm::vec3& v);

CameraFrame camera_frame(const Camera& c, int width, int height);
// The ray through pixel (i, j) at sub-pixel offset (ox, oy) (0.5, 0.5 = the centre).
glm::vec3 camera_ray(const CameraFrame& f, int i, int j, float ox = 0.5f, float oy = 0.5f);

// A camera ray of any kind: its origin and unit direction. lens is the thin lens's point on
// the unit disk (lens_point); the other kinds ignore it.
struct CameraRay {
  glm::vec3 origin, direction;
};
CameraRay camera_ray(const CameraFrame& f, int i, int j, float ox, float oy, glm::vec2 lens);
// The thin lens's point for pixel (i, j) of the image and the pixel's sample k, on the unit
// disk (docs/camera.md, "The thin lens"): Philox4x32-10 of counter (i, j, k, 0) and key
// (seed, 0x4c656e73), its first two words as floats on the grid of 2^-24, mapped by the
// concentric mapping (lens_disk).
glm::vec2 lens_point(uint32_t seed, int i, int j, int k);
inline constexpr uint32_t kLensKey = 0x4c656e73;  // "Lens": the key's second word
// The concentric mapping of (u, v) in [0, 1)^2 onto the unit disk, with its sine and cosine
// polynomials, in float32 and in the documented order.
glm::vec2 lens_disk(glm::vec2 u);
// The farthest a camera ray's origin lies from the world's origin (bounded above): |eye| for a
// pinhole, plus the lens's radius or the orthographic view's half diagonal.
float camera_origin_reach(const CameraFrame& f);

// The pixels whose camera rays may meet the box [lo, hi], at any sample offset in [0, 1)^2:
// columns [first.x, end.x) and rows [first.y, end.y), within the image. Conservative by three
// pixels on every side, more on a view so narrow that the rays' rounding moves them further. The
// whole image when the box is not finite or reaches to within a thousandth of its size from the
// eye's plane (the projection of a box that surrounds the eye or lies beside it is unbounded), and
// an empty rectangle for an empty box (lo > hi) or one wholly behind the eye's plane.
struct PixelRect {
  glm::ivec2 first{0}, end{0};
  bool empty() const { return first.x >= end.x || first.y >= end.y; }
};
PixelRect pixels_seeing_box(const CameraFrame& f, const glm::vec3& lo, const glm::vec3& hi);

// An axis-aligned box; empty where lo > hi.
struct Aabb {
  glm::vec3 lo{0.0f}, hi{-1.0f};
};

// The image cut into tiles of tile x tile pixels (a power of two), and per tile whether one of
// its pixels may see one of a list of boxes (pixels_seeing_box): where the scene's objects lie
// on screen, more closely than their common box's rectangle. The kernels look a pixel's tile
// up (kernel/CameraRays.h); a pixel in a tile marked 0 sees none of the boxes.
struct TileMask {
  int shift = 0;  // tile = 1 << shift
  glm::ivec2 tiles{0};
  std::vector<int32_t> seen;  // tiles.x * tiles.y, row by row: 1 or 0
  PixelRect bounds;           // the union of the boxes' rectangles
};
// Tiles of 8 pixels, or larger where the image would have more than 2^18 of them.
TileMask tiles_seeing_boxes(const CameraFrame& f, const std::vector<Aabb>& boxes);

}  // namespace rt
