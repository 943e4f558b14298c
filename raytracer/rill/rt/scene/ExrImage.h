// OpenEXR output (through the OpenEXR library): linear 32-bit float channels, bit for bit, and
// 32-bit unsigned integer channels, one file for the colour and the AOVs.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rt {

// A channel's pixel type in the file: FLOAT (binary32, every bit kept: infinities, -0,
// denormals, NaN) or UINT (32-bit unsigned).
enum class ExrType { Float, Uint };

// One channel to write: width * height values, row 0 at the top, left to right (the layout of
// RenderResult's images), `step` values apart (3 for one component of RenderResult::color's
// glm::vec3s). Exactly one of `floats` and `uints` is set, as `type` says.
struct ExrChannel {
  std::string name;
  ExrType type = ExrType::Float;
  const float* floats = nullptr;
  const uint32_t* uints = nullptr;
  int step = 1;

  static ExrChannel of_floats(std::string name, const float* data, int step = 1) {
    return {std::move(name), ExrType::Float, data, nullptr, step};
  }
  static ExrChannel of_uints(std::string name, const uint32_t* data, int step = 1) {
    return {std::move(name), ExrType::Uint, nullptr, data, step};
  }
};

// Writes a scanline EXR file, ZIP-compressed (lossless), with the channels given. Rows are
// stored top to bottom (INCREASING_Y, data window (0,0)..(width-1,height-1)); the file lists
// the channels sorted by name, as OpenEXR requires. Written whole or not at all
// (write_output_file): the file is made in memory (its compressed size, besides the pixels)
// and then written, so that an error at any point (a full disk, a directory that does not exist)
// throws SceneError naming `path` and leaves no file. Throws SceneError for a size below 1, a
// channel without data, or two channels of one name.
void write_exr(const std::string& path, int width, int height,
               const std::vector<ExrChannel>& channels);

// An EXR file read back (for tests and tools): each channel as FLOAT (HALF widened) or UINT.
struct ExrImage {
  struct Channel {
    std::string name;
    ExrType type = ExrType::Float;
    std::vector<float> floats;    // type Float: width * height, row 0 at the top
    std::vector<uint32_t> uints;  // type Uint
  };
  int width = 0, height = 0;      // of the data window
  std::vector<Channel> channels;  // in the file's order (sorted by name)

  // The channel of that name, or nullptr.
  const Channel* find(const std::string& name) const;
};

// Reads a scanline or tiled EXR file's first part. Throws SceneError naming the file when it
// is missing, unreadable, not an EXR file, has a subsampled channel, or its header declares a
// size or a channel count over the limits (ImageLimits.h), checked before allocating.
ExrImage read_exr(const std::string& path);

}  // namespace rt
