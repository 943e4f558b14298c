// The device's 8-bit sRGB encoding (Srgb8.h): thresholds found on the host, a binary search
// in the kernel.
#include "rill/rt/film/Srgb8.h"

#include <cstring>

#include "rill/rt/scene/Image.h"

namespace rt {

using namespace rill;

namespace {

float from_bits(uint32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

// The smallest positive float whose encoding reaches `level`: a binary search over the bit
// patterns of (0, 1], which are ordered like the floats they encode.
float first_float_at(int level) {
  uint32_t lo = 1, hi = 0x3f800000u;  // to_srgb8(1.0f) == 255 reaches every level
  while (lo < hi) {
    const uint32_t mid = lo + (hi - lo) / 2;
    if (to_srgb8(from_bits(mid)) >= level)
      hi = mid;
    else
      lo = mid + 1;
  }
  return from_bits(lo);
}

}  // namespace

const std::array<float, 255>& srgb8_thresholds() {
  static const std::array<float, 255> table = [] {
    std::array<float, 255> t{};
    for (int level = 1; level <= 255; ++level)
      t[static_cast<size_t>(level - 1)] = first_float_at(level);
    return t;
  }();
  return table;
}

Int encode_srgb8(const Float& linear, const Array<Float>& thresholds) {
  // How many thresholds lie at or below the value: steps 128, 64, ..., 1 reach any count in
  // 0..255, and a probe never passes 255 (before step s the count is at most 256 - 2s).
  // NaN compares false everywhere and encodes to 0, as on the host.
  Int level = 0;
  for (int step = 128; step >= 1; step /= 2) {
    Int probe = level + step;
    Bool reached = thresholds[probe - 1] <= linear;
    level = select(reached, probe, level);
  }
  return level;
}

Int pack_rgb8(const Int& r, const Int& g, const Int& b) {
  return r + g * 256 + b * 65536;
}

}  // namespace rt
