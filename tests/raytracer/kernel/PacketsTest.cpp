// Coherent traversal (kernel/GroupWalk.cpp, docs/raytracer.md "Coherent traversal"): lane
// groups that walk the grid together find exactly the closest hit that each ray finds alone,
// which is the brute-force closest hit over every triangle with the kernel's own float
// arithmetic and tie rule. Checked on every backend with packets on (a group of one where the
// backend has no lanes) and auto (off), on coherent ray sets (camera rays, rays from the
// camera's hits towards the light, axis-parallel packets with signed zeros and denormals) and
// on grids with subgrids and with long empty-space jumps.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

class Packets : public ::testing::TestWithParam<std::string> {};

struct Rays {
  std::string what;
  std::vector<glm::vec3> o, d;
};

// Camera rays (8 neighbours in a row share a lane group), then from each camera hit, moved
// back along the ray by a thousandth of the scene, a ray towards the first light: the
// coherent sets the megakernel traces.
std::vector<Rays> coherent_rays(const Scene& s, int w, int h) {
  Tracer cam(s, build_grid(s, 4));
  const std::vector<glm::vec3> dirs = cam.camera_rays("cpu", s.camera, w, h);
  std::vector<Rays> sets(2);
  sets[0].what = "camera rays";
  sets[0].d = dirs;
  sets[0].o.assign(dirs.size(), s.camera.eye);
  sets[1].what = "rays towards the light";
  glm::vec3 lo, hi;
  scene_bounds(s, lo, hi);
  const float back = 1e-3f * glm::length(hi - lo);
  const glm::vec3 light = s.lights.empty() ? s.camera.eye : s.lights[0].position;
  for (const glm::vec3& d : dirs) {
    int32_t id;
    float t;
    testing::brute_force_closest(s, s.camera.eye, d, id, t);
    if (id < 0) continue;
    const glm::vec3 p = s.camera.eye + (t - back) * d;
    const glm::vec3 l = light - p;
    const float len = std::sqrt(testing::dotf(l, l));
    if (!(len > 0.0f)) continue;
    sets[1].o.push_back(p);
    sets[1].d.push_back(l / len);
  }
  return sets;
}

// Checks every ray's hit against the oracle, bit for bit; returns the hits.
int expect_brute_force(const Scene& s, const Rays& r, const std::vector<int32_t>& prim,
                       const std::vector<float>& dist, const std::string& what) {
  int wrong = 0, hits = 0;
  for (size_t k = 0; k < r.o.size(); ++k) {
    int32_t id;
    float t;
    testing::brute_force_closest(s, r.o[k], r.d[k], id, t);
    hits += id >= 0;
    const bool same =
        prim[k] == id && (id < 0 || std::bit_cast<uint32_t>(dist[k]) == std::bit_cast<uint32_t>(t));
    if (!same && ++wrong <= 5)
      ADD_FAILURE() << what << ", " << r.what << ", ray " << k << ": " << prim[k] << " at "
                    << dist[k] << ", brute force " << id << " at " << t;
  }
  EXPECT_EQ(wrong, 0) << what << ", " << r.what;
  return hits;
}

void check_packets(const std::string& backend, const Scene& s, const Grid& g,
                   const std::vector<Rays>& sets, const std::string& what) {
  // Auto is Off today (PacketsDefaults below checks that).
  for (rt::Packets p : {rt::Packets::Auto, rt::Packets::On}) {
    TracerOptions k;
    k.packets = p;
    Tracer tracer(s, g, k);
    for (const Rays& r : sets) {
      std::vector<int32_t> prim;
      std::vector<float> dist;
      tracer.intersect(backend, r.o, r.d, prim, dist);
      ASSERT_EQ(prim.size(), r.o.size());
      const int hits = expect_brute_force(s, r, prim, dist,
                                          what + ", packets " + packets_name(p) + " on " + backend);
      // Most camera rays hit; of the rays towards the light, some are blocked.
      EXPECT_GT(hits, static_cast<int>(r.o.size()) / (&r == &sets[0] ? 4 : 100))
          << what << ", " << r.what;
    }
  }
}

