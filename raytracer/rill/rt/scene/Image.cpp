#include "rill/rt/scene/Image.h"

#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/OutputFile.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace rt {

unsigned char to_srgb8(float v) {
  if (!(v > 0.0f)) return 0;  // also NaN
  if (v >= 1.0f) return 255;
  double s =
      v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(static_cast<double>(v), 1.0 / 2.4) - 0.055;
  return static_cast<unsigned char>(std::lround(s * 255.0));
}

void write_png(const std::string& path, int w, int h, const std::vector<glm::vec3>& rgb) {
  std::vector<unsigned char> px(rgb.size() * 3);
  for (size_t i = 0; i < rgb.size(); ++i)
    for (int c = 0; c < 3; ++c) px[i * 3 + static_cast<size_t>(c)] = to_srgb8(rgb[i][c]);
  write_png_rgb8(path, w, h, px);
}

void write_png_rgb8(const std::string& path, int w, int h, const std::vector<unsigned char>& px) {
  if (px.size() != static_cast<size_t>(w) * static_cast<size_t>(h) * 3)
    throw std::runtime_error("cannot write " + path + ": " + std::to_string(px.size()) +
                             " bytes for a " + std::to_string(w) + "x" + std::to_string(h) +
                             " RGB image");
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = PNG_FORMAT_RGB;
  // Encoded in memory, then written through the checked writer: libpng's own file writer
  // removes the file it could not write, which in place is the device itself (as root,
  // --out /dev/full deleted /dev/full). Encoded once, into libpng's bound on the encoded
  // size (asking for the exact size first compresses the image twice: 15 ms of a 640x320
  // first image); the bound's pages that the encoder does not reach are never touched.
  png_alloc_size_t size = PNG_IMAGE_PNG_SIZE_MAX(image);
  const std::unique_ptr<char[]> bytes(new char[size]);
  if (!png_image_write_to_memory(&image, bytes.get(), &size, 0, px.data(), 0, nullptr))
    throw std::runtime_error("cannot write " + path + ": " + image.message);
  write_output_file(path, std::string_view(bytes.get(), size));
}

namespace {

void write_pfm_raw(const std::string& path, int w, int h, int channels, const float* data,
                   size_t floats) {
  if (w < 1 || h < 1 ||
      floats != static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels))
    throw std::runtime_error("cannot write " + path + ": " + std::to_string(floats) +
                             " values for a " + std::to_string(w) + "x" + std::to_string(h) +
                             " image of " + std::to_string(channels) + " channel(s)");
  const std::string header = std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(w) +
                             " " + std::to_string(h) + "\n-1.0\n";
  const size_t row = static_cast<size_t>(w) * static_cast<size_t>(channels);
  write_output_file(path, [&](OutputSink& out) {
    out.write(header);
    for (int y = h - 1; y >= 0; --y)  // rows bottom to top
      out.write(data + static_cast<size_t>(y) * row, row * sizeof(float));
  });
}

}  // namespace

void write_pfm(const std::string& path, int w, int h, const std::vector<glm::vec3>& rgb) {
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  write_pfm_raw(path, w, h, 3, reinterpret_cast<const float*>(rgb.data()), rgb.size() * 3);
}

void write_pfm(const std::string& path, int w, int h, const std::vector<float>& grey) {
  write_pfm_raw(path, w, h, 1, grey.data(), grey.size());
}

std::vector<float> parse_pfm(const std::string& bytes, const std::string& path, int& w, int& h,
                             int& channels) {
  std::istringstream in(bytes);
  std::string magic;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  if (!in || (magic != "PF" && magic != "Pf") || w < 1 || h < 1 || !(scale < 0))
    throw std::runtime_error(path + ": not a little-endian PFM file");
  if (in.get() == std::char_traits<char>::eof())  // the one whitespace byte before the data
    throw std::runtime_error(path + ": truncated PFM file (no data after the header)");
  channels = magic == "PF" ? 3 : 1;
  // The header's size against the bytes that follow it, before allocating: a header that
  // claims 100000x100000 pixels in a 20-byte file is an error, not a 120 GB allocation.
  const auto at = static_cast<uint64_t>(std::max<std::streamoff>(in.tellg(), 0));
  const uint64_t left = bytes.size() - std::min<uint64_t>(at, bytes.size());
  // In this order, so that no product wraps: w and h are below 2^31.
  const uint64_t floats_left = left / (static_cast<uint64_t>(channels) * sizeof(float));
  const uint64_t need = static_cast<uint64_t>(w) * static_cast<uint64_t>(h) *
                        static_cast<uint64_t>(channels) * sizeof(float);
  if (static_cast<uint64_t>(w) * static_cast<uint64_t>(h) > floats_left)
    throw std::runtime_error(path + ": truncated PFM file (" + std::to_string(w) + "x" +
                             std::to_string(h) + " needs " + std::to_string(need) +
                             " bytes of data, the file has " + std::to_string(left) + ")");
  // Bytes enough, and a size Rill could have written (ImageLimits.h).
  check_declared_image(path, "PFM", w, h);
  const size_t row = static_cast<size_t>(w) * static_cast<size_t>(channels);
  std::vector<float> data(row * static_cast<size_t>(h));
  // Rows are stored bottom to top.
  for (int y = h - 1; y >= 0; --y)
    std::memcpy(data.data() + static_cast<size_t>(y) * row,
                bytes.data() + at + static_cast<size_t>(h - 1 - y) * row * sizeof(float),
                row * sizeof(float));
  return data;
}

std::vector<float> read_pfm(const std::string& path, int& w, int& h, int& channels) {
  return parse_pfm(read_input_file(path, "a PFM file"), path, w, h, channels);
}

}  // namespace rt
