// libFuzzer target: the JSON scene parser and the whole scene build up to the grid, as
// `rill-trace render scene.json` does (parse_json_scene, validate, grid).
//
// Input: the text of a scene file. Its relative paths are read from a scratch folder that
// holds a small OBJ (tri.obj), its MTL (tri.mtl) and a 2x2 PNG (t.png), so "mesh", "mtllib"
// and bitmap "file" entries can name them. Seeds: corpus/scene_json.
#include <cstddef>
#include <cstdint>
#include <string>

#include "FuzzScene.h"
#include "rill/rt/load/SceneFile.h"

namespace {

const rill::fuzz::ScratchDir& scratch() {
  static const rill::fuzz::ScratchDir dir;
  static const bool mesh = [] {
    const std::string obj =
        "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
        "usemtl red\nf 1/1/1 2/2/1 3/3/1\n";
    const std::string mtl = "newmtl red\nKd 0.8 0.1 0.1\nKs 0.2 0.2 0.2\nNs 20\nmap_Kd t.png\n";
    dir.write("tri.obj", obj.data(), obj.size());
    dir.write("tri.mtl", mtl.data(), mtl.size());
    return true;
  }();
  (void)mesh;
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    rt::Scene s = rt::parse_json_scene(text, scratch().dir(), "fuzz");
    rill::fuzz::build_up_to_grid(s);
  } catch (const rt::SceneError&) {
  }
  return 0;
}
