// The distributed renderer's tile queue (apps/rill-trace/distributed/TileQueue.h), without
// MPI: the tiles cover the image once, a lost rank's tiles come back, a tile counts once.
#include <gtest/gtest.h>

#include <set>
#include <tuple>
#include <vector>

#include "distributed/TileQueue.h"

namespace rt::distributed {
namespace {

TEST(TileQueue, TilesCoverTheImageOnce) {
  for (auto [w, h, size] : {std::tuple{48, 36, 12}, {37, 23, 7}, {5, 3, 64}, {1, 1, 1}}) {
    std::vector<int> covered(static_cast<size_t>(w * h), 0);
    const std::vector<Tile> tiles = make_tiles(w, h, size);
    for (size_t i = 0; i < tiles.size(); ++i) {
      const Tile& t = tiles[i];
      EXPECT_EQ(t.id, static_cast<int>(i));
      EXPECT_GE(t.width, 1);
      EXPECT_LE(t.width, size);
      EXPECT_LE(t.height, size);
      for (int y = t.y; y < t.y + t.height; ++y)
        for (int x = t.x; x < t.x + t.width; ++x) ++covered[static_cast<size_t>(y * w + x)];
    }
    for (int c : covered) ASSERT_EQ(c, 1) << w << "x" << h << " in tiles of " << size;
    EXPECT_EQ(tiles.size(), static_cast<size_t>(((w + size - 1) / size) * ((h + size - 1) / size)));
  }
  EXPECT_THROW(make_tiles(4, 4, 0), std::invalid_argument);
  EXPECT_THROW(make_tiles(0, 4, 2), std::invalid_argument);
}

// A sequence's tiles: every frame's in order, ids running on from frame to frame, each frame
// covered as a still is.
TEST(TileQueue, FramesFollowEachOther) {
  const std::vector<Tile> still = make_tiles(37, 23, 7);
  const std::vector<Tile> tiles = make_tiles(37, 23, 7, 5, 3);
  ASSERT_EQ(tiles.size(), 3 * still.size());
  for (size_t i = 0; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    const Tile& s = still[i % still.size()];
    EXPECT_EQ(t.id, static_cast<int>(i));
    EXPECT_EQ(t.frame, 5 + static_cast<int>(i / still.size()));
    EXPECT_EQ(std::tie(t.x, t.y, t.width, t.height), std::tie(s.x, s.y, s.width, s.height));
  }
  EXPECT_THROW(make_tiles(4, 4, 2, 0, 0), std::invalid_argument);
  TileQueue q(tiles);
  EXPECT_EQ(q.next(1)->frame, 5);
}

// The queue's tail in small tiles: the tiles before it as they were, the last ones cut, the
// image still covered once, ids in order.
TEST(TileQueue, SplitTailCutsTheLastTiles) {
  std::vector<Tile> tiles = make_tiles(40, 30, 16, 0, 2);  // 3x2 tiles a frame, 12 in all
  const std::vector<Tile> whole = tiles;
  split_tail(tiles, 3, 8);
  // Tiles 9, 10, 11 of frame 1: 16x16 -> 4 tiles, 8x14 (x 32) -> 2, 16x14 -> 4.
  ASSERT_EQ(tiles.size(), 9u + 4u + 2u + 4u);
  for (size_t i = 0; i < tiles.size(); ++i) EXPECT_EQ(tiles[i].id, static_cast<int>(i));
  for (size_t i = 0; i < 9; ++i)
    EXPECT_EQ(std::tie(tiles[i].frame, tiles[i].x, tiles[i].y, tiles[i].width, tiles[i].height),
              std::tie(whole[i].frame, whole[i].x, whole[i].y, whole[i].width, whole[i].height));
  std::vector<int> covered(40 * 30, 0);
  for (const Tile& t : tiles) {
    if (t.frame != 1) continue;
    EXPECT_LE(t.width, t.id >= 9 ? 8 : 16);
    for (int y = t.y; y < t.y + t.height; ++y)
      for (int x = t.x; x < t.x + t.width; ++x) ++covered[static_cast<size_t>(y * 40 + x)];
  }
  for (int c : covered) ASSERT_EQ(c, 1);
  std::vector<Tile> same = whole;
  split_tail(same, 3, 0);
  EXPECT_EQ(same.size(), whole.size());
}

TEST(TileQueue, HandsOutEachTileAndTakesBackALostRanks) {
  TileQueue q(make_tiles(8, 8, 4));  // 4 tiles
  ASSERT_EQ(q.total(), 4);
  const Tile a = *q.next(1), b = *q.next(2), c = *q.next(1);
  EXPECT_EQ(a.id, 0);
  EXPECT_EQ(b.id, 1);
  EXPECT_EQ(c.id, 2);
  EXPECT_EQ(q.in_flight(1), (std::vector<int>{0, 2}));
  EXPECT_TRUE(q.finish(1, a.id));
  // Rank 1 is lost with tile 2 in hand: it goes back to the front, before tile 3.
  EXPECT_EQ(q.requeue(1), 1);
  EXPECT_TRUE(q.in_flight(1).empty());
  EXPECT_EQ(q.next(2)->id, 2);
  EXPECT_EQ(q.next(3)->id, 3);
  EXPECT_FALSE(q.next(3).has_value());
  EXPECT_TRUE(q.finish(2, 1));
  EXPECT_TRUE(q.finish(2, 2));
  // Tile 2 from rank 1 after all (it was slow, not dead): counted once.
  EXPECT_FALSE(q.finish(1, 2));
  EXPECT_EQ(q.done(), 3);
  EXPECT_FALSE(q.complete());
  EXPECT_TRUE(q.finish(3, 3));
  EXPECT_TRUE(q.complete());
  EXPECT_THROW(q.finish(3, 4), std::out_of_range);
}

TEST(TileQueue, ATileDoneElsewhereIsNotHandedOutAgain) {
  TileQueue q(make_tiles(4, 4, 2));  // 4 tiles
  const Tile t = *q.next(1);
  EXPECT_TRUE(q.finish(1, t.id));
  EXPECT_EQ(q.requeue(1), 0);  // nothing in flight there
  // A tile handed out to 2, requeued when 2 is lost, then returned by 2 all the same.
  const Tile u = *q.next(2);
  EXPECT_EQ(q.requeue(2), 1);
  EXPECT_TRUE(q.finish(2, u.id));
  std::set<int> handed;
  while (std::optional<Tile> n = q.next(3)) handed.insert(n->id);
  EXPECT_EQ(handed, (std::set<int>{2, 3}));
}

}  // namespace
}  // namespace rt::distributed
