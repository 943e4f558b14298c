#include "rill/rt/render/ResultFiles.h"

#include "rill/rt/scene/ExrImage.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/Scene.h"

#include <cctype>
#include <filesystem>

namespace rt {

namespace {

size_t pixels(const RenderResult& r) {
  return static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
}

// The three components of one glm::vec3 per pixel as channels PREFIX + R, G, B (or X, Y, Z).
void add_rgb(std::vector<ExrChannel>& channels, const std::vector<glm::vec3>& v,
             const std::string& prefix, const char* names = "RGB") {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  for (int c = 0; c < 3; ++c)
    channels.push_back(ExrChannel::of_floats(prefix + names[c], &v[0].x + c, 3));
}

bool has_colour(const RenderResult& r) {
  return r.color.size() == pixels(r) && !r.color.empty();
}

}  // namespace

void write_png(const std::string& path, const RenderResult& r) {
  if (r.rgb8.size() == pixels(r) * 3 && !r.rgb8.empty()) {
    write_png_rgb8(path, r.width, r.height, r.rgb8);
  } else if (has_colour(r)) {
    write_png(path, r.width, r.height, r.color);
  } else {
    throw SceneError("cannot write " + path +
                     ": the render read back neither its colour nor its 8-bit image "
                     "(RenderSettings::outputs.color or .rgb8)");
  }
}

void write_exr(const std::string& path, const RenderResult& r) {
  const size_t n = pixels(r);
  if (!has_colour(r))
    throw SceneError("cannot write " + path +
                     ": the render read back no colour (RenderSettings::outputs.color)");
  std::vector<ExrChannel> channels;
  add_rgb(channels, r.color, "");
  if (r.depth.size() == n) channels.push_back(ExrChannel::of_floats("Z", r.depth.data()));
  if (r.normal.size() == n) add_rgb(channels, r.normal, "N.", "XYZ");
  // int32_t and uint32_t may alias: the same bits, -1 read as 4294967295.
  if (r.prim.size() == n)
    channels.push_back(
        ExrChannel::of_uints("prim", reinterpret_cast<const uint32_t*>(r.prim.data())));
  if (r.variance.size() == n) add_rgb(channels, r.variance, "var.");
  if (r.albedo.size() == n) add_rgb(channels, r.albedo, "albedo.");
  write_exr(path, r.width, r.height, channels);
}

void write_pfm(const std::string& path, const RenderResult& r) {
  if (!has_colour(r))
    throw SceneError("cannot write " + path +
                     ": the render read back no colour (RenderSettings::outputs.color)");
  write_pfm(path, r.width, r.height, r.color);
}

void save(const RenderResult& r, const std::string& path) {
  const std::string as_given = std::filesystem::path(path).extension().string();
  std::string ext = as_given;
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".png") return write_png(path, r);
  if (ext == ".pfm") return write_pfm(path, r);
  if (ext == ".exr") return write_exr(path, r);
  throw SceneError(
      "cannot save " + path + ": " +
      (as_given.empty() ? std::string("no extension") : "unknown extension " + as_given) +
      " (rt::save writes .png 8-bit sRGB, .pfm linear colour, .exr linear colour "
      "and the AOVs read back)");
}

}  // namespace rt
