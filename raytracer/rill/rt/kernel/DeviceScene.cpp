// Uploads a scene for the kernels (DeviceScene.h).
#include "rill/rt/kernel/DeviceScene.h"

namespace rt {

DeviceScene::DeviceScene(const Scene& scene, const Grid& g, const TracerOptions& options,
                         const Features& features, const MaterialShaders& shaders)
    : K(options), F(features) {
  grid.upload(g);
  tris.upload(scene, K, F);
  materials.upload(scene, F, shaders);
  lights.upload(scene);
  if (F.shadows) light_buffer.upload(build_light_buffer(scene, g, light_buffer_res(scene)));
  shading.upload(scene);
  light_count = static_cast<int>(scene.lights.size());
  background = scene.background;
}

}  // namespace rt
