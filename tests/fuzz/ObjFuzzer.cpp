// libFuzzer target: the OBJ + MTL loader (tinyobjloader, Rill's MTL reader, fanning and
// validation), then the grid, as `rill-trace render FILE.obj` loads an OBJ.
//
// Input: an OBJ, optionally followed by a line "#~mtl" and the text of an MTL file. Both are
// written to a scratch folder as m.obj and m.mtl, beside a 2x2 PNG t.png, so `mtllib m.mtl`
// and `map_Kd t.png` in the input find them. Seeds: corpus/obj.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "FuzzScene.h"
#include "rill/rt/load/SceneFile.h"

namespace {

const rill::fuzz::ScratchDir& scratch() {
  static const rill::fuzz::ScratchDir dir;
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  const size_t split = input.find("#~mtl");
  const std::string obj = input.substr(0, split);
  const std::string mtl = split == std::string::npos ? "" : input.substr(split);
  const rill::fuzz::ScratchDir& dir = scratch();
  dir.write("m.obj", obj.data(), obj.size());
  dir.write("m.mtl", mtl.data(), mtl.size());
  try {
    rt::Scene s = rt::load_scene(dir.file("m.obj"));
    rill::fuzz::build_up_to_grid(s);
  } catch (const rt::SceneError&) {
    // A clean error: what the loader should give for bad input.
  }
  return 0;
}
