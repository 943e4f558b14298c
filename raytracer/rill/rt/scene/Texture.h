// Textures as the scene holds them: a bitmap (PNG, decoded to linear RGB) or a procedural
// texture (a DSL function, kernel/Textures.h) with its parameters. Materials bind them to
// colour parameters (Material.h); the tracer uploads every texture a used material reads
// into Rill arrays and samples it at the hit's texture coordinates (kernel/Textures.h).
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rt {

// What a bitmap does outside [0, 1]: repeat (the default), clamp to the edge texel, or
// mirror every other repetition.
enum class WrapMode { Repeat, Clamp, Mirror };
// Parses "repeat", "clamp" or "mirror"; throws std::invalid_argument naming the value.
WrapMode parse_wrap_mode(const std::string& s);
const char* wrap_mode_name(WrapMode w);

// A procedural texture's largest scale (Scene::validate).
inline constexpr float kMaxTextureScale = 1e6f;

struct Texture {
  std::string name;             // the key in the scene's "textures" (or the file name)
  std::string type = "bitmap";  // "bitmap", or a procedural texture's name (checker, ...)
  // bitmap
  std::string file;  // where it came from, for messages
  int width = 0, height = 0;
  std::vector<glm::vec3> texels;  // linear RGB, width * height, row 0 at the top (v = 1)
  WrapMode wrap = WrapMode::Repeat;
  bool bilinear = true;  // false: nearest texel
  // procedural (kernel/Textures.h): two colours and the size of the pattern's period
  glm::vec3 color1{0.9f}, color2{0.2f};
  float scale = 1.0f;
};

// Reads a PNG (8 or 16 bits, grey or colour, with or without alpha; alpha is ignored) as
// linear RGB: srgb decodes the sRGB transfer curve (colour maps, the default), otherwise the
// values are taken as they are (data maps). Throws SceneError naming the file when it is
// missing, unreadable or not a PNG, and, before decoding, when its header declares a size over
// the limits of ImageLimits.h (naming the size and the limits).
Texture load_png_texture(const std::string& path, bool srgb = true);
// The same from a PNG's bytes; `path` names it in errors and in the texture.
Texture decode_png_texture(const std::string& bytes, const std::string& path, bool srgb = true);

// The linear value of an 8-bit sRGB code (the exact curve, IEC 61966-2-1).
float srgb8_to_linear(unsigned char c);

// The procedural textures' types, which the tracer implements on the device
// (kernel/Textures.h): "checker" (of uv * scale), and the solid textures "noise", "marble"
// and "wood" (of the hit point P * scale); each blends between color1 and color2.
const std::vector<std::string>& procedural_texture_types();

// Whether a texture is looked up at a surface's texture coordinates (a bitmap, a checker)
// rather than at the point itself (the solid textures).
bool reads_texture_coordinates(const Texture& t);

}  // namespace rt
