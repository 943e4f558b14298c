// libFuzzer target: glTF 2.0 files (assimp's glTF 2.0 reader, Rill's node walk, materials and
// textures), then the grid, as `rill-trace render FILE.gltf` (or .glb) loads one.
//
// Input: a .glb when it starts with the magic "glTF", else a .gltf; written to a scratch
// folder as m.glb or m.gltf, beside a 2x2 PNG t.png that images may name. Seeds: corpus/gltf
// (a .gltf with its buffer as a data URI, a .glb, materials with textures).
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "rill/rt/load/SceneFile.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const rill::fuzz::ScratchDir dir;
  const bool binary = size >= 4 && std::string(reinterpret_cast<const char*>(data), 4) == "glTF";
  const std::string name = binary ? "m.glb" : "m.gltf";
  dir.write(name, reinterpret_cast<const char*>(data), size);
  try {
    rt::Scene s = rt::load_scene(dir.file(name));
    rill::fuzz::build_up_to_grid(s);
  } catch (const rt::SceneError&) {
    // A clean error: what the loader should give for bad input.
  }
  return 0;
}
