// Texture lookups on the device (Textures.h).
#include "rill/rt/kernel/Textures.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "rill/rt/kernel/DeviceArrays.h"

namespace rt {

using namespace rill;

namespace {

constexpr int kBitmap = 0, kChecker = 1, kNoise = 2, kMarble = 3, kWood = 4;

int kind_of(const Texture& t) {
  if (t.type == "bitmap") return kBitmap;
  // The procedural kinds are numbered in the order of procedural_texture_types().
  const std::vector<std::string>& types = procedural_texture_types();
  for (size_t i = 0; i < types.size(); ++i)
    if (t.type == types[i]) return static_cast<int>(i) + 1;
  throw SceneError("texture '" + t.name + "': unknown type '" + t.type + "'");
}

// A fixed permutation of 0..255 (a Fisher-Yates shuffle driven by a 32-bit LCG), twice, so
// that perm[perm[x] + y] needs no wrap.
std::vector<int32_t> permutation() {
  std::vector<int32_t> p(256);
  for (int i = 0; i < 256; ++i) p[static_cast<size_t>(i)] = i;
  uint32_t state = 0x2545F491u;
  for (int i = 255; i > 0; --i) {
    state = state * 1664525u + 1013904223u;
    const int j = static_cast<int>((state >> 8) % static_cast<uint32_t>(i + 1));
    std::swap(p[static_cast<size_t>(i)], p[static_cast<size_t>(j)]);
  }
  p.insert(p.end(), p.begin(), p.begin() + 256);
  return p;
}

}  // namespace

void TextureTable::upload(const Scene& scene) {
  kinds_.clear();
  if (scene.textures.empty()) return;
  std::vector<glm::vec3> texels;
  std::vector<glm::vec4> params;
  for (const Texture& t : scene.textures) {
    const int kind = kind_of(t);
    if (std::find(kinds_.begin(), kinds_.end(), kind) == kinds_.end()) kinds_.push_back(kind);
    int first = 0;
    if (kind == kBitmap) {
      if (t.width <= 0 || t.height <= 0 ||
          t.texels.size() != static_cast<size_t>(t.width) * static_cast<size_t>(t.height))
        throw SceneError("texture '" + t.name + "': no texels");
      if (texels.size() + t.texels.size() + 512 > (size_t{1} << 24))
        throw SceneError("texture '" + t.name + "': the scene's bitmaps exceed 2^24 texels");
      first = static_cast<int>(texels.size());
      texels.insert(texels.end(), t.texels.begin(), t.texels.end());
    }
    params.emplace_back(kind, first, t.width, t.height);
    params.emplace_back(t.color1, t.scale);
    params.emplace_back(t.color2,
                        static_cast<float>(static_cast<int>(t.wrap) + (t.bilinear ? 4 : 0)));
  }
  perm_first_ = static_cast<int>(texels.size());
  for (int32_t v : permutation()) texels.emplace_back(static_cast<float>(v), 0.0f, 0.0f);
  upload_padded(texels_, texels);
  upload_padded(params_, params);
}

bool TextureTable::has_kind(int k) const {
  return std::find(kinds_.begin(), kinds_.end(), k) != kinds_.end();
}

Float3 TextureTable::texel(const Int& first, const Int& width, const Int& x, const Int& y) const {
  return texels_[first + y * width + x];
}

Int TextureTable::perm(const Int& i) const {
  return to_int(texels_[perm_first_ + i].x());
}

// The coordinate wrapped into [0, 1] (repeat: [0, 1)); clamp leaves it to the index clamp.
static Float wrap_coord(const Float& u, const Float& mode) {
  Float rep = fract(u);
  Float t = u - 2.0f * floor(u * 0.5f);  // [0, 2)
  Float mir = select(t < 1.0f, t, 2.0f - t);
  return select(mode == 0.0f, rep, select(mode == 2.0f, mir, u));
}

Float3 TextureTable::bitmap(const Int& first, const Int& width, const Int& height,
                            const Float& flags, const Float2& uv) const {
  Bool bilinear = flags >= 4.0f;
  Float mode = select(bilinear, flags - 4.0f, flags);
  Float u = wrap_coord(uv.x(), mode), v = wrap_coord(uv.y(), mode);
  Float fw = to_float(width), fh = to_float(height);
  Int w1 = width - 1, h1 = height - 1;
  // Texel space: x right, y down from the top row (v = 1).
  Float x = u * fw, y = (1.0f - v) * fh;
  Float3 out(0.0f);
  RILL_IF(bilinear) {
    Float xs = x - 0.5f, ys = y - 0.5f;
    Float x0f = floor(xs), y0f = floor(ys);
    Float fx = xs - x0f, fy = ys - y0f;
    Int x0 = to_int(x0f), y0 = to_int(y0f);
    Int x1 = x0 + 1, y1 = y0 + 1;
    // Repeat wraps the neighbours across the edge; clamp and mirror hold the edge texel.
    Bool rep = mode == 0.0f;
    x0 = select(rep && x0 < 0, w1, clamp(x0, Int(0), w1));
    y0 = select(rep && y0 < 0, h1, clamp(y0, Int(0), h1));
    x1 = select(rep && x1 > w1, Int(0), clamp(x1, Int(0), w1));
    y1 = select(rep && y1 > h1, Int(0), clamp(y1, Int(0), h1));
    Float3 top = texel(first, width, x0, y0) * (1.0f - fx) + texel(first, width, x1, y0) * fx;
    Float3 bottom = texel(first, width, x0, y1) * (1.0f - fx) + texel(first, width, x1, y1) * fx;
    out = top * (1.0f - fy) + bottom * fy;
  }
  RILL_ELSE {
    out = texel(first, width, clamp(to_int(floor(x)), Int(0), w1),
                clamp(to_int(floor(y)), Int(0), h1));
  }
  RILL_ENDIF;
  return out;
}

// Value noise in [0, 1]: lattice values from the permutation table, interpolated with the
// smoothstep weights 3t^2 - 2t^3 (only + and *: the same bits everywhere under strict).
Float TextureTable::noise(const Float3& p) const {
  Float3 pf = floor(p);
  Float3 f = p - pf;
  Float3 w = f * f * (3.0f - 2.0f * f);
  Float3 cell = pf - 256.0f * floor(pf * (1.0f / 256.0f));  // 0..255, exact
  Int3 i = to_int(cell);
  Int3 j = select(i == Int3(255), Int3(0), i + 1);
  auto lattice = [&](const Int& x, const Int& y, const Int& z) {
    return to_float(perm(perm(perm(x) + y) + z)) * (1.0f / 255.0f);
  };
  Float c000 = lattice(i.x(), i.y(), i.z()), c100 = lattice(j.x(), i.y(), i.z());
  Float c010 = lattice(i.x(), j.y(), i.z()), c110 = lattice(j.x(), j.y(), i.z());
  Float c001 = lattice(i.x(), i.y(), j.z()), c101 = lattice(j.x(), i.y(), j.z());
  Float c011 = lattice(i.x(), j.y(), j.z()), c111 = lattice(j.x(), j.y(), j.z());
  Float x00 = c000 + (c100 - c000) * w.x(), x10 = c010 + (c110 - c010) * w.x();
  Float x01 = c001 + (c101 - c001) * w.x(), x11 = c011 + (c111 - c011) * w.x();
  Float y0 = x00 + (x10 - x00) * w.y(), y1 = x01 + (x11 - x01) * w.y();
  return y0 + (y1 - y0) * w.z();
}

Float TextureTable::turbulence(const Float3& p) const {
  Float sum = 0.0f;
  float amp = 1.0f, freq = 1.0f;
  for (int octave = 0; octave < 4; ++octave) {  // unrolled on the host
    sum += amp * abs(2.0f * noise(p * freq) - 1.0f);
    amp *= 0.5f;
    freq *= 2.0f;
  }
  return sum;
}

Float3 TextureTable::sample(const Int& tex, const Float2& uv, const Float3& P) const {
  Float4 info = params_[3 * tex];
  Float4 a = params_[3 * tex + 1], b = params_[3 * tex + 2];
  Int kind = to_int(info.x());
  Float3 c1(a.x(), a.y(), a.z()), c2(b.x(), b.y(), b.z());
  Float scale = a.w();
  Float3 out = c1;
  // Only the kinds the scene has are generated.
  if (has_kind(kBitmap)) {
    RILL_IF(kind == kBitmap) {
      out = bitmap(to_int(info.y()), to_int(info.z()), to_int(info.w()), b.w(), uv);
    }
    RILL_ENDIF;
  }
  if (has_kind(kChecker)) {
    RILL_IF(kind == kChecker) {
      Float s = floor(uv.x() * scale) + floor(uv.y() * scale);
      out = select(s - 2.0f * floor(s * 0.5f) != 0.0f, c2, c1);
    }
    RILL_ENDIF;
  }
  if (has_kind(kNoise)) {
    RILL_IF(kind == kNoise) {
      Float n = noise(P * scale);
      out = c1 + (c2 - c1) * n;
    }
    RILL_ENDIF;
  }
  if (has_kind(kMarble)) {
    RILL_IF(kind == kMarble) {
      Float3 p = P * scale;
      Float t = 0.5f + 0.5f * sin(p.x() + 4.0f * turbulence(p));
      out = c1 + (c2 - c1) * t;
    }
    RILL_ENDIF;
  }
  if (has_kind(kWood)) {
    RILL_IF(kind == kWood) {
      Float3 p = P * scale;
      Float r = sqrt(p.x() * p.x() + p.z() * p.z()) + 0.8f * noise(p * 0.5f);
      Float ring = fract(r);
      Float t = ring * ring * (3.0f - 2.0f * ring);
      out = c1 + (c2 - c1) * t;
    }
    RILL_ENDIF;
  }
  return out;
}

}  // namespace rt
