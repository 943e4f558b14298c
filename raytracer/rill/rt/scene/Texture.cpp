// Bitmap textures from PNG files (libpng's simplified API), the sRGB decoding table, wrap
// mode names and the list of procedural texture types (Texture.h).
#include "rill/rt/scene/Texture.h"

#include <png.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

WrapMode parse_wrap_mode(const std::string& s) {
  if (s == "repeat") return WrapMode::Repeat;
  if (s == "clamp") return WrapMode::Clamp;
  if (s == "mirror") return WrapMode::Mirror;
  throw std::invalid_argument("unknown wrap mode '" + s + "' (repeat, clamp or mirror)");
}

const char* wrap_mode_name(WrapMode w) {
  switch (w) {
    case WrapMode::Repeat:
      return "repeat";
    case WrapMode::Clamp:
      return "clamp";
    case WrapMode::Mirror:
      return "mirror";
  }
  return "repeat";
}

const std::vector<std::string>& procedural_texture_types() {
  static const std::vector<std::string> types = {"checker", "noise", "marble", "wood"};
  return types;
}

bool reads_texture_coordinates(const Texture& t) {
  return t.type == "bitmap" || t.type == "checker";
}

float srgb8_to_linear(unsigned char c) {
  // Computed once in double and rounded to float, so that every platform decodes the same
  // bits whatever its pow().
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) {
      const double v = i / 255.0;
      t[static_cast<size_t>(i)] =
          static_cast<float>(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
    }
    return t;
  }();
  return table[c];
}

Texture decode_png_texture(const std::string& bytes, const std::string& path, bool srgb) {
  // The signature first: libpng's own message for another format ("Not a PNG file") does not
  // name the file, and a short file should say so.
  if (bytes.size() < 8 || png_sig_cmp(reinterpret_cast<png_const_bytep>(bytes.data()), 0, 8) != 0)
    throw SceneError(path + ": not a PNG file");
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()))
    throw SceneError(path + ": cannot read the PNG: " + image.message);
  // 16-bit files without gamma information are taken as sRGB-encoded like 8-bit ones (libpng
  // would assume linear and re-encode them), so that 16-bit data maps keep their values.
  image.flags |= PNG_IMAGE_FLAG_16BIT_sRGB;
  // RGBA, whose alpha is then dropped: alpha is ignored, as Texture.h says (reading RGB would
  // composite onto black). libpng converts grey, palettes and 16 bits.
  image.format = PNG_FORMAT_RGBA;
  // The size the header claims, checked before allocating: compressed data can claim far more
  // pixels than it holds (69 bytes can claim 16384x16384: 1 GiB of RGBA, 3 GiB of linear
  // floats), so a texture is held to the limits of a rendered image (ImageLimits.h).
  try {
    check_declared_image(path, "PNG", image.width, image.height);
  } catch (const SceneError&) {
    png_image_free(&image);
    throw;
  }
  std::vector<png_byte> px(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, px.data(), 0, nullptr))
    throw SceneError(path + ": cannot read the PNG: " + image.message);

  Texture t;
  t.name = std::filesystem::path(path).filename().string();
  t.type = "bitmap";
  t.file = path;
  t.width = static_cast<int>(image.width);
  t.height = static_cast<int>(image.height);
  t.texels.resize(static_cast<size_t>(t.width) * static_cast<size_t>(t.height));
  for (size_t i = 0; i < t.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const png_byte v = px[4 * i + static_cast<size_t>(c)];
      t.texels[i][c] = srgb ? srgb8_to_linear(v) : v / 255.0f;
    }
  return t;
}

Texture load_png_texture(const std::string& path, bool srgb) {
  return decode_png_texture(read_input_file(path, "a PNG file"), path, srgb);
}

}  // namespace rt
