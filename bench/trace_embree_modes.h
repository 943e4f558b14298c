// Embree's own coherent ray modes for rill-bench-trace's embree section (issue 51): the camera
// rays of an image traced as packets (rtcIntersect4/8/16 over pixel tiles of 2x2, 4x2 or 4x4,
// with valid masks where a tile crosses the image's edge) and as streams (rtcIntersect1M over
// the rays of an 8x8 pixel tile, as Embree's own tutorials trace a tile), both with the
// coherent-rays flag set, beside the one-ray-at-a-time rtcIntersect1 of trace_embree.h.
//
// The threads and the split of work are the rtcIntersect1 row's: tbb::parallel_for over
// blocked ranges of about 1024 rays (here whole tiles, 1024 / tile size of them), so the modes
// differ only in how Embree is asked, not in how the image is spread over the cores.
//
// The mode list (--embree-modes) is parsed without Embree; tracing needs it
// (RILL_BENCH_HAVE_EMBREE).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#ifdef RILL_BENCH_HAVE_EMBREE
#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <limits>

#include "trace_embree.h"
#endif

namespace bench {

// How Embree is asked for the closest hits: one ray per call, a packet of `width` rays, or a
// stream of one tile's rays.
struct EmbreeMode {
  enum class Kind { Single, Packet, Stream };
  Kind kind = Kind::Single;
  int width = 1;  // rays per call (a stream: at most; edge tiles hold fewer)

  // The tile of pixels one call traces (tile_w x tile_h); one pixel for Single.
  int tile_w() const { return kind == Kind::Stream ? 8 : width == 4 ? 2 : width == 1 ? 1 : 4; }
  int tile_h() const { return kind == Kind::Stream ? 8 : width / tile_w(); }
  std::string function() const {
    return kind == Kind::Stream ? "rtcIntersect1M" : "rtcIntersect" + std::to_string(width);
  }
  // The table's name of the mode: "rtcIntersect8, 4x2 tiles".
  std::string label() const {
    if (kind == Kind::Single) return function();
    return function() + ", " + std::to_string(tile_w()) + "x" + std::to_string(tile_h()) + " tiles";
  }
};

// --embree-modes, the modes beside rtcIntersect1 (which always runs): "auto" (see
// auto_embree_modes), or a comma list of 4, 8, 16 (rtcIntersect4/8/16) and 1M (the stream).
// Returns no modes for "auto": the CPU decides, once Embree is up.
inline std::vector<EmbreeMode> parse_embree_modes(const std::vector<std::string>& items) {
  std::vector<EmbreeMode> out;
  if (items.size() == 1 && items[0] == "auto") return out;
  if (items.empty()) throw std::invalid_argument("--embree-modes: auto, or name at least one mode");
  for (const std::string& s : items) {
    EmbreeMode m;
    if (s == "4" || s == "8" || s == "16") {
      m = {EmbreeMode::Kind::Packet, std::stoi(s)};
    } else if (s == "1M" || s == "1m") {
      m = {EmbreeMode::Kind::Stream, 64};
    } else if (s == "1") {
      throw std::invalid_argument(
          "--embree-modes: rtcIntersect1 always runs; list the others (4, 8, 16, 1M) or auto");
    } else {
      throw std::invalid_argument("--embree-modes: unknown mode '" + s +
                                  "' (auto, or a comma list of 4, 8, 16, 1M)");
    }
    for (const EmbreeMode& o : out)
      if (o.kind == m.kind && o.width == m.width)
        throw std::invalid_argument("--embree-modes: '" + s + "' is listed twice");
    out.push_back(m);
  }
  return out;
}

#ifdef RILL_BENCH_HAVE_EMBREE

// Whether Embree runs packets of this width natively on this CPU (otherwise it emulates them,
// splitting the packet, and a row of that width would measure the emulation).
inline bool embree_native_packet(RTCDevice device, int width) {
  const RTCDeviceProperty p = width == 4   ? RTC_DEVICE_PROPERTY_NATIVE_RAY4_SUPPORTED
                              : width == 8 ? RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED
                                           : RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED;
  return rtcGetDeviceProperty(device, p) != 0;
}

// Whether this mode runs natively here: "yes", "no" (emulated), "-" for rtcIntersect1.
inline std::string embree_native(RTCDevice device, const EmbreeMode& m) {
  bool yes = true;
  if (m.kind == EmbreeMode::Kind::Single) return "-";
  if (m.kind == EmbreeMode::Kind::Packet) yes = embree_native_packet(device, m.width);
  if (m.kind == EmbreeMode::Kind::Stream)
    yes = rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_RAY_STREAM_SUPPORTED) != 0;
  return yes ? "yes" : "no";
}

