// What makes a light more than a point light (scene/Scene.h, Light): a spot's cone, a
// directional light's direction, Whitted's inverse-square falloff. Both integrators read them
// from the same two arrays per light, made here, and the spot's cone factor is one DSL
// function, so Whitted (kernel/Shading.h) and the path integrator (kernel/LightSampler.h)
// agree on it.
//
// The cone factor of a spot whose axis makes angle theta with the direction to a point is
// pbrt's: 1 within inner_deg, 0 beyond outer_deg, and between them smoothstep(t) =
// t^2 (3 - 2 t) of t = (cos theta - cos outer) / (cos inner - cos outer); a hard edge where
// inner == outer.
//
// A scene without such lights has none of this code (Features::light_shapes): its kernels
// are those of a scene of point lights, as before spot and directional lights existed.
#pragma once

#include <rill/rill.h>

#include <vector>

#include "rill/rt/kernel/Records.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// The kinds in LightShapes::shape's x.
constexpr float kShapePoint = 0.0f, kShapeSpot = 1.0f, kShapeDirectional = 2.0f;

// Host: whether light l needs LightShapes under the integrator (the path integrator's point
// lights always fall off as 1/r^2, so falloff alone needs nothing there).
bool light_shaped(const Light& l, Integrator integrator);
bool any_light_shaped(const Scene& s);

// The cone factor as the host computes it in double (for the tests' and docs' formula):
// cos_theta the cosine between the spot's axis and the direction from it to the point.
double spot_cone_factor(const Light& l, double cos_theta);

struct LightShapes {
  // Per light: x its kind (kShape*), y the cosine of the outer angle, z of the inner one, w 1
  // for Whitted's inverse-square falloff (else 0).
  rill::Array<Float4> shape;
  // Per light: the unit axis of a spot, or the unit direction a directional light's light
  // travels (from the light into the scene).
  rill::Array<Float3> axis;
  // Arrays' names: the path integrator's and Whitted's tables are separate arrays.
  LightShapes(const char* shape_name, const char* axis_name)
      : shape(1, shape_name), axis(1, axis_name) {}
  void upload(const std::vector<Light>& lights);
  // The cone factor of light l (1 unless a spot) towards unit direction wi from the shaded
  // point to the light.
  Float cone(const Int& l, const Float3& wi) const;
  Bool directional(const Int& l) const { return shape[l].x() == kShapeDirectional; }
  Bool inverse_square(const Int& l) const { return shape[l].w() > 0.0f; }
};

}  // namespace rt
