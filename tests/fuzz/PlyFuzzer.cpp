// libFuzzer target: PLY files (PlyCheck.h's structure check, then assimp's PLY reader and
// Rill's triangulation and normals), then the grid, as `rill-trace render FILE.ply` loads one.
//
// Input: the PLY file, written to a scratch folder as m.ply. Seeds: corpus/ply (ASCII and
// binary, with and without normals, polygons).
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "rill/rt/load/SceneFile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const rill::fuzz::ScratchDir dir;
  dir.write("m.ply", reinterpret_cast<const char*>(data), size);
  try {
    rt::Scene s = rt::load_scene(dir.file("m.ply"));
    rill::fuzz::build_up_to_grid(s);
  } catch (const rt::SceneError&) {
    // A clean error: what the loader should give for bad input.
  }
  return 0;
}
