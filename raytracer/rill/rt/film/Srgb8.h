// 8-bit sRGB encoding on the device, with the same bytes as the host's to_srgb8
// (scene/Image.h).
//
// The host encodes with std::pow in double, which no backend can promise to reproduce bit
// for bit. The encoding is monotonic, though, so it is fully described by 255 thresholds:
// the smallest float that encodes to each level 1..255. A level is the count of thresholds
// at or below the value, so the device's byte equals the host's for every float, NaN and
// infinities included, on every backend and accuracy.
//
// The count takes one gather instead of a binary search's eight: the value's bit pattern
// (exponent and top mantissa bits) picks a bucket, and at most two thresholds lie inside any
// bucket (checked when the table is made). The bucket's entry holds the count below it and
// the next two thresholds, so two comparisons finish the count.
#pragma once

#include <rill/rill.h>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace rt {

// threshold[L - 1]: the smallest float v with to_srgb8(v) >= L, for L in 1..255.
const std::array<float, 255>& srgb8_thresholds();

// The host side of the buckets: a value c in [0, 1] falls in bucket
// max((bits(c) >> kSrgb8BucketShift) - kSrgb8FirstBucket, 0).
inline constexpr int kSrgb8BucketShift = 16;
inline constexpr int kSrgb8FirstBucket = (127 - 13) << (23 - kSrgb8BucketShift);  // 2^-13
struct Srgb8Tables {
  std::vector<float> thresholds;  // srgb8_thresholds() and two 2.0f, read past the end
  // Per bucket: the count of thresholds at or below its first float (`below`), and the bit
  // patterns of thresholds[below] and thresholds[below + 1]: the device reads one entry.
  std::vector<glm::ivec3> buckets;
};
// Made once; throws if a bucket would hold more than two thresholds.
const Srgb8Tables& srgb8_tables();

// The tables on the device and the encoding that reads them.
class Srgb8Encoder {
 public:
  Srgb8Encoder();
  // The encoded level (0..255) of one linear value.
  rill::Int encode(const rill::Float& linear) const;

 private:
  rill::Array<rill::Int3> buckets_;
};

}  // namespace rt
