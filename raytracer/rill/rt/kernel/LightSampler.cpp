// The path integrator's lights (LightSampler.h).
#include "rill/rt/kernel/LightSampler.h"

#include <cmath>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/DeviceArrays.h"
#include "rill/rt/kernel/Sampling.h"

namespace rt {

using namespace rill;

namespace {

double luminance(const glm::vec3& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// A texture's mean colour, for the lights' powers: a bitmap's texels', a procedural one's two
// colours'.
glm::dvec3 mean_colour(const Texture& t) {
  if (t.type != "bitmap") return (glm::dvec3(t.color1) + glm::dvec3(t.color2)) * 0.5;
  glm::dvec3 sum(0.0);
  for (const glm::vec3& texel : t.texels) sum += glm::dvec3(texel);
  return t.texels.empty() ? sum : sum / static_cast<double>(t.texels.size());
}

// The radiance a material's power is computed from: its emission, times its texture's mean.
glm::vec3 mean_emission(const Scene& scene, const Material& m) {
  if (m.emission_texture < 0) return m.emission;
  return glm::vec3(glm::dvec3(m.emission) *
                   mean_colour(scene.textures[static_cast<size_t>(m.emission_texture)]));
}

// A light's power, for the choice of light only (LightSampler.h).
double light_power(const Scene& scene, const Light& l) {
  const double lum = luminance(l.color);
  switch (l.type) {
    case LightType::Spot: {
      const double ci = std::cos(l.inner_deg * (M_PI / 180.0));
      const double co = std::cos(l.outer_deg * (M_PI / 180.0));
      return 2.0 * M_PI * lum * (1.0 - 0.5 * (ci + co));
    }
    case LightType::Directional: {
      glm::vec3 lo, hi;
      const double r =
          scene_bounds(scene, lo, hi) ? 0.5 * glm::length(glm::dvec3(hi) - glm::dvec3(lo)) : 1.0;
      return M_PI * r * r * lum;
    }
    case LightType::Point:
      break;
  }
  return 4.0 * M_PI * lum;
}

}  // namespace

void LightSampler::upload(const Scene& scene, const Triangles& tris, const Features& F,
                          const std::vector<bool>& smooth_material, const TextureTable& textures) {
  tris_ = &tris;
  textures_ = &textures;
  F_ = F;
  textured_ = false;
  std::vector<double> power;
  std::vector<glm::vec3> pos, col;
  for (const Light& l : scene.lights) {
    pos.push_back(l.position);
    col.push_back(l.color);
    power.push_back(light_power(scene, l));
  }
  shaped_ = false;
  for (const Light& l : scene.lights) shaped_ = shaped_ || l.type != LightType::Point;
  points_host_ = static_cast<int>(scene.lights.size());
  std::vector<int32_t> emitting, entry(F.geometry ? scene.triangle_count() : 0, -1);
  std::vector<double> material_area(scene.materials.size(), 0.0);
  if (F.geometry) {
    for (size_t t = 0; t < scene.triangle_count(); ++t) {
      const Material& m = scene.materials[static_cast<size_t>(scene.material[t])];
      const glm::vec3* p = &scene.positions[3 * t];
      if (!m.emits() || !triangle_usable(p[0], p[1], p[2])) continue;
      const double a = 0.5 * glm::length(glm::cross(glm::dvec3(p[1]) - glm::dvec3(p[0]),
                                                    glm::dvec3(p[2]) - glm::dvec3(p[0])));
      material_area[static_cast<size_t>(scene.material[t])] += a;
      if (!(a > 0.0)) continue;
      entry[t] = static_cast<int32_t>(power.size());
      emitting.push_back(static_cast<int32_t>(t));
      power.push_back(M_PI * a * luminance(mean_emission(scene, m)) * (m.two_sided ? 2.0 : 1.0));
      textured_ = textured_ || m.emission_texture >= 0;
    }
    // An emitting material that triangles name, none of which has an area (each degenerate
    // or not finite): a light that cannot shine, surely a mistake in the scene.
    std::vector<bool> named(scene.materials.size(), false);
    for (int32_t m : scene.material) named[static_cast<size_t>(m)] = true;
    for (size_t m = 0; m < scene.materials.size(); ++m)
      if (named[m] && scene.materials[m].emits() && !(material_area[m] > 0.0))
        throw SceneError("material '" + clipped(scene.materials[m].name) +
                         "' emits light, but its triangles have no area");
  }
  count_host_ = static_cast<int>(power.size());
  double total = 0.0;
  for (double p : power) total += p;
  // Lights whose powers are all 0 (black emission textures): chosen uniformly instead.
  if (!(total > 0.0)) {
    for (double& p : power) p = 1.0;
    total = static_cast<double>(power.size());
  }
  std::vector<float> cdf{0.0f};
  double run = 0.0;
  for (size_t i = 0; i < power.size(); ++i) {
    run += power[i];
    cdf.push_back(i + 1 == power.size() ? 1.0f : static_cast<float>(run / total));
  }
  // The area lights' own table, for Whitted's (sample_area): the same powers from the first
  // triangle on.
  std::vector<float> area_cdf{0.0f};
  double area_total = 0.0, area_run = 0.0;
  for (size_t i = static_cast<size_t>(points_host_); i < power.size(); ++i) area_total += power[i];
  if (!(area_total > 0.0))  // every triangle black: chosen uniformly (they give nothing)
    for (size_t i = static_cast<size_t>(points_host_); i < power.size(); ++i)
      area_total += (power[i] = 1.0);
  for (size_t i = static_cast<size_t>(points_host_); i < power.size(); ++i) {
    area_run += power[i];
    area_cdf.push_back(i + 1 == power.size() ? 1.0f : static_cast<float>(area_run / area_total));
  }
  std::vector<glm::vec4> mat;
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const Material& mm = scene.materials[m];
    const bool smooth = m < smooth_material.size() && smooth_material[m];
    mat.emplace_back(mm.emission, (mm.two_sided ? 1.0f : 0.0f) + (smooth ? 2.0f : 0.0f));
  }
  upload_padded(cdf_, cdf);
  upload_padded(area_cdf_, area_cdf);
  upload_padded(tri_, emitting);
  upload_padded(entry_, entry);
  upload_padded(point_pos_, pos);
  upload_padded(point_col_, col);
  upload_padded(material_, mat);
  if (shaped_) shapes_.upload(scene.lights);
  if (textured_) {
    std::vector<int32_t> tex;
    for (const Material& m : scene.materials) tex.push_back(m.emission_texture);
    upload_padded(texture_, tex);
  }
}

Float2 LightSampler::uv_at(const Int& t, const Float2& b) const {
  if (!F_.texcoords) return Float2(0.0f);
  const Float w = 1.0f - b.x() - b.y();
  return tris_->uv[3 * t] * w + tris_->uv[3 * t + 1] * b.x() + tris_->uv[3 * t + 2] * b.y();
}

Float3 LightSampler::radiance(const Int& material, const Float3& le, const Float2& uv,
                              const Float3& P) const {
  if (!textured_) return le;  // (the kernels of scenes without emission textures: unchanged)
  Float3 out = le;
  const Int tex = texture_[material];
  RILL_IF(tex >= 0) {
    out = le * textures_->sample(tex, uv, P);
  }
  RILL_ENDIF;
  return out;
}

Float3 LightSampler::emission(const Surface& s) const {
  const Float4 m = material_[s.material];
  const Float flags = m.w();
  const Bool two_sided = flags == 1.0f || flags == 3.0f;
  return select(s.entering || two_sided,
                radiance(s.material, Float3(m.x(), m.y(), m.z()), s.uv, s.P), Float3(0.0f));
}

Bool LightSampler::smooth(const Surface& s) const {
  return material_[s.material].w() >= 2.0f;
}

Float LightSampler::area(const Int& t) const {
  return 0.5f * length(cross(tris_->e1[t], tris_->e2[t]));
}

Float3 LightSampler::front_normal(const Int& t, const Float2& b) const {
  Float3 ng = tris_->ng[t];
  if (F_.vertex_normals) {  // as Shading::surface: the vertex normals tell the outside
    const Float w = 1.0f - b.x() - b.y();
    const Float3 nn = tris_->n0[t] * w + tris_->n1[t] * b.x() + tris_->n2[t] * b.y();
    ng = select(dot(ng, nn) < 0.0f, -ng, ng);
  }
  return ng;
}

Int LightSampler::find(const rill::Array<Float>& cdf, int count, const Float& u) const {
  // The entry i with cdf[i] <= u < cdf[i + 1]: cdf[lo] <= u < cdf[hi] holds throughout.
  Int lo = 0, hi = count;
  for (int n = count; n > 1; n = (n + 1) / 2) {
    const Int mid = shr_logical(lo + hi, Int(1));
    const Bool below = cdf[mid] <= u;
    lo = select(below, mid, lo);
    hi = select(below, hi, mid);
  }
  return lo;
}

Float LightSampler::pdf(const Int& prim, const Float& t, const Float3& d) const {
  if (!areas()) return Float(0.0f);
  const Int e = entry_[prim];
  const Int ec = max(e, Int(0));
  const Float pick = cdf_[ec + 1] - cdf_[ec];
  const Float cos_l = abs(dot(tris_->ng[prim], d));
  const Float denom = area(prim) * cos_l;
  const Float p = pick * (t * t) / select(denom > 0.0f, denom, Float(1.0f));
  return select(e >= 0 && denom > 0.0f, p, Float(0.0f));
}

LightDraw LightSampler::sample(const Float3& o, const Float3& u) const {
  LightDraw out{Float3(0.0f, 0.0f, 1.0f), Float(0.0f), Float3(0.0f), Float(0.0f), Bool(false)};
  const Int e = find(cdf_, count_host_, u.x());
  const Float pick = cdf_[e + 1] - cdf_[e];
  auto point_light = [&] {
    const Float3 to = point_pos_[e] - o;
    const Float d2 = dot(to, to);
    const Float d = sqrt(d2);
    out.wi = to / select(d > 0.0f, d, Float(1.0f));
    out.dist = d;
    out.radiance = point_col_[e] / select(d2 > 0.0f, d2, Float(1.0f));
    out.pdf = select(d2 > 0.0f, pick, Float(0.0f));
    out.delta = true;
    if (shaped_) {  // a spot's cone; a directional light's fixed direction, without distance
      const Bool directional = shapes_.directional(e);
      out.wi = select(directional, -shapes_.axis[e], out.wi);
      out.dist = select(directional, Float(kBig), out.dist);
      out.radiance = select(directional, point_col_[e], out.radiance) * shapes_.cone(e, out.wi);
      out.pdf = select(directional, pick, out.pdf);
    }
  };
  auto area_light = [&] {
    const Int t = tri_[max(e - points_host_, Int(0))];
    const Float2 b = uniform_triangle(Float2(u.y(), u.z()));
    const Float3 y = tris_->v0[t] + b.x() * tris_->e1[t] + b.y() * tris_->e2[t];
    const Float3 to = y - o;
    const Float d2 = dot(to, to);
    const Float d = sqrt(d2);
    const Float3 wi = to / select(d > 0.0f, d, Float(1.0f));
    const Float3 n = front_normal(t, b);
    const Float cos_l = dot(n, wi);  // < 0: the ray from o meets the front side
    const Float4 m = material_[tris_->material[t]];
    const Bool two_sided = m.w() == 1.0f || m.w() == 3.0f;
    const Bool lit = cos_l < 0.0f || (two_sided && cos_l > 0.0f);
    const Float denom = area(t) * abs(cos_l);
    out.wi = wi;
    out.dist = d;
    out.radiance =
        select(lit, radiance(tris_->material[t], Float3(m.x(), m.y(), m.z()), uv_at(t, b), y),
               Float3(0.0f));
    out.pdf = select(lit && denom > 0.0f && d2 > 0.0f,
                     pick * d2 / select(denom > 0.0f, denom, Float(1.0f)), Float(0.0f));
  };
  if (points() && areas()) {
    RILL_IF(e < points_host_) {
      point_light();
    }
    RILL_ELSE {
      area_light();
    }
    RILL_ENDIF;
  } else if (points()) {
    point_light();
  } else if (areas()) {
    area_light();
  }
  return out;
}

AreaPoint LightSampler::sample_area(const Float3& u) const {
  const Int i = find(area_cdf_, count_host_ - points_host_, u.x());
  const Float pick = area_cdf_[i + 1] - area_cdf_[i];
  const Int t = tri_[i];
  const Float2 b = uniform_triangle(Float2(u.y(), u.z()));
  const Float3 y = tris_->v0[t] + b.x() * tris_->e1[t] + b.y() * tris_->e2[t];
  const Int material = tris_->material[t];
  const Float4 m = material_[material];
  const Float a = area(t);
  return AreaPoint{y, front_normal(t, b),
                   radiance(material, Float3(m.x(), m.y(), m.z()), uv_at(t, b), y),
                   m.w() == 1.0f || m.w() == 3.0f,
                   select(a > 0.0f, pick / select(a > 0.0f, a, Float(1.0f)), Float(0.0f))};
}

}  // namespace rt
