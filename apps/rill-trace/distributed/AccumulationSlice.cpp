// A tile's part of the running sums (AccumulationSlice.h).
#include "distributed/AccumulationSlice.h"

#include <algorithm>

namespace rt::distributed {

namespace {

// Copies a w x h block from `src` (rows of src_width pixels, starting at (sx, sy)) to `dst`
// (rows of dst_width, starting at (dx, dy)).
void copy_rows(std::vector<glm::vec3>& dst, int dst_width, int dx, int dy,
               const std::vector<glm::vec3>& src, int src_width, int sx, int sy, int w, int h) {
  for (int y = 0; y < h; ++y) {
    const auto from = src.begin() + (static_cast<size_t>(sy + y) * src_width + sx);
    std::copy(from, from + w, dst.begin() + (static_cast<size_t>(dy + y) * dst_width + dx));
  }
}

}  // namespace

Accumulation slice_of(const Accumulation& whole, const Tile& t) {
  Accumulation part;
  part.width = t.width;
  part.height = t.height;
  part.samples = whole.samples;
  const size_t n = static_cast<size_t>(t.width) * static_cast<size_t>(t.height);
  auto cut = [&](std::vector<glm::vec3>& dst, const std::vector<glm::vec3>& src) {
    if (src.empty()) return;
    dst.resize(n);
    copy_rows(dst, t.width, 0, 0, src, whole.width, t.x, t.y, t.width, t.height);
  };
  cut(part.sum, whole.sum);
  cut(part.carry, whole.carry);
  cut(part.squares, whole.squares);
  return part;
}

void place_slice(Accumulation& whole, const Tile& t, const Accumulation& part) {
  const size_t n = static_cast<size_t>(whole.width) * static_cast<size_t>(whole.height);
  auto put = [&](std::vector<glm::vec3>& dst, const std::vector<glm::vec3>& src) {
    if (src.empty()) return;
    if (dst.empty()) dst.assign(n, glm::vec3(0.0f));
    copy_rows(dst, whole.width, t.x, t.y, src, t.width, 0, 0, t.width, t.height);
  };
  put(whole.sum, part.sum);
  put(whole.carry, part.carry);
  put(whole.squares, part.squares);
}

}  // namespace rt::distributed
