// A tile's part of an image's running sums (rt::Accumulation), and back: rank 0 keeps the
// whole image's sums between the rounds of a progressive render under mpirun
// (docs/distributed.md, "Rounds"), sends each tile its slice with the Assign, and places the
// slice a TileDone brings back. Plain copies of rows: a pixel's floats travel unchanged, so a
// tile resumed from its slice goes on from the very floats a single process would hold.
#pragma once

#include "distributed/TileQueue.h"
#include "rill/rt/render/RenderResult.h"

namespace rt::distributed {

// The tile's pixels of `whole` (the tile inside it), as an accumulation of the tile's size
// with whole's sample count; the squares only if whole has them.
Accumulation slice_of(const Accumulation& whole, const Tile& t);

// Copies the tile's accumulation `part` into `whole` at the tile. whole's squares are made
// (zero) by the first part that has them.
void place_slice(Accumulation& whole, const Tile& t, const Accumulation& part);

}  // namespace rt::distributed
