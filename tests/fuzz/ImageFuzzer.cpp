// libFuzzer target: the image readers, PNG (bitmap textures, libpng's simplified API) and PFM
// (resumed renders and comparisons). Every input goes to both decoders; each rejects what is
// not its format by the signature or header. Seeds: corpus/image.
#include <rill/rt/scene/Image.h>
#include <rill/rt/scene/Scene.h>
#include <rill/rt/scene/Texture.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    rt::Texture t = rt::decode_png_texture(bytes, "input.png", /*srgb=*/(size & 1) != 0);
    if (t.texels.size() != static_cast<size_t>(t.width) * static_cast<size_t>(t.height))
      __builtin_trap();
  } catch (const rt::SceneError&) {
  }
  try {
    int w = 0, h = 0, channels = 0;
    std::vector<float> px = rt::parse_pfm(bytes, "input.pfm", w, h, channels);
    if (px.size() !=
        static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels))
      __builtin_trap();
  } catch (const std::runtime_error&) {
  }
  return 0;
}
