// glTF materials onto the ggx shader (GltfMaterial.h), read from assimp's material
// properties (its glTF 2.0 importer's keys: AI_MATKEY_BASE_COLOR, ..._METALLIC_FACTOR, ...).
#include "rill/rt/scene/GltfMaterial.h"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace rt {

namespace {

// A factor from the file: non-finite values are refused (JSON has no NaN, but 1e39 is an
// infinite float), the rest clamped to [lo, hi].
float factor(float v, float lo, float hi, const std::string& where) {
  if (!std::isfinite(v)) throw SceneError(where + " is not a finite number");
  return std::clamp(v, lo, hi);
}

glm::vec3 colour(const aiColor4D& c, float hi, const std::string& where) {
  return glm::vec3(factor(c.r, 0.0f, hi, where), factor(c.g, 0.0f, hi, where),
                   factor(c.b, 0.0f, hi, where));
}

// The texture of type `type` (its first), read as linear RGB (srgb: colour textures), or
// nullopt-like false when the material has none.
bool read_texture(const aiScene& scene, const aiMaterial& m, aiTextureType type,
                  const std::string& path, const std::string& where, Texture& out,
                  std::vector<std::string>& ignored) {
  aiString name;
  if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &name) != AI_SUCCESS) return false;
  const std::string file = name.C_Str();
  try {
    if (!file.empty() && file[0] == '*') {
      // An image embedded in the file (a .glb's buffer view, a data URI): assimp's "*N".
      const aiTexture* t = scene.GetEmbeddedTexture(file.c_str());
      if (t == nullptr || t->pcData == nullptr || t->mHeight != 0)
        throw SceneError("embedded image " + clipped(file) + " is missing");
      if (std::string(t->achFormatHint) != "png")
        throw SceneError("embedded image " + clipped(file) + " is '" + clipped(t->achFormatHint) +
                         "', and Rill reads PNG images only");
      out = decode_png_texture(std::string(reinterpret_cast<const char*>(t->pcData), t->mWidth),
                               path + " (embedded image " + file + ")");
    } else {
      std::filesystem::path f(file);
      if (f.is_relative()) f = std::filesystem::path(path).parent_path() / f;
      out = load_png_texture(f.string());
    }
  } catch (const SceneError& e) {
    throw SceneError(path + ": " + where + ": " + e.what());
  }
  out.name = file;
  int uv = 0;
  if (m.Get(AI_MATKEY_UVWSRC(type, 0), uv) == AI_SUCCESS && uv != 0)
    ignored.push_back("texCoord " + std::to_string(uv) + " (textures read TEXCOORD_0)");
  int mode = aiTextureMapMode_Wrap;
  if (m.Get(AI_MATKEY_MAPPINGMODE_U(type, 0), mode) == AI_SUCCESS) {
    out.wrap = mode == aiTextureMapMode_Clamp    ? WrapMode::Clamp
               : mode == aiTextureMapMode_Mirror ? WrapMode::Mirror
                                                 : WrapMode::Repeat;
  }
  return true;
}

// A copy of t with every texel times a and plus b (a factor baked in).
int add_scaled(Scene& s, const Texture& t, const glm::vec3& a, const glm::vec3& b,
               const std::string& what) {
  Texture c = t;
  for (glm::vec3& x : c.texels) x = x * a + b;
  c.name = t.name + " (" + what + ")";
  s.textures.push_back(std::move(c));
  return static_cast<int>(s.textures.size()) - 1;
}

}  // namespace

int add_gltf_material(Scene& s, const aiScene& scene, const aiMaterial& m, const std::string& path,
                      std::vector<std::string>& ignored) {
  Material out;
  out.name = m.GetName().C_Str();
  if (out.name.empty()) out.name = "gltf-material";
  out.shader = "ggx";
  const std::string where = "material '" + clipped(out.name) + "'";
  aiColor4D base(1.0f, 1.0f, 1.0f, 1.0f);
  m.Get(AI_MATKEY_BASE_COLOR, base);
  float metallic = 1.0f, roughness = 1.0f;  // glTF's defaults
  m.Get(AI_MATKEY_METALLIC_FACTOR, metallic);
  m.Get(AI_MATKEY_ROUGHNESS_FACTOR, roughness);
  const glm::vec3 bc = colour(base, 1.0f, path + ": " + where + " baseColorFactor");
  metallic = factor(metallic, 0.0f, 1.0f, path + ": " + where + " metallicFactor");
  roughness = factor(roughness, 0.0f, 1.0f, path + ": " + where + " roughnessFactor");
  out.set("roughness", roughness);
  Texture tex;
  if (read_texture(scene, m, aiTextureType_BASE_COLOR, path, where + " baseColorTexture", tex,
                   ignored) ||
      read_texture(scene, m, aiTextureType_DIFFUSE, path, where + " baseColorTexture", tex,
                   ignored)) {
    // F0 = 0.04 (1 - m) + base m, diffuse = base (1 - m), base = factor * texel.
    if (metallic > 0.0f)
      out.params["specular"] = ParamValue::of_texture(
          add_scaled(s, tex, bc * metallic, glm::vec3(0.04f * (1.0f - metallic)), "F0"));
    else
      out.set("specular", glm::vec3(0.04f));
    if (metallic < 1.0f)
      out.params["diffuse"] = ParamValue::of_texture(
          add_scaled(s, tex, bc * (1.0f - metallic), glm::vec3(0.0f), "diffuse"));
    else
      out.set("diffuse", glm::vec3(0.0f));
  } else {
    out.set("specular", glm::vec3(0.04f * (1.0f - metallic)) + bc * metallic);
    out.set("diffuse", bc * (1.0f - metallic));
  }
  aiColor4D emissive(0.0f, 0.0f, 0.0f, 1.0f);
  m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
  float strength = 1.0f;  // KHR_materials_emissive_strength
  m.Get(AI_MATKEY_EMISSIVE_INTENSITY, strength);
  strength = factor(strength, 0.0f, 1e30f, path + ": " + where + " emissiveStrength");
  out.emission = colour(emissive, 1e30f, path + ": " + where + " emissiveFactor") * strength;
  if (read_texture(scene, m, aiTextureType_EMISSIVE, path, where + " emissiveTexture", tex,
                   ignored)) {
    // The emission is the texture times the factor: Material::emission is the scale.
    s.textures.push_back(std::move(tex));
    out.emission_texture = static_cast<int>(s.textures.size()) - 1;
  }
  int two_sided = 0;
  if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) out.two_sided = two_sided != 0;
  // What the ggx material cannot hold.
  if (m.GetTextureCount(aiTextureType_UNKNOWN) > 0) ignored.push_back("metallicRoughnessTexture");
  if (m.GetTextureCount(aiTextureType_NORMALS) > 0) ignored.push_back("normalTexture");
  if (m.GetTextureCount(aiTextureType_LIGHTMAP) > 0) ignored.push_back("occlusionTexture");
  aiString alpha;
  if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, alpha) == AI_SUCCESS &&
      std::string(alpha.C_Str()) != "OPAQUE")
    ignored.push_back("alphaMode " + clipped(alpha.C_Str()) + " (surfaces are opaque)");
  return s.add_material(out);
}

}  // namespace rt
