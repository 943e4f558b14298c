// Intel Embree 3 as the reference for rill-bench-trace: the same triangles in an Embree
// scene, the same rays traced one at a time with rtcIntersect1 (single-ray queries, as the
// Rill kernel traces one ray per instance), spread over the cores by oneTBB the way Rill's
// CPU backend spreads its kernel (blocked_range of grain 1024).
//
// Only the triangles the Rill grid traces are given to Embree (rt::triangle_usable: finite,
// non-zero area), each under its Rill primitive id, so the two report comparable ids.
// Embree's memory is counted with its memory monitor (BVH, its copy of the vertices and
// indices, build scratch it still holds).
//
// Compiled only when CMake found Embree 3 (RILL_BENCH_HAVE_EMBREE).
#pragma once

#ifdef RILL_BENCH_HAVE_EMBREE

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace bench {

class EmbreeScene {
 public:
  explicit EmbreeScene(const rt::Scene& s) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
    rtcSetDeviceMemoryMonitorFunction(device_, &EmbreeScene::monitor, this);
    const auto t0 = std::chrono::steady_clock::now();
    scene_ = rtcNewScene(device_);
    for (size_t t = 0; t < s.triangle_count(); ++t)
      if (rt::triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]))
        ids_.push_back(static_cast<int32_t>(t));
    if (!ids_.empty()) {
      RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * ids_.size()));
      auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), ids_.size()));
      for (size_t k = 0; k < ids_.size(); ++k)
        for (size_t c = 0; c < 3; ++c) {
          const glm::vec3& p = s.positions[3 * static_cast<size_t>(ids_[k]) + c];
          v[9 * k + 3 * c] = p.x;
          v[9 * k + 3 * c + 1] = p.y;
          v[9 * k + 3 * c + 2] = p.z;
          idx[3 * k + c] = static_cast<unsigned>(3 * k + c);
        }
      rtcCommitGeometry(g);
      rtcAttachGeometry(scene_, g);
      rtcReleaseGeometry(g);
    }
    rtcCommitScene(scene_);
    build_ms_ =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
      throw std::runtime_error("Embree: building the scene failed");
  }
  ~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  double build_ms() const { return build_ms_; }
  // Bytes Embree holds for the scene (after the build).
  int64_t bytes() const { return bytes_.load(); }
  // For the packet and stream modes (trace_embree_modes.h): the device (its properties), the
  // committed scene.
  RTCDevice device() const { return device_; }
  RTCScene handle() const { return scene_; }

  // Closest hit of rays (eye, dirs[i]), t in (0, inf): primitive id (-1: miss), distance.
  void trace(const glm::vec3& eye, const std::vector<glm::vec3>& dirs, int32_t* prim,
             float* dist) const {
    trace_each([&](size_t) -> const glm::vec3& { return eye; }, dirs, prim, dist);
  }
  // The same for rays of their own origins (origins[i], dirs[i]): the path tracer's bounces.
  void trace(const std::vector<glm::vec3>& origins, const std::vector<glm::vec3>& dirs,
             int32_t* prim, float* dist) const {
    if (origins.size() != dirs.size())
      throw std::invalid_argument("Embree: origins and directions differ in size");
    trace_each([&](size_t i) -> const glm::vec3& { return origins[i]; }, dirs, prim, dist);
  }

  // A ray (o, d) for t in (0, inf) with no hit yet, for rtcIntersect1 and the stream mode.
  static void set_ray(RTCRayHit& rh, const glm::vec3& o, const glm::vec3& d, unsigned id) {
    rh.ray.org_x = o.x;
    rh.ray.org_y = o.y;
    rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x;
    rh.ray.dir_y = d.y;
    rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = std::numeric_limits<float>::infinity();
    rh.ray.time = 0.0f;
    rh.ray.mask = 0xffffffffu;
    rh.ray.id = id;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  }
  // A ray's answer in Rill's terms: the primitive id (-1: miss) and the distance (+inf).
  void answer(unsigned geom_id, unsigned prim_id, float tfar, int32_t& prim, float& dist) const {
    const bool hit = geom_id != RTC_INVALID_GEOMETRY_ID;
    prim = hit ? ids_[prim_id] : -1;
    dist = hit ? tfar : std::numeric_limits<float>::infinity();
  }

 private:
  template <class OriginOf>
  void trace_each(const OriginOf& origin_of, const std::vector<glm::vec3>& dirs, int32_t* prim,
                  float* dist) const {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, dirs.size(), 1024),
                      [&](const tbb::blocked_range<size_t>& r) {
                        RTCIntersectContext ctx;
                        rtcInitIntersectContext(&ctx);
                        for (size_t i = r.begin(); i < r.end(); ++i) {
                          RTCRayHit rh;
                          set_ray(rh, origin_of(i), dirs[i], 0);
                          rtcIntersect1(scene_, &ctx, &rh);
                          answer(rh.hit.geomID, rh.hit.primID, rh.ray.tfar, prim[i], dist[i]);
                        }
                      });
  }

  static bool monitor(void* self, ssize_t bytes, bool /*post*/) {
    static_cast<EmbreeScene*>(self)->bytes_ += bytes;
    return true;
  }

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::vector<int32_t> ids_;  // Embree primID -> Rill primitive id
  double build_ms_ = 0;
  std::atomic<int64_t> bytes_{0};
};

}  // namespace bench

#endif  // RILL_BENCH_HAVE_EMBREE