// What "auto" stands for on this CPU: the packets of 8 and 16 that it runs natively (8 if
// neither: Embree's AVX width, emulated), and the stream.
inline std::vector<EmbreeMode> auto_embree_modes(RTCDevice device) {
  std::vector<EmbreeMode> out;
  for (int w : {8, 16})
    if (embree_native_packet(device, w)) out.push_back({EmbreeMode::Kind::Packet, w});
  if (out.empty()) out.push_back({EmbreeMode::Kind::Packet, 8});
  out.push_back({EmbreeMode::Kind::Stream, 64});
  return out;
}

namespace detail {

template <int N>
struct EmbreePacket;
template <>
struct EmbreePacket<4> {
  using RayHit = RTCRayHit4;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect4(valid, s, c, r);
  }
};
template <>
struct EmbreePacket<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect8(valid, s, c, r);
  }
};
template <>
struct EmbreePacket<16> {
  using RayHit = RTCRayHit16;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect16(valid, s, c, r);
  }
};

// The image's pixels in tiles of tw x th, numbered row by row; tiles at the right and bottom
// edges may stick out of the image.
struct Tiles {
  int width, height, tw, th;
  size_t across() const { return (static_cast<size_t>(width) + tw - 1) / tw; }
  size_t count() const { return across() * ((static_cast<size_t>(height) + th - 1) / th); }
  int x0(size_t t) const { return static_cast<int>(t % across()) * tw; }
  int y0(size_t t) const { return static_cast<int>(t / across()) * th; }
  // About 1024 rays a task, as the rtcIntersect1 row's blocked ranges hold.
  size_t grain() const { return std::max<size_t>(1, 1024 / static_cast<size_t>(tw * th)); }
};

template <int N>
void trace_packets(const EmbreeScene& e, const Tiles& tiles, const glm::vec3& eye,
                   const std::vector<glm::vec3>& dirs, int32_t* prim, float* dist) {
  using P = EmbreePacket<N>;
  const float inf = std::numeric_limits<float>::infinity();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.count(), tiles.grain()),
                    [&](const tbb::blocked_range<size_t>& r) {
                      RTCIntersectContext ctx;
                      rtcInitIntersectContext(&ctx);
                      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                      for (size_t t = r.begin(); t < r.end(); ++t) {
                        // Embree reads the valid mask with vector loads of the packet's width.
                        alignas(64) int valid[N];
                        size_t pixel[N];
                        typename P::RayHit rh;
                        for (int k = 0; k < N; ++k) {
                          const int x = tiles.x0(t) + k % tiles.tw, y = tiles.y0(t) + k / tiles.tw;
                          const bool inside = x < tiles.width && y < tiles.height;
                          valid[k] = inside ? -1 : 0;
                          // A lane outside the image still gets a well-formed ray (pixel 0's),
                          // never traced.
                          pixel[k] =
                              inside ? static_cast<size_t>(y) * static_cast<size_t>(tiles.width) +
                                           static_cast<size_t>(x)
                                     : 0;
                          const glm::vec3& d = dirs[pixel[k]];
                          rh.ray.org_x[k] = eye.x;
                          rh.ray.org_y[k] = eye.y;
                          rh.ray.org_z[k] = eye.z;
                          rh.ray.dir_x[k] = d.x;
                          rh.ray.dir_y[k] = d.y;
                          rh.ray.dir_z[k] = d.z;
                          rh.ray.tnear[k] = 0.0f;
                          rh.ray.tfar[k] = inf;
                          rh.ray.time[k] = 0.0f;
                          rh.ray.mask[k] = 0xffffffffu;
                          rh.ray.id[k] = static_cast<unsigned>(k);
                          rh.ray.flags[k] = 0;
                          rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
                          rh.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
                        }
                        P::intersect(valid, e.handle(), &ctx, &rh);
                        for (int k = 0; k < N; ++k) {
                          if (!valid[k]) continue;
                          e.answer(rh.hit.geomID[k], rh.hit.primID[k], rh.ray.tfar[k],
                                   prim[pixel[k]], dist[pixel[k]]);
                        }
                      }
                    });
}

