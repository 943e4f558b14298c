// What the kernels are generated with, decided on the host from the scene: only what the
// scene calls for is generated. A scene without reflective materials has no reflection
// code, one without lights no shadow rays, one without glass no refraction code and no ray
// stack; only the shaders its materials use are compiled in (kernel/MaterialTable.h), and
// texture code only where a material binds a texture.
#pragma once

#include <string>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

struct Scene;
struct SurfaceShader;
using MaterialShaders = std::vector<const SurfaceShader*>;  // per material (kernel/Shader.h)

struct Features {
  bool geometry = false;  // any traceable triangle (else every ray misses)
  bool lights = false;    // point lights (else a headlight at the eye, no shadows)
  // Whitted only: emitting materials are area lights too, options.light_samples points drawn
  // on them per shaded point (kernel/Shading.h, loop_light); with neither these nor point
  // lights, the headlight.
  bool area_lights = false;
  // Spot or directional lights, or (Whitted) a point light with inverse-square falloff:
  // the lights' shapes (kernel/LightShape.h). Without, point lights' code alone.
  bool light_shapes = false;
  bool shadows = false;         // shadow rays (lights or area lights, and options.shadows)
  bool specular = false;        // any used material with a Phong highlight, and lights
  bool reflection = false;      // any used material that reflects (shader lobes)
  bool refraction = false;      // any used material that transmits (Fresnel, TIR)
  bool vertex_normals = false;  // interpolated normals (mesh normals and smooth_normals)
  bool vertex_colors = false;   // per-vertex colours multiply the diffuse colour
  bool texcoords = false;       // per-vertex texture coordinates (a used texture needs them)
  bool dynamic = false;         // animated objects: the BVH beside the grid (accel/Bvh.h)
  int stack = 0;                // ray stack entries (refraction: reflected branch)
  // The camera's rays (the scene's camera: a tracer renders cameras of this kind only).
  CameraKind camera = CameraKind::Pinhole;
  std::string str() const;  // "geometry lights shadows ..." for logs and stats
};

constexpr int kRayStack = 3;

// shaders: one per material of s, as resolve_shaders gives them (shaders/Registry.h).
Features scene_features(const Scene& s, const MaterialShaders& shaders);
// Per material: whether a triangle that can be hit uses it (a usable one, or any that moves:
// it may be usable at another time). The kernels contain only these materials' shaders.
std::vector<bool> used_materials(const Scene& s);

}  // namespace rt
