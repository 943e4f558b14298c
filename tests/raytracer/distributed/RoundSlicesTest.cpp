// What a round of a progressive render under mpirun moves between rank 0 and a worker
// (apps/rill-trace/distributed/AccumulationSlice.h, Messages.h), without MPI: the tiles'
// slices of the sums put back together give the sums bit for bit, each pixel's floats where
// they were; an Assign and a TileDone come through their bytes unchanged, and cut bytes are
// refused.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "distributed/AccumulationSlice.h"
#include "distributed/Messages.h"
#include "distributed/TileQueue.h"

namespace rt::distributed {
namespace {

// Sums whose every float differs (pixel index and channel), with squares if asked.
Accumulation numbered(int width, int height, int samples, bool squares) {
  Accumulation a;
  a.width = width;
  a.height = height;
  a.samples = samples;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  for (size_t i = 0; i < n; ++i) {
    const float f = static_cast<float>(i);
    a.sum.emplace_back(f, f + 0.25f, f + 0.5f);
    a.carry.emplace_back(-f, 1e-7f * f, 0.125f);
    if (squares) a.squares.emplace_back(f * f, 3.0f, f + 0.75f);
  }
  return a;
}

bool same_bits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  // memcmp of an empty vector's null data is undefined, even for 0 bytes.
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]) == 0);
}

TEST(RoundSlices, TheTilesSlicesPutBackAreTheSums) {
  for (auto [w, h, size, squares] :
       {std::tuple{48, 36, 12, true}, {37, 23, 7, false}, {5, 3, 64, true}, {1, 1, 1, false}}) {
    SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + " tiles of " + std::to_string(size));
    const Accumulation whole = numbered(w, h, 5, squares);
    Accumulation back;
    back.width = w;
    back.height = h;
    back.sum.assign(whole.sum.size(), glm::vec3(0.0f));
    back.carry.assign(whole.carry.size(), glm::vec3(0.0f));
    for (const Tile& t : make_tiles(w, h, size)) {
      const Accumulation part = slice_of(whole, t);
      ASSERT_EQ(part.width, t.width);
      ASSERT_EQ(part.height, t.height);
      EXPECT_EQ(part.samples, 5);
      ASSERT_EQ(part.sum.size(), static_cast<size_t>(t.width * t.height));
      EXPECT_EQ(part.squares.size(), squares ? part.sum.size() : 0u);
      // The tile's first pixel is the image's pixel at the tile's corner.
      EXPECT_EQ(part.sum[0], whole.sum[static_cast<size_t>(t.y * w + t.x)]);
      place_slice(back, t, part);
    }
    EXPECT_TRUE(same_bits(back.sum, whole.sum));
    EXPECT_TRUE(same_bits(back.carry, whole.carry));
    EXPECT_TRUE(same_bits(back.squares, whole.squares));
  }
}

TEST(RoundSlices, AssignAndTileDoneSurviveTheirBytes) {
  Assign a;
  a.tile = Tile{7, 0, 14, 21, 7, 5};
  a.spp = 12;
  a.accumulation = true;
  a.resume = numbered(7, 5, 4, true);
  Assign b;
  unpack(pack(a), b);
  EXPECT_EQ(b.tile.id, 7);
  EXPECT_EQ(b.tile.x, 14);
  EXPECT_EQ(b.tile.y, 21);
  EXPECT_EQ(b.tile.width, 7);
  EXPECT_EQ(b.tile.height, 5);
  EXPECT_EQ(b.spp, 12);
  EXPECT_TRUE(b.accumulation);
  EXPECT_EQ(b.resume.samples, 4);
  EXPECT_EQ(b.resume.width, 7);
  EXPECT_TRUE(same_bits(b.resume.sum, a.resume.sum));
  EXPECT_TRUE(same_bits(b.resume.carry, a.resume.carry));
  EXPECT_TRUE(same_bits(b.resume.squares, a.resume.squares));

  TileDone d;
  d.id = 3;
  d.pixels.width = 7;
  d.pixels.height = 5;
  d.pixels.spp = 12;
  d.pixels.color.assign(35, glm::vec3(0.5f));
  d.pixels.accumulation = numbered(7, 5, 12, false);
  TileDone e;
  const Bytes bytes = pack(d);
  unpack(bytes, e);
  EXPECT_EQ(e.id, 3);
  EXPECT_EQ(e.pixels.spp, 12);
  EXPECT_EQ(e.pixels.accumulation.samples, 12);
  EXPECT_TRUE(same_bits(e.pixels.accumulation.sum, d.pixels.accumulation.sum));
  EXPECT_TRUE(same_bits(e.pixels.accumulation.carry, d.pixels.accumulation.carry));
  EXPECT_TRUE(e.pixels.accumulation.squares.empty());
  EXPECT_TRUE(same_bits(e.pixels.color, d.pixels.color));
  // Cut short by a byte: refused, never read past the end.
  const Bytes cut(bytes.begin(), bytes.end() - 1);
  EXPECT_THROW(unpack(cut, e), std::runtime_error);
}

}  // namespace
}  // namespace rt::distributed
