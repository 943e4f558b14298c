// How far two intersectors agree on the same rays' closest hits (rill-bench-trace's Embree and
// bounce sections: Rill's against Embree's). A ray agrees when both report the same primitive
// (both missing included), or when both hit at the same distance within 1e-5 relative: a ray
// through an edge or vertex that triangles share may pick either of them, and both answers
// are right. Everything else is a mismatch, counted by kind rather than hidden.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace bench {

// The relative distance tolerance: the two triangle tests round differently, in the last few
// ulps of the distance (about 1e-7 relative each), far below it.
constexpr float kSameDistance = 1e-5f;

struct HitAgreement {
  size_t rays = 0;
  size_t same = 0;   // the same primitive, or both miss
  size_t agree = 0;  // same, or both hit at the same distance (another triangle of an edge)
  // The mismatches, by kind: only the first intersector hits; only the second; both hit, at
  // different distances.
  size_t only_first = 0, only_second = 0, other_hit = 0;

  double fraction() const {
    return rays == 0 ? 1.0 : static_cast<double>(agree) / static_cast<double>(rays);
  }
  size_t mismatches() const { return rays - agree; }
  // "0", or "12: 3 only Rill, 4 only Embree, 5 another hit" with the given names.
  std::string mismatch_str(const char* first, const char* second) const {
    if (mismatches() == 0) return "0";
    return std::to_string(mismatches()) + ": " + std::to_string(only_first) + " only " + first +
           ", " + std::to_string(only_second) + " only " + second + ", " +
           std::to_string(other_hit) + " another hit";
  }
};

// Primitive ids (-1: miss) and distances of the same rays from two intersectors.
inline HitAgreement compare_hits(const std::vector<int32_t>& prim_a,
                                 const std::vector<float>& dist_a,
                                 const std::vector<int32_t>& prim_b,
                                 const std::vector<float>& dist_b) {
  HitAgreement h;
  h.rays = std::min(prim_a.size(), prim_b.size());
  for (size_t i = 0; i < h.rays; ++i) {
    const bool hit_a = prim_a[i] >= 0, hit_b = prim_b[i] >= 0;
    if (prim_a[i] == prim_b[i]) {  // -1 for both: both miss
      ++h.same;
      ++h.agree;
    } else if (hit_a && hit_b &&
               std::fabs(dist_a[i] - dist_b[i]) <= kSameDistance * std::max(dist_a[i], dist_b[i])) {
      ++h.agree;
    } else if (hit_a && hit_b) {
      ++h.other_hit;
    } else if (hit_a) {
      ++h.only_first;
    } else {
      ++h.only_second;
    }
  }
  return h;
}

}  // namespace bench