TEST_P(Packets, CameraAndLightRaysFindTheBruteForceClosestHit) {
  RT_REQUIRE_BACKEND(GetParam());
  const bool cpu = GetParam() == "cpu" || GetParam() == "simd";
  // thesis C only on the CPU backends: its 61,562 triangles make the oracle the slow part.
  for (const char* name : {"thesis-b", "glass", "thesis-c"}) {
    if (!cpu && std::string(name) == "thesis-c") continue;
    Scene s = builtin_scene(name);
    const std::vector<Rays> sets = coherent_rays(s, 40, 24);
    // The grid rill-trace builds for simd (subgrids), and a fine one-level grid whose empty
    // voxels far from any triangle make rays jump.
    check_packets(GetParam(), s, build_grid_for(s, "simd"), sets, std::string(name) + " auto grid");
    if (cpu)
      check_packets(GetParam(), s, build_grid(s, 64, kNoSubgrids), sets,
                    std::string(name) + " 64^3 grid");
  }
}

TEST_P(Packets, AxisParallelPacketsWithSignedZerosAndDenormals) {
  RT_REQUIRE_BACKEND(GetParam());
  // A box on a floor; groups of 8 rays along one axis whose other components are +0, -0 or
  // denormal (flat: they step 0 on those axes, so the group walks together), from origins on
  // the grid's cell planes, and mixed groups whose steps differ (they walk alone).
  Scene s;
  s.name = "box";
  const int m = s.add_material(Material{});
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f), m);
  add_quad(s, {-4, -1.5f, -4}, {4, -1.5f, -4}, {4, -1.5f, 4}, {-4, -1.5f, 4}, m);
  s.lights.push_back(Light{{0, 5, 0}, glm::vec3(1.0f)});
  // (llvmpipe's GLSL flushes denormals to zero, which the host oracle does not: docs/accuracy.md.
  // There the flat components are signed zeros alone.)
  const bool flushes = GetParam().rfind("glsl", 0) == 0;
  const float dn = flushes ? 0.0f : std::numeric_limits<float>::denorm_min();
  const float sub = flushes ? 0.0f : 1e-39f;
  const float flat[] = {0.0f, -0.0f, dn, -dn, sub, -sub, 0.0f, -0.0f};
  Rays r{"axis-parallel packets", {}, {}};
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {1.0f, -1.0f})
      for (int row = 0; row < 6; ++row)
        for (int lane = 0; lane < 8; ++lane) {
          glm::vec3 dir(0.0f), org(0.0f);
          dir[axis] = sign;
          dir[(axis + 1) % 3] = flat[lane];
          dir[(axis + 2) % 3] = flat[(lane + row) % 8];
          // Origins on cell planes of a 4^3 grid over [-4, 4] x [-1.5, 1] x [-4, 4], and off.
          org[(axis + 1) % 3] = -1.0f + 0.5f * static_cast<float>(lane % 5);
          org[(axis + 2) % 3] = -0.5f + 0.25f * static_cast<float>(row);
          org[axis] = -6.0f * sign;
          // Every third row: one lane turned around, so its group walks alone.
          if (row % 3 == 2 && lane == 5) dir[axis] = -sign;
          r.o.push_back(org);
          r.d.push_back(dir);
        }
  for (int res : {4, 5, 16}) check_packets(GetParam(), s, build_grid(s, res), {r}, "box");
}

// Whether `backend`'s lane groups are the device's subgroups here, as its description says
// (vulkan: "lane groups: subgroups of 8" on lavapipe; glsl-compute: 32 on NVIDIA's GL, none
// on Mesa 22's llvmpipe).
bool device_subgroups(const std::string& backend) {
  return (backend == "vulkan" || backend == "glsl-compute") &&
         rill::backend(backend).description().find("lane groups: subgroups of ") !=
             std::string::npos;
}

