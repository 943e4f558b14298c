// glTF 2.0 metallic-roughness materials as Rill materials on the ggx shader (shaders/Ggx.cpp),
// following the glTF specification's own approximation of its BRDF (Appendix B):
//   specular (F0) = mix(0.04, base colour, metallic)
//   diffuse       = base colour * (1 - metallic)
//   roughness     = roughnessFactor (ggx's alpha = roughness^2, as glTF's)
// with base colour = baseColorFactor (rgb) times baseColorTexture, and emission =
// emissiveFactor times emissiveTexture. A texture with a factor is baked into a texture of
// its own (texels times the factor), since a bitmap texture has no scale.
#pragma once

#include <string>
#include <vector>

#include "rill/rt/scene/Scene.h"

struct aiMaterial;
struct aiScene;

namespace rt {

// Adds the material to `s` (and the textures it reads: PNG files beside the glTF or images
// embedded in it) and returns its index. `ignored` collects what of the material Rill does not
// map (names of features, for one warning per file). Throws SceneError naming the file and
// the material: a missing or unreadable texture, an image that is not a PNG.
int add_gltf_material(Scene& s, const aiScene& scene, const aiMaterial& m, const std::string& path,
                      std::vector<std::string>& ignored);

}  // namespace rt
