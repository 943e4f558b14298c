// Image output: PNG for people, PFM (portable float map) for comparisons.
#pragma once

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace rt {

// Linear colour -> 8-bit sRGB PNG (clamped to [0, 1]). Rows top to bottom.
void write_png(const std::string& path, int w, int h, const std::vector<glm::vec3>& rgb);
// An image already encoded as 8-bit sRGB (3 bytes per pixel, RenderResult::rgb8) as PNG.
void write_png_rgb8(const std::string& path, int w, int h, const std::vector<unsigned char>& rgb8);
// 8-bit sRGB encoding of one linear value.
unsigned char to_srgb8(float linear);
// PFM, little-endian, rows stored bottom to top as the format requires.
void write_pfm(const std::string& path, int w, int h, const std::vector<glm::vec3>& rgb);
void write_pfm(const std::string& path, int w, int h, const std::vector<float>& grey);
// Reads a PFM (either kind) into 3 or 1 channels per pixel, rows top to bottom. Throws
// std::runtime_error naming the file when it is not a PFM, shorter than its header says, or
// larger than the limits (ImageLimits.h; SceneError), before allocating.
std::vector<float> read_pfm(const std::string& path, int& w, int& h, int& channels);
// The same from a PFM's bytes; `path` names it in errors.
std::vector<float> parse_pfm(const std::string& bytes, const std::string& path, int& w, int& h,
                             int& channels);

}  // namespace rt
