// Textures on the device: every texture the scene holds (scene/Texture.h) in Rill arrays,
// and their lookup as a DSL function, the same bits on every backend under strict.
//
//   bitmap   the texels of all bitmaps in one array of linear RGB; bilinear (or nearest)
//            filtering with texel centres at (i + 0.5) / width, v = 1 at row 0 (the top),
//            and the wrap modes repeat, clamp and mirror, applied to the coordinates
//            before the lookup so that no index goes out of range.
//   checker  squares of color1 and color2, scale squares per unit of uv.
//   noise    value noise of the hit point (scale lattice cells per unit), color1 to color2:
//            smoothly interpolated values from a permutation table (Perlin 1985), so no
//            integer hashing is needed on GLSL.
//   marble   veins along x: a sine of x * scale disturbed by four octaves of turbulence.
//   wood     rings around the y axis, disturbed by noise.
// Procedural textures are solid textures of the hit point P except checker (uv).
#pragma once

#include <rill/rill.h>

#include <vector>

#include "rill/rt/kernel/Records.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

class TextureTable {
 public:
  // Uploads the scene's textures (none: nothing is uploaded and sample() is never called).
  void upload(const Scene& scene);
  // The colour of texture `tex` (an index into Scene::textures) at uv and point P.
  Float3 sample(const Int& tex, const Float2& uv, const Float3& P) const;
  bool empty() const { return kinds_.empty(); }

 private:
  Float3 bitmap(const Int& first, const Int& width, const Int& height, const Float& flags,
                const Float2& uv) const;
  Float3 texel(const Int& first, const Int& width, const Int& x, const Int& y) const;
  Int perm(const Int& i) const;
  Float noise(const Float3& p) const;
  Float turbulence(const Float3& p) const;

  // Two arrays only: on GLSL every array is a texture unit, and a multipass kernel reading
  // the triangles, the materials and its input streams is near Mesa's 32.
  // The texels of every bitmap, then the noise's permutation table (perm_first_ on: 512
  // entries in x, a permutation of 0..255 twice).
  rill::Array<Float3> texels_{1, "tex_texels"};
  // Per texture three entries: (kind, first texel, width, height) (integers, exact in
  // float below 2^24), (color1, scale), (color2, wrap mode + 4 * bilinear).
  rill::Array<Float4> params_{1, "tex_params"};
  int perm_first_ = 0;
  std::vector<int> kinds_;  // host: the kinds present (code only for them)
  bool has_kind(int k) const;
};

}  // namespace rt