inline void trace_streams(const EmbreeScene& e, const Tiles& tiles, const glm::vec3& eye,
                          const std::vector<glm::vec3>& dirs, int32_t* prim, float* dist) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.count(), tiles.grain()),
                    [&](const tbb::blocked_range<size_t>& r) {
                      RTCIntersectContext ctx;
                      rtcInitIntersectContext(&ctx);
                      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                      std::vector<RTCRayHit> rays(static_cast<size_t>(tiles.tw * tiles.th));
                      std::vector<size_t> pixel(rays.size());
                      for (size_t t = r.begin(); t < r.end(); ++t) {
                        // The tile's pixels inside the image, row by row: a shorter stream at the
                        // edges.
                        unsigned m = 0;
                        const int x0 = tiles.x0(t), y0 = tiles.y0(t);
                        for (int y = y0; y < std::min(y0 + tiles.th, tiles.height); ++y)
                          for (int x = x0; x < std::min(x0 + tiles.tw, tiles.width); ++x, ++m) {
                            pixel[m] = static_cast<size_t>(y) * static_cast<size_t>(tiles.width) +
                                       static_cast<size_t>(x);
                            EmbreeScene::set_ray(rays[m], eye, dirs[pixel[m]], m);
                          }
                        rtcIntersect1M(e.handle(), &ctx, rays.data(), m, sizeof(RTCRayHit));
                        for (unsigned k = 0; k < m; ++k) {
                          e.answer(rays[k].hit.geomID, rays[k].hit.primID, rays[k].ray.tfar,
                                   prim[pixel[k]], dist[pixel[k]]);
                        }
                      }
                    });
}

}  // namespace detail

// The closest hits of the camera rays (eye, dirs[y * width + x]) of a width x height image
// in mode m: primitive id (-1: miss) and distance, per pixel.
inline void trace_image(const EmbreeScene& e, const EmbreeMode& m, const glm::vec3& eye,
                        const std::vector<glm::vec3>& dirs, int width, int height, int32_t* prim,
                        float* dist) {
  if (dirs.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    throw std::invalid_argument("Embree: the rays are not a width x height image");
  const detail::Tiles tiles{width, height, m.tile_w(), m.tile_h()};
  switch (m.kind) {
    case EmbreeMode::Kind::Single:
      e.trace(eye, dirs, prim, dist);
      return;
    case EmbreeMode::Kind::Stream:
      detail::trace_streams(e, tiles, eye, dirs, prim, dist);
      return;
    case EmbreeMode::Kind::Packet:
      if (m.width == 4) detail::trace_packets<4>(e, tiles, eye, dirs, prim, dist);
      if (m.width == 8) detail::trace_packets<8>(e, tiles, eye, dirs, prim, dist);
      if (m.width == 16) detail::trace_packets<16>(e, tiles, eye, dirs, prim, dist);
      return;
  }
}

#endif  // RILL_BENCH_HAVE_EMBREE

}  // namespace bench
