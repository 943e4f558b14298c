// 8-bit sRGB encoding on the device, with the same bytes as the host's to_srgb8
// (scene/Image.h).
//
// The host encodes with std::pow in double, which no backend can promise to reproduce bit
// for bit. The encoding is monotonic, though, so it is fully described by 255 thresholds:
// the smallest float that encodes to each level 1..255. The device counts the thresholds at
// or below a value by a binary search (8 gathers), so its byte equals the host's for every
// float, NaN and infinities included, on every backend and accuracy.
#pragma once

#include <rill/rill.h>

#include <array>
#include <cstdint>

namespace rt {

// threshold[L - 1]: the smallest float v with to_srgb8(v) >= L, for L in 1..255.
const std::array<float, 255>& srgb8_thresholds();

// The encoded level (0..255) of one linear value, gathered from `thresholds` (an array of
// srgb8_thresholds()).
rill::Int encode_srgb8(const rill::Float& linear, const rill::Array<rill::Float>& thresholds);

// Packs an encoded colour into one Int (r + 256 g + 65536 b), and back on the host.
rill::Int pack_rgb8(const rill::Int& r, const rill::Int& g, const rill::Int& b);
inline void unpack_rgb8(uint32_t packed, unsigned char* rgb) {
  rgb[0] = static_cast<unsigned char>(packed & 0xff);
  rgb[1] = static_cast<unsigned char>((packed >> 8) & 0xff);
  rgb[2] = static_cast<unsigned char>((packed >> 16) & 0xff);
}

}  // namespace rt
