// The device's 8-bit sRGB encoding (Srgb8.h): thresholds and buckets found on the host, one
// gather and two comparisons in the kernel.
#include "rill/rt/film/Srgb8.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

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

Srgb8Tables make_tables() {
  const auto& t = srgb8_thresholds();
  Srgb8Tables out;
  out.thresholds.assign(t.begin(), t.end());
  // Read past the end for values near 1 (which the device clamps to at most 1): 2.0 is above
  // any of them, and finite (fast mode may assume there are no infinities).
  out.thresholds.insert(out.thresholds.end(), 2, 2.0f);
  auto at_or_below = [&](float v) {
    return static_cast<int32_t>(std::upper_bound(t.begin(), t.end(), v) - t.begin());
  };
  // Buckets run up to the one that holds 1.0f alone (the device clamps to [0, 1]).
  const uint32_t last = (0x3f800000u >> kSrgb8BucketShift) - kSrgb8FirstBucket;
  for (uint32_t b = 0; b <= last; ++b) {
    const uint32_t first_bits = b == 0 ? 0u : (b + kSrgb8FirstBucket) << kSrgb8BucketShift;
    const uint32_t last_bits =
        b == last ? 0x3f800000u : ((b + kSrgb8FirstBucket + 1) << kSrgb8BucketShift) - 1;
    const int32_t below = at_or_below(from_bits(first_bits));
    if (at_or_below(from_bits(last_bits)) - below > 2)
      throw std::logic_error("srgb8 buckets: bucket " + std::to_string(b) +
                             " holds more than two thresholds");
    out.buckets.emplace_back(
        below, std::bit_cast<int32_t>(out.thresholds[static_cast<size_t>(below)]),
        std::bit_cast<int32_t>(out.thresholds[static_cast<size_t>(below) + 1]));
  }
  return out;
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

const Srgb8Tables& srgb8_tables() {
  static const Srgb8Tables tables = make_tables();
  return tables;
}

Srgb8Encoder::Srgb8Encoder() : buckets_(srgb8_tables().buckets, "srgb8_buckets") {}

Int Srgb8Encoder::encode(const Float& linear) const {
  // max(0, x) returns its first operand for a NaN (Math.h), so NaN and negatives become 0
  // and encode to 0, as on the host; above 1 every threshold counts.
  Float c = min(max(Float(0.0f), linear), 1.0f);
  Int bucket = max((as_int(c) >> kSrgb8BucketShift) - kSrgb8FirstBucket, 0);
  Int3 entry = buckets_[bucket];
  Int next = select(as_float(entry.y()) <= c, Int(1), Int(0));
  Int after = select(as_float(entry.z()) <= c, Int(1), Int(0));
  return entry.x() + next + after;
}

}  // namespace rt
