// Everything the tracer's kernels read, in one place: the grid, the triangles, the
// materials (with their shaders and textures), the lights, the camera and the shading
// uniforms, uploaded once per tracer; and the DSL building blocks over them (Intersector,
// Shading). Both strategies (megakernel/, multipass/) build their programs from this.
#pragma once

#include "rill/rt/kernel/BvhView.h"
#include "rill/rt/kernel/CameraRays.h"
#include "rill/rt/kernel/GridView.h"
#include "rill/rt/kernel/Intersector.h"
#include "rill/rt/kernel/LightBufferView.h"
#include "rill/rt/kernel/LightSampler.h"
#include "rill/rt/kernel/MaterialTable.h"
#include "rill/rt/kernel/Shading.h"
#include "rill/rt/kernel/Triangles.h"

namespace rt {

struct DeviceScene {
  // Uploads the scene (validated) and the grid; F and K select what is uploaded and
  // generated.
  // shaders: those of the scene's materials (shaders/Registry.h, resolve_shaders).
  DeviceScene(const Scene& scene, const Grid& grid, const TracerOptions& K, const Features& F,
              const MaterialShaders& shaders);
  DeviceScene(const DeviceScene&) = delete;
  DeviceScene& operator=(const DeviceScene&) = delete;

  const TracerOptions K;
  const Features F;
  const SceneOptions options;  // the integrator and its settings among them
  GridView grid;
  BvhView bvh;  // the moving triangles' (F.dynamic): the Tracer uploads it, each frame
  Triangles tris;
  MaterialTable materials;
  Lights lights;
  LightBufferView light_buffer;  // the shadow rays' (F.shadows, SceneOptions::light_buffer)
  CameraRays camera;
  Intersector intersector{grid, bvh, light_buffer, lights.position, tris, K, F};
  // (path_lights, declared below, is only referred to here: constructed after shading, and
  // declared in this order so that every other scene's kernels are the same.)
  Shading shading{tris, materials, lights, path_lights, K, F};
  // The path integrator's lights (point lights and emitting triangles); uploaded under
  // Integrator::Path, and for Whitted's area lights (F.area_lights), which draw from it.
  LightSampler path_lights;
  int light_count = 0;         // host
  glm::vec3 background{0.0f};  // host (Shading::background's value)
};

}  // namespace rt
