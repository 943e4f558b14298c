// The lights as the path integrator sees them (docs/path-tracing.md): the point lights and the
// area lights, every usable triangle whose material emits (Material::emission), in one table
// that next-event estimation draws from with probability proportional to power, and the
// emitted radiance at a hit with the density with which light sampling would have chosen it
// (for multiple importance sampling).
//
// Spot and directional lights (kernel/LightShape.h) are point lights with a shape: a spot of
// intensity I on its axis sends I times its cone factor, over r^2; a directional light of
// irradiance E sends E from its fixed direction, with no distance (its shadow ray has no end).
// Both are delta lights, which only light sampling finds.
//
// Power, for the choice only: a point light of intensity I has 4 pi lum(I), a spot
// 2 pi lum(I) (1 - (cos inner + cos outer) / 2) (pbrt's), a directional light of irradiance E
// pi R^2 lum(E) with R the radius of the scene's bounding sphere (pbrt's), a triangle of
// area A and radiance Le has pi A lum(Le) per side it emits from. Under an emission texture
// (Material::emission_texture) Le is the scale times the texture's mean (a bitmap's texels',
// a procedural texture's two colours'): the choice stays unbiased wherever the texture is,
// since the radiance at the point drawn is the texture's there. The table is a cumulative
// distribution in float (cdf[0] = 0, cdf[n] = 1) searched in ceil(log2 n) steps; an entry's
// probability is cdf[i + 1] - cdf[i], the same subtraction wherever it is needed, so light
// sampling and the MIS weights at BSDF-sampled hits use one density.
//
// Whitted's area lights (Features::area_lights, Shading::loop_light) draw from the emitting
// triangles alone: the same powers restricted to them, in a table of their own (light_cdf_area),
// so that bright point lights do not squeeze the triangles' entries into a few floats.
#pragma once

#include <rill/rill.h>

#include "rill/rt/kernel/Features.h"
#include "rill/rt/kernel/LightShape.h"
#include "rill/rt/kernel/Records.h"
#include "rill/rt/kernel/Textures.h"
#include "rill/rt/kernel/Triangles.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

// A point on a light, as next-event estimation drew it from a shading point.
struct LightDraw {
  Float3 wi;        // unit direction from the shading point to the light
  Float dist;       // distance to it
  // The light arriving along -wi: Le, I / dist^2 for a point light (times a spot's cone), E
  // for a directional light.
  Float3 radiance;
  Float pdf;        // over solid angle at the shading point; a point light: its probability
  Bool delta;       // a point, spot or directional light (no other strategy can find it)
};

// A point drawn on the emitting triangles alone (LightSampler::sample_area).
struct AreaPoint {
  Float3 y;        // the point
  Float3 n;        // the unit normal of its emitting (front) side
  Float3 le;       // the material's emitted radiance
  Bool two_sided;  // it emits on both sides
  Float p_area;    // the density over area with which it was drawn: pick / triangle area
};

class LightSampler {
 public:
  // Builds the table from the scene's point lights and emitting usable triangles. Throws
  // SceneError for an emitting material whose triangles (those the scene uses) have no area.
  // smooth_material: per material, whether its shader's BSDF has a smooth lobe (Bsdf::smooth).
  // textures: the scene's, for emission textures (kept by reference; none needed without).
  void upload(const Scene& scene, const Triangles& tris, const Features& F,
              const std::vector<bool>& smooth_material, const TextureTable& textures);
  bool any() const { return count_host_ > 0; }               // host: a light to sample
  bool points() const { return points_host_ > 0; }           // host: point lights
  bool areas() const { return count_host_ > points_host_; }  // host: emitting triangles
  int count() const { return count_host_; }

  // Le towards s.V at a hit (0 from behind a one-sided emitter).
  Float3 emission(const Surface& s) const;
  // Whether the hit's material has a smooth lobe (Bsdf::smooth): light sampling there.
  Bool smooth(const Surface& s) const;
  // The density over solid angle with which light sampling would pick the hit point of prim
  // seen at distance t along the unit direction d (0 for a triangle that is no light).
  Float pdf(const Int& prim, const Float& t, const Float3& d) const;
  // A light drawn with u (u.x the light, u.y and u.z the point on a triangle) from origin o.
  LightDraw sample(const Float3& o, const Float3& u) const;
  // A point on the emitting triangles alone, the triangle drawn by power with u.x (the table
  // restricted to area lights), the point uniformly on it with u.y, u.z. Needs areas().
  AreaPoint sample_area(const Float3& u) const;

 private:
  // The unit normal of the emitting side of triangle t at barycentrics b, as Shading::surface
  // turns it (towards the vertex normals where the scene has them).
  Float3 front_normal(const Int& t, const Float2& b) const;
  Float area(const Int& t) const;
  // The radiance of material `material` (le its Material::emission) at texture coordinates uv
  // and point P: le, times its emission texture's colour there where it has one.
  Float3 radiance(const Int& material, const Float3& le, const Float2& uv, const Float3& P) const;
  // Triangle t's texture coordinates at barycentrics b (as Shading::surface interpolates them).
  Float2 uv_at(const Int& t, const Float2& b) const;
  // The entry of cdf (n entries) with cdf[i] <= u < cdf[i + 1].
  Int find(const rill::Array<Float>& cdf, int n, const Float& u) const;

  const Triangles* tris_ = nullptr;
  const TextureTable* textures_ = nullptr;
  bool textured_ = false;  // host: some emitting material has an emission texture
  Features F_;
  int count_host_ = 0, points_host_ = 0;
  rill::Array<Float> cdf_{1, "light_cdf"};
  rill::Array<Float> area_cdf_{1, "light_cdf_area"};  // the emitting triangles' alone
  rill::Array<Int> tri_{1, "light_tri"};              // entry -> triangle (areas)
  rill::Array<Int> entry_{1, "light_entry"};          // triangle -> entry, or -1
  rill::Array<Float3> point_pos_{1, "plight_pos"}, point_col_{1, "plight_col"};
  bool shaped_ = false;  // host: spot or directional lights (LightShape.h)
  LightShapes shapes_{"plight_shape", "plight_axis"};
  // Per material: Le in xyz, and in w 1 for two-sided plus 2 for a smooth lobe.
  rill::Array<Float4> material_{1, "mat_light"};
  rill::Array<Int> texture_{1, "mat_light_tex"};  // per material: its emission texture, or -1
};

}  // namespace rt
