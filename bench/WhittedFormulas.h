// The Whitted shading formulas on the host, in float32, for rill-bench-trace's plain Embree
// renderer (embree_whitted.h): the one place that renderer takes them from. They mirror, in
// the same order of operations, the DSL code of Rill's Whitted megakernel:
//   raytracer/rill/rt/kernel/Shading.cpp   the surface record, the self-intersection offset,
//                                          a point light's shadow ray, eq. 5.1 and the next ray
//   raytracer/rill/rt/shaders/Phong.cpp    Phong's local light (ambient, Lambert, highlight)
//   raytracer/rill/rt/shaders/Mirror.cpp   the mirror's scatter
//   raytracer/rill/rt/shaders/Glass.cpp    refraction with Schlick's Fresnel term, TIR
// and dsl/include/rill/Math.h's dot, length, normalize and reflect. They are copies, not the
// kernel's own code (sharing it as templates would change the kernels' generated source), so
// CTest bench.trace.whitted_smoke renders with both and fails when the images stop agreeing:
// a formula changed on one side only cannot go unnoticed.
#pragma once

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace bench::whitted {

constexpr float kMinWeight = 1.0e-3f;  // rt::kMinWeight: lighter secondary rays are not traced
constexpr float kBig = 3.0e38f;        // rt::kBig: a ray without end

// The DSL's order: (x*x + y*y) + z*z.
inline float dot(const glm::vec3& a, const glm::vec3& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
inline float length(const glm::vec3& v) {
  return std::sqrt(dot(v, v));
}
inline glm::vec3 normalize(const glm::vec3& v) {
  return v / length(v);
}
// i - (2 dot(n, i)) n, as in GLSL.
inline glm::vec3 reflect(const glm::vec3& i, const glm::vec3& n) {
  return i - (2.0f * dot(n, i)) * n;
}

// The self-intersection offset (Shading::offset_origin): the scaled one moves each coordinate
// 8 ulps per unit of the normal (Wachter & Binder), or eps where the coordinate is within
// 1/32 of zero; the epsilon one moves p by eps along n.
inline float add_ulps(float p, int32_t ulps) {
  int32_t bits;
  std::memcpy(&bits, &p, sizeof bits);
  // As the kernel's integer add: two's complement wrap-around (done unsigned, defined).
  bits = static_cast<int32_t>(static_cast<uint32_t>(bits) + static_cast<uint32_t>(ulps));
  float out;
  std::memcpy(&out, &bits, sizeof out);
  return out;
}
inline glm::vec3 offset_origin(const glm::vec3& p, const glm::vec3& n, float eps, bool scaled) {
  if (!scaled) return p + n * eps;
  constexpr float kOrigin = 1.0f / 32.0f, kIntScale = 8.0f;
  glm::vec3 out;
  for (int k = 0; k < 3; ++k) {
    const auto of = static_cast<int32_t>(kIntScale * n[k]);
    out[k] = std::fabs(p[k]) < kOrigin ? p[k] + n[k] * eps : add_ulps(p[k], p[k] < 0.0f ? -of : of);
  }
  return out;
}

// Shading::set_eps: 2e-5 of the scene's diagonal, at least 1e-6 of its farthest corner.
inline float scene_eps(bool any, const glm::vec3& lo, const glm::vec3& hi) {
  float e = 1e-4f;
  if (any) {
    const double diag = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
    const double mag = std::max(glm::length(glm::dvec3(lo)), glm::length(glm::dvec3(hi)));
    e = static_cast<float>(std::max(2e-5 * diag, 1e-6 * mag));
    if (!(e > 0)) e = 1e-4f;
  }
  return e;
}

// The surface record (rt::Surface) of the hit of a ray of direction rd.
struct Surface {
  glm::vec3 P, ns, nf, ngf, V;
  bool entering;
  int32_t material;
};

// Shading::surface: P from the barycentrics (scaled offset) or along the ray; the shading
// normal interpolated where the scene has vertex normals (n0..n2 null otherwise).
inline Surface surface(const glm::vec3& ro, const glm::vec3& rd, float t, float u, float v,
                       const glm::vec3& v0, const glm::vec3& e1, const glm::vec3& e2, glm::vec3 ng,
                       const glm::vec3* n012, int32_t material, bool scaled) {
  const glm::vec3 P = scaled ? v0 + u * e1 + v * e2 : ro + t * rd;
  glm::vec3 ns = ng;
  if (n012) {
    const float w = 1.0f - u - v;
    const glm::vec3 nn = n012[0] * w + n012[1] * u + n012[2] * v;
    const float nl = length(nn);
    ns = nl > 0.0f ? nn / nl : ng;
    if (dot(ng, ns) < 0.0f) ng = -ng;
  }
  const bool entering = dot(ng, rd) < 0.0f;
  return Surface{P, ns, entering ? ns : -ns, entering ? ng : -ng, -rd, entering, material};
}

// A point light's shadow ray (Shading::shadow_ray): from the offset origin towards the
// light, stopping eps short of it; inactive when the light is behind the surface.
struct ShadowRay {
  glm::vec3 o, d;
  float tmax;
  bool active;
};
inline ShadowRay shadow_ray(const Surface& s, const glm::vec3& light, float eps, bool scaled) {
  const glm::vec3 so = offset_origin(s.P, s.ngf, eps, scaled);
  const glm::vec3 L = light - so;
  const float dist = length(L);
  const glm::vec3 rd = L / dist;
  return ShadowRay{so, rd, dist - eps, dist > 0.0f && dot(s.nf, rd) > 0.0f};
}

// A Phong material's parameters (phong and glass; the mirror has only reflect).
struct Phong {
  glm::vec3 diffuse{0.8f}, specular{0.0f};
  float shininess = 32.0f;
};

// phong_emitted: the ambient term.
inline glm::vec3 phong_emitted(const Phong& m, float ambient) {
  return ambient * m.diffuse;
}
// phong_reflected: Lambert plus the highlight (none for the headlight), times the light's
// colour. specular: some material of the scene has a highlight (the kernel has its code).
inline glm::vec3 phong_reflected(const Surface& s, const Phong& m, const glm::vec3& L,
                                 const glm::vec3& color, bool headlight, bool specular) {
  const float ndl = dot(s.nf, L);
  glm::vec3 c = m.diffuse * std::max(ndl, 0.0f);
  if (!headlight && specular) {
    const glm::vec3 R = reflect(-L, s.nf);
    const float rv = std::max(dot(R, s.V), 0.0f);
    // pow only where its term can change the colour (pow(0, n) is 0 for n > 0); the
    // kernel leaves it out where it cannot change the bits (shaders/Phong.cpp).
    if (ndl > 0.0f && m.specular != glm::vec3(0.0f) && (rv > 0.0f || m.shininess == 0.0f))
      c = c + m.specular * std::pow(rv, m.shininess);
  }
  return c * color;
}

// What a shader's scatter gives (rt::Scatter).
struct Scatter {
  float local_weight = 0.0f, reflect_weight = 0.0f;
  glm::vec3 reflect_dir{0.0f};
  float transmit_weight = 0.0f;
  glm::vec3 transmit_dir{0.0f};
};

// mirror_scatter (phong and mirror): 1 - r of the weight sees the local light, r goes on.
inline Scatter mirror_scatter(const Surface& s, float weight, float r) {
  Scatter out;
  out.local_weight = weight * (1.0f - r);
  out.reflect_weight = weight * r;
  out.reflect_dir = reflect(-s.V, s.nf);
  return out;
}

// The glass shader's scatter: the refracted direction and Schlick's Fresnel term (1 under
// total internal reflection) split what reflect and transmit leave.
inline Scatter glass_scatter(const Surface& su, float weight, float refl, float trans, float ior) {
  Scatter out;
  out.local_weight = weight * (1.0f - refl - trans);
  const glm::vec3 inc = -su.V;
  out.reflect_dir = reflect(inc, su.nf);
  const float eta = su.entering ? 1.0f / ior : ior;
  const float cosi = dot(su.V, su.nf);
  const float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
  const bool tir = k < 0.0f;
  const float sk = std::sqrt(std::max(k, 0.0f));
  out.transmit_dir = eta * inc + (eta * cosi - sk) * su.nf;
  float r0 = (ior - 1.0f) / (ior + 1.0f);
  r0 = r0 * r0;
  const float c = 1.0f - (su.entering ? cosi : sk);
  const float c2 = c * c;
  const float fres = tir ? 1.0f : r0 + (1.0f - r0) * (c2 * c2 * c);
  out.reflect_weight = weight * (refl + trans * fres);
  out.transmit_weight = weight * trans * (1.0f - fres);
  return out;
}

}  // namespace bench::whitted
