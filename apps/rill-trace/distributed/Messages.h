// What rank 0 and the workers say to each other: one struct per message, each sent as bytes
// under its own MPI tag.
//
// The protocol, start to end (Farm.cpp):
//   worker -> 0   Hello       after loading: the scene hash, or why loading failed
//   0 -> worker   Abort       a rank failed to load or has another scene: everyone stops
//   0 -> worker   Assign      a tile to render (two ahead, so a worker never waits for one),
//                             with its slice of the running sums in a round (below)
//   worker -> 0   TileDone    a tile's pixels, as the outputs asked for (and its sums)
//   worker -> 0   Failed      rendering threw: its tiles go to the other ranks
//   0 -> worker   Stop        the image is complete (after the last round)
//   both ways     Heartbeat   "still here", every half second while loading or rendering
// Bytes rather than MPI datatypes: the messages hold strings and optional arrays, and every
// rank runs the same rill-trace on the same kind of host. An Assign names the tile's frame
// (--frames); a TileDone needs only the tile's id, which is unique over every frame of a job.
// A progressive render (--time-limit, --save, --resume) runs several jobs, its rounds, between
// the Hellos and the Stop: each Assign then says up to which sample the tile renders, from its
// slice of the sums so far, and the TileDone brings the tile's sums back (docs/distributed.md).
#pragma once

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "distributed/TileQueue.h"
#include "rill/rt/Tracer.h"

namespace rt::distributed {

enum Tag : int { kHello = 1, kAbort, kAssign, kTileDone, kFailed, kStop, kHeartbeat };
const char* tag_name(int tag);

using Bytes = std::vector<char>;

struct Hello {
  bool ok = false;
  uint64_t scene_hash = 0;
  std::string host, backend;
  std::string message;  // why loading failed (ok false)
};

// A tile to render. In a round of a progressive render: up to sample `spp` (0: the scene's
// spp), going on from `resume` (the tile's slice of the image's sums; samples 0: from the
// first sample), with the tile's sums back when `accumulation`.
struct Assign {
  Tile tile;
  int spp = 0;
  bool accumulation = false;
  Accumulation resume;
};

struct TileDone {
  int id = 0;
  double busy_ms = 0;  // rendering it, on the worker
  // The tile's size; rays, and the outputs asked for: colour, 8-bit, depth, prim, normal,
  // and the path integrator's albedo and variance (--albedo, --variance); its samples per
  // pixel, and its running sums in a round (Assign::accumulation).
  RenderResult pixels;
};

// Abort, Failed: a message for the user.
struct Text {
  std::string message;
};

Bytes pack(const Hello& m);
Bytes pack(const Assign& m);
Bytes pack(const TileDone& m);
Bytes pack(const Text& m);
// Each throws std::runtime_error on bytes that are not a whole message of its kind.
void unpack(const Bytes& b, Hello& m);
void unpack(const Bytes& b, Assign& m);
void unpack(const Bytes& b, TileDone& m);
void unpack(const Bytes& b, Text& m);

}  // namespace rt::distributed
