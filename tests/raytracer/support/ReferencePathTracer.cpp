// The reference path tracer (ReferencePathTracer.h): double precision, brute force.
#include "ReferencePathTracer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace rt::testing {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Barycentric slack of the hit test: a ray through the shared edge of two triangles hits at
// least one of them despite rounding (both is harmless: the closest is kept).
constexpr double kEdgeSlack = 1e-12;

// SplitMix64 (Steele, Lea and Flood 2014): the next 64 random bits.
uint64_t next_bits(uint64_t& state) {
  uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
// Uniform in [0, 1): the top 53 bits.
double next_unit(uint64_t& state) {
  return double(next_bits(state) >> 11) * 0x1p-53;
}

// Pixel `index`'s own sequence: the seed and the index mixed, so that neighbouring pixels and
// seeds start far apart.
uint64_t pixel_state(uint64_t seed, uint64_t index) {
  uint64_t s = seed;
  uint64_t mixed = next_bits(s) ^ (index * 0xD1B54A32D192ED03ull);
  return next_bits(mixed);
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// A cosine-weighted direction about the unit normal n (pdf cos / pi), in the frame of Duff et
// al., "Building an Orthonormal Basis, Revisited" (2017).
glm::dvec3 cosine_direction(const glm::dvec3& n, uint64_t& state) {
  const double u1 = next_unit(state), u2 = next_unit(state);
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  const double lx = r * std::cos(phi), ly = r * std::sin(phi), lz = std::sqrt(1.0 - u1);
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 bt(b, sign + n.y * n.y * a, -n.y);
  return glm::normalize(lx * t + ly * bt + lz * n);
}

}  // namespace

glm::dvec3 emission_of(const rt::Material& m) {
  return glm::dvec3(m.emission);
}

bool two_sided_of(const rt::Material& m) {
  return m.two_sided;
}

void set_emission(rt::Material& m, const glm::vec3& emission, bool two_sided) {
  m.emission = emission;
  m.two_sided = two_sided;
}

ReferencePathTracer::ReferencePathTracer(const rt::Scene& scene)
    : background_(scene.background),
      max_depth_(scene.options.max_depth),
      width_(scene.width),
      height_(scene.height) {
  if (max_depth_ < 0) throw std::invalid_argument("reference path tracer: max_depth < 0");
  if (!scene.normals.empty())
    throw std::invalid_argument("reference path tracer: vertex normals are not implemented");
  for (const rt::Material& m : scene.materials) {
    if (m.shader != "diffuse")
      throw std::invalid_argument("reference path tracer: material '" + m.name + "' has shader '" +
                                  m.shader + "'; only 'diffuse' is implemented");
    Surface s{glm::dvec3(0.8), emission_of(m), two_sided_of(m)};
    auto it = m.params.find("diffuse");
    if (it != m.params.end()) {
      if (it->second.kind != rt::ParamValue::Kind::Color)
        throw std::invalid_argument("reference path tracer: material '" + m.name +
                                    "': 'diffuse' must be a colour");
      s.albedo = glm::dvec3(it->second.color);
    }
    surfaces_.push_back(s);
  }
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (size_t i = 0; i < scene.triangle_count(); ++i) {
    const glm::dvec3 a(scene.positions[3 * i]), b(scene.positions[3 * i + 1]),
        c(scene.positions[3 * i + 2]);
    const glm::dvec3 e1 = b - a, e2 = c - a, n = glm::cross(e1, e2);
    const double len = glm::length(n);
    if (!finite(a) || !finite(b) || !finite(c) || !(len > 0.0) || !std::isfinite(len)) continue;
    const int mat = scene.material[i];
    if (mat < 0 || size_t(mat) >= surfaces_.size())
      throw std::invalid_argument("reference path tracer: triangle " + std::to_string(i) +
                                  " has no material");
    triangles_.push_back({a, e1, e2, n / len, mat});
    lo = glm::min(lo, glm::min(a, glm::min(b, c)));
    hi = glm::max(hi, glm::max(a, glm::max(b, c)));
  }
  offset_ = triangles_.empty() ? 0.0 : 1e-7 * glm::length(hi - lo);

  const rt::Camera& cam = scene.camera;
  eye_ = glm::dvec3(cam.eye);
  forward_ = glm::normalize(glm::dvec3(cam.look_at) - eye_);
  right_ = glm::normalize(glm::cross(forward_, glm::dvec3(cam.up)));
  true_up_ = glm::cross(right_, forward_);
  tan_half_fov_ = std::tan(double(cam.fov_y) * 0.5 * kPi / 180.0);
}

int ReferencePathTracer::closest_hit(const glm::dvec3& origin, const glm::dvec3& d, int skip,
                                     double& t) const {
  int best = -1;
  t = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < triangles_.size(); ++i) {
    if (int(i) == skip) continue;
    const Triangle& tri = triangles_[i];
    // Moller-Trumbore.
    const glm::dvec3 p = glm::cross(d, tri.e2);
    const double det = glm::dot(tri.e1, p);
    if (det == 0.0) continue;
    const double inv = 1.0 / det;
    const glm::dvec3 s = origin - tri.a;
    const double u = glm::dot(s, p) * inv;
    if (u < -kEdgeSlack || u > 1.0 + kEdgeSlack) continue;
    const glm::dvec3 q = glm::cross(s, tri.e1);
    const double v = glm::dot(d, q) * inv;
    if (v < -kEdgeSlack || u + v > 1.0 + kEdgeSlack) continue;
    const double h = glm::dot(tri.e2, q) * inv;
    if (h > 0.0 && h < t) {
      t = h;
      best = int(i);
    }
  }
  return best;
}

