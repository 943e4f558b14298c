// The plain Embree Whitted renderer (embree_whitted.h).
#ifdef RILL_BENCH_HAVE_EMBREE

#include "embree_whitted.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "rill/rt/film/Srgb8.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/shaders/Registry.h"

namespace bench {

namespace {

constexpr int kTile = 16;  // tiles of 16 x 16 pixels, 4 a task: 1024 pixels

// to_srgb8's byte (scene/Image.h) from its thresholds (film/Srgb8.h): the count of them at or
// below v, as the device's encoder counts.
unsigned char srgb8(float v) {
  if (!(v > 0.0f)) return 0;
  const std::array<float, 255>& t = rt::srgb8_thresholds();
  return static_cast<unsigned char>(std::upper_bound(t.begin(), t.end(), v) - t.begin());
}

void refuse(const rt::Scene& s, const std::string& why) {
  throw std::invalid_argument("the Embree Whitted renderer: scene '" + s.name + "': " + why);
}

}  // namespace

struct EmbreeWhitted::Counts {
  int64_t camera = 0, shadow = 0, secondary = 0;
};

EmbreeWhitted::EmbreeWhitted(const rt::Scene& scene, const EmbreeScene& embree,
                             const rt::Features& F, const rt::TracerOptions& K, int max_depth)
    : scene_(scene),
      embree_(embree),
      F_(F),
      scaled_(K.offset == rt::SelfIntersection::Scaled),
      max_depth_(max_depth) {
  if (scene.options.integrator != rt::Integrator::Whitted) refuse(scene, "not a Whitted scene");
  if (F.area_lights) refuse(scene, "emitting materials (area lights)");
  if (F.light_shapes) refuse(scene, "spot or directional lights, or light falloff");
  if (F.vertex_colors) refuse(scene, "vertex colours");
  if (F.texcoords) refuse(scene, "textures");
  if (F.dynamic) refuse(scene, "animated objects");
  if (F.camera != rt::CameraKind::Pinhole) refuse(scene, "a camera other than the pinhole");
  for (const rt::Material& m : scene.materials) {
    const rt::SurfaceShader& sh = rt::material_shader(m);
    const rt::MaterialParams p(m, sh.params);
    Mat out;
    if (sh.name == "phong" || sh.name == "glass") {
      out.kind = sh.name == "phong" ? Kind::Phong : Kind::Glass;
      for (const char* c : {"diffuse", "specular"})
        if (p.get(c).kind == rt::ParamValue::Kind::Texture)
          refuse(scene, "material '" + m.name + "': a texture");
      out.phong.diffuse = p.get("diffuse").color;
      out.phong.specular = p.get("specular").color;
      out.phong.shininess = p.number("shininess");
      out.reflect = p.number("reflect");
      if (out.kind == Kind::Glass) {
        out.transmit = p.number("transmit");
        out.ior = p.number("ior");
      }
    } else if (sh.name == "mirror") {
      out.kind = Kind::Mirror;
      out.reflect = p.number("reflect");
    } else {
      refuse(scene,
             "material '" + m.name + "': shader '" + sh.name + "' (only phong, mirror and glass)");
    }
    mats_.push_back(out);
  }
  glm::vec3 lo, hi;
  const bool any = rt::scene_bounds(scene, lo, hi);
  eps_ = whitted::scene_eps(any, lo, hi);
  // The kernel's triangle arrays (kernel/Triangles.cpp: the unit normal in double).
  const size_t n = scene.triangle_count();
  tris_.resize(n);
  if (F.vertex_normals) normals_.resize(3 * n);
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3* p = &scene.positions[3 * t];
    Tri& tr = tris_[t];
    tr.v0 = p[0];
    tr.e1 = p[1] - p[0];
    tr.e2 = p[2] - p[0];
    const glm::dvec3 c = glm::cross(glm::dvec3(tr.e1), glm::dvec3(tr.e2));
    const double l = glm::length(c);
    tr.ng = (std::isfinite(l) && l > 0) ? glm::vec3(c / l) : glm::vec3(0.0f, 1.0f, 0.0f);
    tr.material = scene.material[t];
    if (F.vertex_normals)
      for (size_t k = 0; k < 3; ++k)
        normals_[3 * t + k] = scene.normals.empty() ? tr.ng : scene.normals[3 * t + k];
  }
}

