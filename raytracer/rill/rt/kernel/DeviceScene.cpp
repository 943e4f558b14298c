// Uploads a scene for the kernels (DeviceScene.h).
#include "rill/rt/kernel/DeviceScene.h"

namespace rt {

DeviceScene::DeviceScene(const Scene& scene, const Grid& g, const TracerOptions& knobs,
                         const Features& features, const MaterialShaders& shaders)
    : K(knobs), F(features), options(scene.options) {
  grid.upload(g);
  tris.upload(scene, K, F);
  materials.upload(scene, F, shaders);
  lights.upload(scene);
  // The light buffer is per point light: area lights' shadow rays walk the grid.
  if (F.shadows && !scene.lights.empty())
    light_buffer.upload(build_light_buffer(scene, g, light_buffer_res(scene)));
  shading.upload(scene);
  light_count = static_cast<int>(scene.lights.size());
  background = scene.background;
  camera.kind = F.camera;
  camera.lens_seed.set(static_cast<int32_t>(scene.options.seed));
  if (F.area_lights) {  // Whitted's area lights draw from the same table (Shading::loop_light)
    path_lights.upload(scene, tris, F, {}, materials.textures());
    shading.area_samples(scene.options);
  } else if (scene.options.integrator == Integrator::Path) {
    std::vector<bool> smooth;
    for (size_t m = 0; m < scene.materials.size(); ++m) {
      const Bsdf& b = shaders.at(m)->bsdf;
      smooth.push_back(!b.smooth ||
                       b.smooth(MaterialParams(scene.materials[m], shaders.at(m)->params)));
    }
    path_lights.upload(scene, tris, F, smooth, materials.textures());
  }
}

}  // namespace rt
