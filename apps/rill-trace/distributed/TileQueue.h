// The tiles of one image and who renders them: rank 0's dynamic queue.
//
// Tiles are handed out one at a time to whichever rank asks, so a fast rank (a GPU) takes
// many and a slow one few, and the ranks finish together within about one tile's time. A
// rank that is lost gives its unfinished tiles back to the front of the queue; a tile that
// comes back twice (a slow rank declared lost, then answering) counts once. The queue knows
// nothing of MPI, so it is tested on its own. An image sequence (--frames) is one queue of
// every frame's tiles, frame after frame: the ranks work on one or two frames at a time, and
// each frame is complete (and written) long before the last.
#pragma once

#include <deque>
#include <optional>
#include <vector>

namespace rt::distributed {

struct Tile {
  int id = 0;     // its index in the queue: frame by frame, row-major within a frame
  int frame = 0;  // the animation frame it belongs to
  int x = 0, y = 0, width = 0, height = 0;
};

// The tiles of `frames` width x height images (frames first_frame, first_frame + 1, ...),
// `size` pixels square (those on the right and bottom edges smaller), row by row from the top
// left, frame after frame.
std::vector<Tile> make_tiles(int width, int height, int size, int first_frame = 0, int frames = 1);

// Cuts the last `count` tiles into tiles of `size` pixels (those at a tile's right and bottom
// edges smaller), in place and in order, and numbers every tile again: the tail of the queue
// in small tiles, so that the ranks finish within a small tile's time of each other while the
// rest of the job goes in few, large launches. size < 1: nothing changes.
void split_tail(std::vector<Tile>& tiles, int count, int size);

class TileQueue {
 public:
  explicit TileQueue(std::vector<Tile> tiles);

  // The next tile for `rank`, now in flight there; none when the queue is empty.
  std::optional<Tile> next(int rank);
  // The tile came back from `rank`: true the first time it is done (its pixels are to be
  // kept), false for a tile done already.
  bool finish(int rank, int id);
  // `rank` is lost: its tiles in flight go back to the front of the queue. Returns how many.
  int requeue(int rank);

  int total() const { return static_cast<int>(tiles_.size()); }
  int done() const { return done_count_; }
  bool complete() const { return done_count_ == total(); }
  bool queued() const { return !queue_.empty(); }
  // The tiles in flight at `rank`.
  std::vector<int> in_flight(int rank) const;
  const Tile& tile(int id) const { return tiles_.at(static_cast<size_t>(id)); }
  bool is_done(int id) const { return done_.at(static_cast<size_t>(id)); }

 private:
  std::vector<Tile> tiles_;
  std::deque<int> queue_;
  std::vector<int> owner_;  // the rank a tile is in flight at, -1: none
  std::vector<bool> done_;
  int done_count_ = 0;
};

}  // namespace rt::distributed
