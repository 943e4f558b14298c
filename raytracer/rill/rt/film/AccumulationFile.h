// A render's running sums on disk (rill-trace render --save / --resume, docs/path-tracing.md):
// an Accumulation (render/RenderResult.h) and what it belongs to, so that a render resumed
// from it is bitwise the render done at once, and one of another scene, size or seed is
// refused.
//
// The format (little-endian): the 8 bytes "RILLACC1", then uint64 scene hash, uint32 seed,
// int32 width, height, samples, then width * height * 3 floats of the sum and as many of the
// carry (row 0 first). "RILLACC2" instead: as many floats of the sum of squares follow (an
// accumulation that kept them, Accumulation::squares). Written whole or not at all
// (scene/OutputFile.h).
#pragma once

#include <cstdint>
#include <string>

#include "rill/rt/render/RenderResult.h"

namespace rt {

// What an accumulation belongs to: a hash of the scene and the render settings that decide
// its pixels (the caller's; rill-trace uses its distributed renderer's scene hash), and the
// random sequence's seed.
struct AccumulationKey {
  uint64_t scene_hash = 0;
  uint32_t seed = 0;
};

// Throws SceneError naming the file when it cannot be written.
void write_accumulation(const std::string& path, const Accumulation& a, const AccumulationKey& key);
// Reads one back and checks it against what the render is: the key and the image size.
// Throws SceneError naming the file and what differs (another scene, seed or size; not a file
// of this kind; cut short).
Accumulation read_accumulation(const std::string& path, const AccumulationKey& key, int width,
                               int height);

}  // namespace rt
