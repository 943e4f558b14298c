// The dynamic tile queue (TileQueue.h).
#include "distributed/TileQueue.h"

#include <algorithm>
#include <stdexcept>

namespace rt::distributed {

std::vector<Tile> make_tiles(int width, int height, int size, int first_frame, int frames) {
  if (width < 1 || height < 1 || size < 1)
    throw std::invalid_argument("make_tiles: the image and the tiles need at least one pixel");
  if (frames < 1) throw std::invalid_argument("make_tiles: no frames");
  std::vector<Tile> tiles;
  for (int f = first_frame; f < first_frame + frames; ++f)
    for (int y = 0; y < height; y += size)
      for (int x = 0; x < width; x += size)
        tiles.push_back(Tile{static_cast<int>(tiles.size()), f, x, y, std::min(size, width - x),
                             std::min(size, height - y)});
  return tiles;
}

void split_tail(std::vector<Tile>& tiles, int count, int size) {
  if (size < 1 || count < 1) return;
  const size_t from = tiles.size() - std::min(tiles.size(), static_cast<size_t>(count));
  std::vector<Tile> tail;
  for (size_t i = from; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    for (int y = 0; y < t.height; y += size)
      for (int x = 0; x < t.width; x += size)
        tail.push_back(Tile{0, t.frame, t.x + x, t.y + y, std::min(size, t.width - x),
                            std::min(size, t.height - y)});
  }
  tiles.resize(from);
  tiles.insert(tiles.end(), tail.begin(), tail.end());
  for (size_t i = 0; i < tiles.size(); ++i) tiles[i].id = static_cast<int>(i);
}

TileQueue::TileQueue(std::vector<Tile> tiles)
    : tiles_(std::move(tiles)), owner_(tiles_.size(), -1), done_(tiles_.size(), false) {
  for (size_t i = 0; i < tiles_.size(); ++i) {
    if (tiles_[i].id != static_cast<int>(i))
      throw std::invalid_argument("TileQueue: tile ids must be 0, 1, 2, ... in order");
    queue_.push_back(static_cast<int>(i));
  }
}

std::optional<Tile> TileQueue::next(int rank) {
  while (!queue_.empty()) {
    const int id = queue_.front();
    queue_.pop_front();
    if (done_[static_cast<size_t>(id)]) continue;  // came back from a rank thought lost
    owner_[static_cast<size_t>(id)] = rank;
    return tiles_[static_cast<size_t>(id)];
  }
  return std::nullopt;
}

bool TileQueue::finish(int rank, int id) {
  if (id < 0 || id >= total()) throw std::out_of_range("TileQueue: no tile " + std::to_string(id));
  const size_t i = static_cast<size_t>(id);
  if (owner_[i] == rank) owner_[i] = -1;
  if (done_[i]) return false;
  done_[i] = true;
  ++done_count_;
  return true;
}

int TileQueue::requeue(int rank) {
  int n = 0;
  // Back to the front, in their order: the image fills in from the top as before.
  for (int id = total() - 1; id >= 0; --id) {
    const size_t i = static_cast<size_t>(id);
    if (owner_[i] != rank) continue;
    owner_[i] = -1;
    if (done_[i]) continue;
    queue_.push_front(id);
    ++n;
  }
  return n;
}

std::vector<int> TileQueue::in_flight(int rank) const {
  std::vector<int> ids;
  for (int id = 0; id < total(); ++id)
    if (owner_[static_cast<size_t>(id)] == rank) ids.push_back(id);
  return ids;
}

}  // namespace rt::distributed
