// An independent path tracer in double precision, the ground truth of the tests of Rill's path
// integrator (options.integrator "path"): plain C++, no DSL and nothing of the ray tracer's
// kernels, so that a bug there cannot hide in both. It reads a Scene's data (triangles,
// materials, camera, background, options.max_depth) and computes everything else itself: the
// camera rays from docs/camera.md's formulas, brute-force closest hits (Moller-Trumbore), and
// unidirectional paths with BSDF sampling only (no next-event estimation, no MIS, no Russian
// roulette), so it shares none of the path integrator's light sampling.
//
// The contract it implements:
// - the only shader is "diffuse": Lambertian, f = diffuse / pi ("diffuse" a colour, 0.8 grey
//   where the material leaves it out);
// - a material emits radiance emission_of(m) on the front side of its triangles (where
//   cross(b - a, c - a) points: a ray with dot(ng, d) < 0 sees it), on both where
//   two_sided_of(m);
// - the background is the radiance of a uniform environment, seen by every ray that escapes;
// - a path is the camera ray and up to D = options.max_depth bounces: at vertex k = 0..D it
//   adds throughput * Le towards the previous point; for k < D it samples a cosine-weighted
//   direction on the side the ray came from (throughput *= diffuse, since f cos / pdf is the
//   albedo); an escaping ray adds throughput * background and ends the path. A closed furnace of
//   albedo a and emission Le so gives Le (1 + a + ... + a^D);
// - pixel (x, y) (x right, y down, row 0 at the top) is the mean over its area (a box filter):
//   each path's sub-pixel offset is uniform in [0, 1)^2.
//
// Each pixel has its own random sequence (SplitMix64 seeded from the seed and the pixel's
// index), so an image depends on neither the threads nor the order of the pixels.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt::testing {

// A material's emitted radiance and whether both sides emit (Material::emission, two_sided).
glm::dvec3 emission_of(const rt::Material& m);
bool two_sided_of(const rt::Material& m);
void set_emission(rt::Material& m, const glm::vec3& emission, bool two_sided = false);

struct ReferenceOptions {
  int width = 0, height = 0;  // 0: the scene's
  int paths_per_pixel = 1024;
  uint64_t seed = 0;  // another seed, another independent image of the same expectation
  int threads = 0;    // 0: std::thread::hardware_concurrency()
};

// Per pixel, row by row from the top: the sample mean of its paths' radiance and the
// variance of that mean (the sample variance s^2, with n - 1, over n), per channel.
struct ReferenceImage {
  int width = 0, height = 0;
  int paths_per_pixel = 0;
  std::vector<glm::dvec3> mean;
  std::vector<glm::dvec3> variance;  // of the mean
  const glm::dvec3& mean_at(int x, int y) const { return mean[size_t(y) * size_t(width) + x]; }
  const glm::dvec3& variance_at(int x, int y) const {
    return variance[size_t(y) * size_t(width) + x];
  }
};

class ReferencePathTracer {
 public:
  // Throws std::invalid_argument for what it does not implement: a shader other than
  // "diffuse", a texture bound to "diffuse", vertex normals (Scene::normals not empty), a
  // negative max_depth. Triangles that are not finite or have no area are never hit. The
  // camera is scene.camera (has_camera is not looked at).
  explicit ReferencePathTracer(const rt::Scene& scene);

  // Throws std::invalid_argument for fewer than 2 paths per pixel (no variance) or an empty
  // image.
  ReferenceImage render(const ReferenceOptions& options) const;

  // One path's radiance from the camera ray through pixel (x, y) at sub-pixel offset
  // (ox, oy) in [0, 1)^2, drawing its bounces from `state` (a SplitMix64 state). For tests
  // that want single paths; render() is the mean of these.
  glm::dvec3 path(int width, int height, int x, int y, double ox, double oy, uint64_t& state) const;

 private:
  struct Triangle {
    glm::dvec3 a, e1, e2, ng;  // ng = cross(e1, e2), normalized
    int material;
  };
  struct Surface {
    glm::dvec3 albedo, emission;
    bool two_sided;
  };
  // The closest hit of origin + t d for t > 0 other than triangle `skip`: its index, or -1.
  int closest_hit(const glm::dvec3& origin, const glm::dvec3& d, int skip, double& t) const;
  glm::dvec3 radiance(glm::dvec3 origin, glm::dvec3 d, uint64_t& state) const;

  std::vector<Triangle> triangles_;
  std::vector<Surface> surfaces_;
  glm::dvec3 background_;
  int max_depth_;
  int width_, height_;  // the scene's image size
  double offset_;       // how far new origins move off the surface: 1e-7 of the scene's diagonal
  // The camera (docs/camera.md) in double.
  glm::dvec3 eye_, forward_, right_, true_up_;
  double tan_half_fov_;
};

// The built-in Cornell box (builtin_scene("cornell"): its triangles, camera, image size)
// for the path integrator: its materials "diffuse" with their diffuse colours, no point
// light, a black background, and an area light of emission (17, 12, 4), a 130 x 105 mm quad
// 1 mm below the ceiling facing down (two triangles appended after the box's). max_depth 5.
rt::Scene path_cornell();

}  // namespace rt::testing