glm::vec3 EmbreeWhitted::local_light(const whitted::Surface& s, const Mat& m, Counts& n) const {
  const bool phong_light = m.kind != Kind::Mirror;  // the mirror has no local light
  glm::vec3 local =
      phong_light ? whitted::phong_emitted(m.phong, scene_.options.ambient) : glm::vec3(0.0f);
  if (!F_.lights) {  // the headlight at the eye
    if (phong_light)
      local += whitted::phong_reflected(s, m.phong, s.V, glm::vec3(1.0f), true, F_.specular);
    return local;
  }
  if (!F_.shadows) {  // Shading::unshadowed_light: the lights' sum, then added
    glm::vec3 sum(0.0f);
    for (const rt::Light& light : scene_.lights)
      if (phong_light)
        sum += whitted::phong_reflected(s, m.phong, whitted::normalize(light.position - s.P),
                                        light.color, false, F_.specular);
    return local + sum;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (const rt::Light& light : scene_.lights) {
    const whitted::ShadowRay sr = whitted::shadow_ray(s, light.position, eps_, scaled_);
    if (!sr.active) continue;
    RTCRay ray;
    ray.org_x = sr.o.x;
    ray.org_y = sr.o.y;
    ray.org_z = sr.o.z;
    ray.dir_x = sr.d.x;
    ray.dir_y = sr.d.y;
    ray.dir_z = sr.d.z;
    ray.tnear = 0.0f;
    ray.tfar = sr.tmax;
    ray.time = 0.0f;
    ray.mask = 0xffffffffu;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(embree_.handle(), &ctx, &ray);
    ++n.shadow;
    // Embree sets tfar to -inf where something blocks (a ray of tmax < 0, a light within eps
    // of the surface, is skipped and keeps its tfar: not blocked, as in the kernel).
    if (ray.tfar == -std::numeric_limits<float>::infinity()) continue;
    // Not blocked: the light's share (Shading::light's direction from P).
    if (phong_light) {
      const glm::vec3 L = whitted::normalize(light.position - s.P);
      local += whitted::phong_reflected(s, m.phong, L, light.color, false, F_.specular);
    }
  }
  return local;
}

whitted::Scatter EmbreeWhitted::scatter(const whitted::Surface& s, const Mat& m,
                                        float weight) const {
  if (m.kind == Kind::Glass) return whitted::glass_scatter(s, weight, m.reflect, m.transmit, m.ior);
  return whitted::mirror_scatter(s, weight, m.reflect);
}

// Megakernel::path_segment, next_ray and pop_or_finish for one pixel's ray tree.
glm::vec3 EmbreeWhitted::trace_pixel(const rt::CameraFrame& cam, int i, int j, Counts& n) const {
  struct Pending {
    glm::vec3 o, d;
    float weight;
    int depth;
  };
  Pending stack[rt::kRayStack];
  int sp = 0;
  glm::vec3 o = cam.eye, d = rt::camera_ray(cam, i, j);
  glm::vec3 color(0.0f);
  float weight = 1.0f;
  int depth = 0;
  bool camera = true;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  for (;;) {
    ++(camera ? n.camera : n.secondary);
    camera = false;
    RTCRayHit rh;
    EmbreeScene::set_ray(rh, o, d, 0);
    rh.ray.tfar = whitted::kBig;
    rtcIntersect1(embree_.handle(), &ctx, &rh);
    int32_t prim = -1;
    float t = 0;
    embree_.answer(rh.hit.geomID, rh.hit.primID, rh.ray.tfar, prim, t);
    bool go = false;
    if (prim < 0) {
      color += weight * scene_.background;
    } else {
      const Tri& tr = tris_[static_cast<size_t>(prim)];
      const whitted::Surface s =
          whitted::surface(o, d, t, rh.hit.u, rh.hit.v, tr.v0, tr.e1, tr.e2, tr.ng,
                           F_.vertex_normals ? &normals_[3 * static_cast<size_t>(prim)] : nullptr,
                           tr.material, scaled_);
      const Mat& m = mats_[static_cast<size_t>(tr.material)];
      const glm::vec3 local = local_light(s, m, n);
      const whitted::Scatter sc = scatter(s, m, weight);
      color = color + sc.local_weight * local;  // eq. 5.1
      if (F_.reflection && depth < max_depth_) {
        const float wr = sc.reflect_weight, wt = F_.refraction ? sc.transmit_weight : 0.0f;
        const bool go_r = wr > whitted::kMinWeight, go_t = wt > whitted::kMinWeight;
        ++depth;
        if (F_.stack > 0 && go_r && go_t && sp < F_.stack)  // the reflection waits
          stack[sp++] = {whitted::offset_origin(s.P, s.ngf, eps_, scaled_), sc.reflect_dir, wr,
                         depth};
        if (go_t) {
          o = whitted::offset_origin(s.P, -s.ngf, eps_, scaled_);
          d = sc.transmit_dir;
          weight = wt;
          go = true;
        } else if (go_r) {
          o = whitted::offset_origin(s.P, s.ngf, eps_, scaled_);
          d = sc.reflect_dir;
          weight = wr;
          go = true;
        }
      }
    }
    if (go) continue;
    if (sp == 0) break;
    const Pending& p = stack[--sp];
    o = p.o;
    d = p.d;
    weight = p.weight;
    depth = p.depth;
  }
  return color;
}

void EmbreeWhitted::render(int width, int height, WhittedImage& image) const {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  image.width = width;
  image.height = height;
  image.color.resize(pixels);
  image.rgb8.resize(3 * pixels);
  const rt::CameraFrame cam = rt::camera_frame(scene_.camera, width, height);
  const int across = (width + kTile - 1) / kTile, down = (height + kTile - 1) / kTile;
  std::atomic<int64_t> camera{0}, shadow{0}, secondary{0};
  tbb::parallel_for(
      tbb::blocked_range<int>(0, across * down, 4), [&](const tbb::blocked_range<int>& r) {
        Counts n;
        for (int tile = r.begin(); tile < r.end(); ++tile) {
          const int x0 = tile % across * kTile, y0 = tile / across * kTile;
          for (int y = y0; y < std::min(y0 + kTile, height); ++y)
            for (int x = x0; x < std::min(x0 + kTile, width); ++x) {
              const size_t p =
                  static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
              const glm::vec3 c = trace_pixel(cam, x, y, n);
              image.color[p] = c;
              for (int k = 0; k < 3; ++k) image.rgb8[3 * p + static_cast<size_t>(k)] = srgb8(c[k]);
            }
        }
        camera += n.camera;
        shadow += n.shadow;
        secondary += n.secondary;
      });
  image.rays = {camera.load(), shadow.load(), secondary.load()};
}

}  // namespace bench

#endif  // RILL_BENCH_HAVE_EMBREE
