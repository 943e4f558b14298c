// Comparing two renders bit for bit (colour, depth, primitive id, normal, ray count), as
// the backend and strategy tests do.
#pragma once

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>

#include "rill/rt/Tracer.h"

namespace rt::testing {

// Bitwise equality, flushing denormals on both sides (docs/accuracy.md: a backend may flush
// them).
inline float flush(float x) {
  return std::fpclassify(x) == FP_SUBNORMAL ? std::copysign(0.0f, x) : x;
}
inline bool same(float a, float b) {
  return std::bit_cast<uint32_t>(flush(a)) == std::bit_cast<uint32_t>(flush(b));
}

inline void expect_identical(const RenderResult& a, const RenderResult& b,
                             const std::string& what) {
  ASSERT_EQ(a.color.size(), b.color.size());
  int diff = 0;
  for (size_t p = 0; p < a.color.size(); ++p) {
    bool ok = a.prim[p] == b.prim[p] && same(a.depth[p], b.depth[p]);
    for (int c = 0; c < 3; ++c)
      ok = ok && same(a.color[p][c], b.color[p][c]) && same(a.normal[p][c], b.normal[p][c]);
    if (!ok && ++diff <= 3)
      ADD_FAILURE() << what << ": pixel " << p << " differs: colour " << a.color[p].x << " "
                    << a.color[p].y << " " << a.color[p].z << " vs " << b.color[p].x << " "
                    << b.color[p].y << " " << b.color[p].z << ", prim " << a.prim[p] << " vs "
                    << b.prim[p];
  }
  EXPECT_EQ(diff, 0) << what;
  EXPECT_EQ(a.rays, b.rays) << what;
}

}  // namespace rt::testing
