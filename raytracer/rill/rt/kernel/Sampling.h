// Monte Carlo building blocks in the DSL, shared by the BSDFs (shaders/) and the path
// integrator (integrator/): an orthonormal frame about a normal, the standard warps from the
// unit square, and the power heuristic of multiple importance sampling. Each is a few float
// operations in a fixed order, so under strict they give the same bits on every backend
// (sin and cos are Rill's own routines there).
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/Records.h"

namespace rt {

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.318309886183790671538f;

// An orthonormal frame (s, t, n) about the unit vector n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited": no branch, no singularity).
struct Basis {
  explicit Basis(const Float3& normal);
  Float3 s, t, n;
  Float3 to_world(const Float3& v) const { return s * v.x() + t * v.y() + n * v.z(); }
  Float3 to_local(const Float3& v) const { return Float3(dot(v, s), dot(v, t), dot(v, n)); }
};

// Cosine-weighted directions about +z (Malley's method on a uniform disk, polar mapping);
// density cos(theta) / pi.
Float3 cosine_hemisphere(const Float2& u);
// A uniform point on a triangle as barycentrics (b1, b2) of v0 + b1 e1 + b2 e2 (the
// square-root warp, pbrt's "uniform sampling of a triangle"); density 1 / area.
Float2 uniform_triangle(const Float2& u);

// The power heuristic's weight (beta = 2) of a strategy of density a against one of density b:
// a^2 / (a^2 + b^2), computed from the ratio of the smaller density to the larger so that
// neither square overflows (a density near a grazing light can be 1e30 or infinite): 0 when
// a is 0, 1 when b is 0 and a is not, 1/2 when both are infinite.
Float power_heuristic(const Float& a, const Float& b);

// The luminance weights of linear sRGB (Rec. 709 Y).
Float luminance(const Float3& c);

}  // namespace rt