glm::dvec3 ReferencePathTracer::radiance(glm::dvec3 origin, glm::dvec3 d, uint64_t& state) const {
  glm::dvec3 sum(0.0), throughput(1.0);
  int last = -1;
  for (int k = 0;; ++k) {
    double t;
    const int hit = closest_hit(origin, d, last, t);
    if (hit < 0) return sum + throughput * background_;
    const Triangle& tri = triangles_[hit];
    const Surface& surf = surfaces_[tri.material];
    const double cos_ng = glm::dot(tri.ng, d);
    if (cos_ng < 0.0 || surf.two_sided) sum += throughput * surf.emission;
    if (k == max_depth_) return sum;
    throughput *= surf.albedo;
    // Nothing more can arrive; stopping here changes no pixel's expectation or other pixels.
    if (throughput == glm::dvec3(0.0)) return sum;
    const glm::dvec3 n = cos_ng < 0.0 ? tri.ng : -tri.ng;  // the side the ray came from
    origin = origin + t * d + offset_ * n;
    d = cosine_direction(n, state);
    last = hit;
  }
}

glm::dvec3 ReferencePathTracer::path(int width, int height, int x, int y, double ox, double oy,
                                     uint64_t& state) const {
  const double aspect = double(width) / double(height);
  const double sx = (((x + ox) / width) * 2.0 - 1.0) * tan_half_fov_ * aspect;
  const double sy = (1.0 - ((y + oy) / height) * 2.0) * tan_half_fov_;
  const glm::dvec3 d = glm::normalize(forward_ + sx * right_ + sy * true_up_);
  return radiance(eye_, d, state);
}

ReferenceImage ReferencePathTracer::render(const ReferenceOptions& options) const {
  ReferenceImage img;
  img.width = options.width > 0 ? options.width : width_;
  img.height = options.height > 0 ? options.height : height_;
  img.paths_per_pixel = options.paths_per_pixel;
  if (img.width <= 0 || img.height <= 0)
    throw std::invalid_argument("reference path tracer: image size must be positive");
  if (img.paths_per_pixel < 2)
    throw std::invalid_argument("reference path tracer: at least 2 paths per pixel");
  const size_t pixels = size_t(img.width) * size_t(img.height);
  img.mean.assign(pixels, glm::dvec3(0.0));
  img.variance.assign(pixels, glm::dvec3(0.0));

  std::atomic<int> next_row{0};
  auto work = [&] {
    for (int y; (y = next_row++) < img.height;)
      for (int x = 0; x < img.width; ++x) {
        const size_t index = size_t(y) * size_t(img.width) + size_t(x);
        uint64_t state = pixel_state(options.seed, index);
        // Welford's running mean and sum of squared deviations.
        glm::dvec3 mean(0.0), m2(0.0);
        for (int i = 0; i < img.paths_per_pixel; ++i) {
          const double ox = next_unit(state), oy = next_unit(state);
          const glm::dvec3 l = path(img.width, img.height, x, y, ox, oy, state);
          const glm::dvec3 delta = l - mean;
          mean += delta / double(i + 1);
          m2 += delta * (l - mean);
        }
        const double n = img.paths_per_pixel;
        img.mean[index] = mean;
        img.variance[index] = m2 / (n - 1.0) / n;
      }
  };
  int threads = options.threads > 0 ? options.threads : int(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, img.height);
  std::vector<std::thread> pool;
  for (int i = 1; i < threads; ++i) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  return img;
}

rt::Scene path_cornell() {
  // The library's data: its geometry and light are checked against the Cornell box's in the
  // self-test (ReferencePathTracerTest, PathCornell); nothing here runs Rill's integrator.
  return rt::builtin_scene("cornell-path");
}

}  // namespace rt::testing