// Whole renders: camera rays, shadow rays (any hit, through the light buffer or the grid),
// reflections and refraction give the same image and AOVs, bit for bit, with packets on and
// off (the megakernel's walks; 8 lanes on simd, the device's subgroups on vulkan and
// glsl-compute where it has them, a group of one on cpu), and the same image as cpu's.
TEST_P(Packets, ImagesAreTheSameBitsWithPacketsOnAndOff) {
  RT_REQUIRE_BACKEND(GetParam());
  if (GetParam() != "cpu" && GetParam() != "simd" && !device_subgroups(GetParam()))
    GTEST_SKIP() << "a group of one: AxisParallel and CameraAndLightRays cover the walk there";
  for (const char* name : {"thesis-b", "glass", "thesis-c"}) {
    Scene s = builtin_scene(name);
    const Grid g = build_grid_for(s, GetParam());
    RenderSettings rs;
    rs.backend = GetParam();
    rs.width = 48;
    rs.height = 32;
    rs.outputs.depth = rs.outputs.prim = true;
    std::vector<RenderResult> r;
    for (rt::Packets p : {rt::Packets::Off, rt::Packets::On}) {
      TracerOptions k;
      k.packets = p;
      Tracer tracer(s, g, k);
      r.push_back(tracer.render(rs, s.camera));
      // The kernel the render ran (its first frame compiles it) walks with the lane group's
      // operations: the lockstep helpers on simd, subgroup operations on a device.
      const std::string src = tracer.source(GetParam());
      const char* group_min = GetParam() == "simd" ? "rill_g_min" : "subgroupMin(";
      if (p == rt::Packets::On && GetParam() != "cpu") {
        EXPECT_NE(src.find(group_min), std::string::npos) << name;
      } else {
        EXPECT_EQ(src.find(group_min), std::string::npos) << name;
      }
    }
    if (GetParam() != "cpu") {  // strict images are the same bits on every backend
      RenderSettings on_cpu = rs;
      on_cpu.backend = "cpu";
      const RenderResult c = Tracer(s, g).render(on_cpu, s.camera);
      ASSERT_EQ(c.color.size(), r[1].color.size()) << name;
      EXPECT_EQ(std::memcmp(c.color.data(), r[1].color.data(), c.color.size() * sizeof(glm::vec3)),
                0)
          << name << ": packets on " << GetParam() << " against cpu";
      EXPECT_EQ(c.prim, r[1].prim) << name;
    }
    ASSERT_EQ(r[0].color.size(), r[1].color.size()) << name;
    EXPECT_EQ(
        std::memcmp(r[0].color.data(), r[1].color.data(), r[0].color.size() * sizeof(glm::vec3)), 0)
        << name;
    EXPECT_EQ(r[0].prim, r[1].prim) << name;
    ASSERT_EQ(r[0].depth.size(), r[1].depth.size()) << name;
    EXPECT_EQ(std::memcmp(r[0].depth.data(), r[1].depth.data(), r[0].depth.size() * sizeof(float)),
              0)
        << name;
    EXPECT_EQ(r[0].rays, r[1].rays) << name;
  }
}

// Auto is off on every backend (measured slower, Options.h): its kernels are those without
// packets, byte for byte; On gives the simd kernel the lane group's operations.
TEST(PacketsDefaults, AutoIsOffOnEveryBackendAndOnUsesTheGroup) {
  for (const char* be : {"cpu", "simd", "opencl", "glsl", "glsl-compute"})
    EXPECT_FALSE(packets_for(rt::Packets::Auto, be)) << be;
  EXPECT_TRUE(packets_for(rt::Packets::On, "cpu"));
  EXPECT_FALSE(packets_for(rt::Packets::Off, "simd"));
  EXPECT_EQ(parse_packets("auto"), rt::Packets::Auto);
  EXPECT_EQ(parse_packets("off"), rt::Packets::Off);
  EXPECT_THROW(parse_packets("yes"), std::invalid_argument);
  Scene s = builtin_scene("thesis-a");
  const Grid g = build_grid_for(s, "simd");
  TracerOptions off, on;
  off.packets = rt::Packets::Off;
  on.packets = rt::Packets::On;
  Tracer automatic(s, g), without(s, g, off), with(s, g, on);
  std::string why;
  for (const char* be : {"cpu", "simd"}) {
    if (!testing::backend_available(be, why)) continue;
    EXPECT_EQ(automatic.intersect_kernel(be).source(), without.intersect_kernel(be).source()) << be;
    EXPECT_EQ(automatic.source(be), without.source(be)) << be;
    EXPECT_EQ(without.source(be).find("rill_g_min"), std::string::npos) << be;
  }
  if (testing::backend_available("simd", why)) {
    EXPECT_NE(with.intersect_kernel("simd").source().find("rill_g_min"), std::string::npos);
    EXPECT_NE(with.source("simd").find("rill_g_min"), std::string::npos);
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Packets, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
