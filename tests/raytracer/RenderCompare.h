// Comparing two renders bit for bit (colour, depth, primitive id, normal, ray count), as
// the backend and strategy tests do.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "rill/rt/Tracer.h"

namespace rt::testing {

// The same bytes, denormals included (an empty vector's data() may be null, which memcmp
// must not get even for 0 bytes).
template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Bitwise equality, flushing denormals on both sides (docs/accuracy.md: a backend may flush
// them).
inline float flush(float x) {
  return std::fpclassify(x) == FP_SUBNORMAL ? std::copysign(0.0f, x) : x;
}
inline bool same(float a, float b) {
  return std::bit_cast<uint32_t>(flush(a)) == std::bit_cast<uint32_t>(flush(b));
}

// The settings of a render that a test compares: the scene's size and samples per pixel, on
// `backend`, with the AOVs read back (expect_identical compares them too).
inline RenderSettings compared_settings(const Scene& scene, const std::string& backend) {
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
  rs.backend = backend;
  rs.width = scene.width;
  rs.height = scene.height;
  rs.spp = scene.options.spp;
  return rs;
}

inline void expect_identical(const RenderResult& a, const RenderResult& b,
                             const std::string& what) {
  ASSERT_EQ(a.color.size(), b.color.size());
  // The AOVs where the renders read them back (FrameOutputs), both or neither.
  ASSERT_EQ(a.prim.size(), b.prim.size()) << what;
  ASSERT_EQ(a.depth.size(), b.depth.size()) << what;
  ASSERT_EQ(a.normal.size(), b.normal.size()) << what;
  const bool prim = !a.prim.empty(), depth = !a.depth.empty(), normal = !a.normal.empty();
  int diff = 0;
  for (size_t p = 0; p < a.color.size(); ++p) {
    bool ok = (!prim || a.prim[p] == b.prim[p]) && (!depth || same(a.depth[p], b.depth[p]));
    for (int c = 0; c < 3; ++c)
      ok = ok && same(a.color[p][c], b.color[p][c]) &&
           (!normal || same(a.normal[p][c], b.normal[p][c]));
    if (!ok && ++diff <= 3)
      ADD_FAILURE() << what << ": pixel " << p << " differs: colour " << a.color[p].x << " "
                    << a.color[p].y << " " << a.color[p].z << " vs " << b.color[p].x << " "
                    << b.color[p].y << " " << b.color[p].z << ", prim " << (prim ? a.prim[p] : 0)
                    << " vs " << (prim ? b.prim[p] : 0);
  }
  EXPECT_EQ(diff, 0) << what;
  EXPECT_EQ(a.rays, b.rays) << what;
}

// The pixels of `whole` that a window covers, as a RenderResult of the window's size: each
// per-pixel vector that `whole` holds (colour, AOVs, the 8-bit image's 3 bytes a pixel).
inline RenderResult crop(const RenderResult& whole, const RenderSettings::Window& w) {
  RenderResult c;
  c.width = w.width;
  c.height = w.height;
  auto rows = [&](const auto& from, auto& to, size_t per_pixel) {
    if (from.empty()) return;
    for (int y = w.y; y < w.y + w.height; ++y) {
      const size_t p = static_cast<size_t>(y) * static_cast<size_t>(whole.width) + w.x;
      const auto begin = from.begin() + static_cast<std::ptrdiff_t>(p * per_pixel);
      to.insert(to.end(), begin, begin + static_cast<std::ptrdiff_t>(w.width * per_pixel));
    }
  };
  rows(whole.color, c.color, 1);
  rows(whole.depth, c.depth, 1);
  rows(whole.prim, c.prim, 1);
  rows(whole.normal, c.normal, 1);
  rows(whole.albedo, c.albedo, 1);
  rows(whole.rgb8, c.rgb8, 3);
  return c;
}

}  // namespace rt::testing
