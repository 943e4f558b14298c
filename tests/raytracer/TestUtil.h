// Helpers shared by the ray tracer tests: temporary files, backends, small scenes, and an
// independent float32 Moller-Trumbore that rounds exactly like the kernel.
#pragma once

#include <gtest/gtest.h>
#include <rill/rill.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ParamName.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace rt::testing {

// A fresh directory under the system's temporary directory, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> n{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "rill-rt-" + std::to_string(::getpid()) + "-" + std::to_string(n++);
    if (info != nullptr) name += std::string("-") + info->name();
    for (char& c : name)
      if (c == '/') c = '_';
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name, const std::string& content) const {
    std::string p = (path_ / name).string();
    std::ofstream f(p, std::ios::binary);
    f << content;
    return p;
  }
  std::string path(const std::string& name) const { return (path_ / name).string(); }
  std::string dir() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

// A device that takes no bytes (ENOSPC on every write), as /dev/full is: a node of its own in
// dir where the test may make one (root), else /dev/full itself. A writer that removes the
// file it could not write (libpng's did) then removes the test's node, never the system's.
inline std::string full_device(const TempDir& dir) {
  const std::string node = dir.path("full");
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 7)) == 0) return node;
  return "/dev/full";
}

// The message of the SceneError that f throws (fails the test if it throws none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError";
  return {};
}

// A 2 x 1 grid of quads (4 triangles) whose middle vertices rise with `h`; `flip` writes the
// second face's corners in another order (another topology).
inline std::string wave_obj(float h, bool flip = false) {
  std::string s = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nv 1 1 " + std::to_string(h) + "\nv 2 1 0\n";
  s += "f 1 2 5 4\n";
  s += flip ? "f 3 6 5 2\n" : "f 2 3 6 5\n";
  return s;
}

// Skips the test when the backend cannot run here.
inline bool backend_available(const std::string& name, std::string& why) {
  for (rill::Backend* b : rill::backends())
    if (b->name() == name) {
      why = b->unavailable_reason();
      return why.empty();
    }
  why = "not built";
  return false;
}
#define RT_REQUIRE_BACKEND(name)                                             \
  do {                                                                       \
    std::string why_;                                                        \
    if (!::rt::testing::backend_available(name, why_)) GTEST_SKIP() << why_; \
  } while (0)

inline std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (rill::Backend* b : rill::backends()) names.push_back(b->name());
  return names;
}

// Whether the ray o + t d, t >= 0, meets the box [lo, hi] (in double).
inline bool ray_meets_box(glm::dvec3 o, glm::dvec3 d, glm::dvec3 lo, glm::dvec3 hi) {
  double t0 = 0, t1 = HUGE_VAL;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
  return t0 <= t1;
}

// float32 operations in the kernel's order (this file is compiled with -ffp-contract=off).
inline float dotf(const glm::vec3& a, const glm::vec3& b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
inline glm::vec3 crossf(const glm::vec3& a, const glm::vec3& b) {
  return glm::vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

// Moller-Trumbore exactly as the kernel evaluates it, on the triangle data it gets.
inline bool hit_triangle_f(const glm::vec3& o, const glm::vec3& d, const glm::vec3& v0,
                           const glm::vec3& e1, const glm::vec3& e2, float& t) {
  glm::vec3 pv = crossf(d, e2);
  float det = dotf(e1, pv);
  glm::vec3 tv = o - v0;
  glm::vec3 qv = crossf(tv, e1);
  if (det == 0.0f) return false;
  float inv = 1.0f / det;
  float u = dotf(tv, pv) * inv;
  float v = dotf(d, qv) * inv;
  t = dotf(e2, qv) * inv;
  return u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f;
}

// The closest hit by testing every usable triangle (those the grid holds) with
// hit_triangle_f, as the kernel computes each test; ties go to the smaller id, tested first.
// The traversal's oracle (GridTest.cpp, PacketsTest.cpp). No hit: id -1, t infinite.
inline void brute_force_closest(const Scene& s, const glm::vec3& o, const glm::vec3& d, int32_t& id,
                                float& t) {
  id = -1;
  t = INFINITY;
  for (size_t k = 0; k < s.triangle_count(); ++k) {
    const glm::vec3* p = &s.positions[3 * k];
    if (!triangle_usable(p[0], p[1], p[2])) continue;
    float tk;
    if (hit_triangle_f(o, d, p[0], p[1] - p[0], p[2] - p[0], tk) && tk < t) {
      t = tk;
      id = static_cast<int32_t>(k);
    }
  }
}

// Double-precision ray-triangle intersection for references: t, and the smallest
// barycentric coordinate (negative: outside, by how much).
inline bool hit_triangle_d(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& a,
                           const glm::dvec3& b, const glm::dvec3& c, double& t, double& margin) {
  glm::dvec3 e1 = b - a, e2 = c - a;
  glm::dvec3 pv = glm::cross(d, e2);
  double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  glm::dvec3 tv = o - a;
  double u = glm::dot(tv, pv) / det;
  glm::dvec3 qv = glm::cross(tv, e1);
  double v = glm::dot(d, qv) / det;
  t = glm::dot(e2, qv) / det;
  margin = std::min({u, v, 1.0 - u - v});
  return t > 0.0;
}

}  // namespace rt::testing
