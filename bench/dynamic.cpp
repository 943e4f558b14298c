// rill-bench-dynamic: dynamic scenes (issue 22, docs/dynamic-scenes.md).
//
//   rill-bench-dynamic [--sections build,frames] [--repeats R] [--size WxH]
//                      [--backends cpu,...] [--instances 0,1,10,100] [--frames F]
//                      [--bvh rebuild|refit]
//
// Sections (medians of R repeats; the builders interleaved so that they share the machine's
// moods):
//   build   the moving triangles' BVH (accel/Bvh.h): a full rebuild (binned SAH) and a refit,
//           against Embree 3's rtcCommitScene on the same triangles, as a rebuild (its
//           default quality, and its fast "low" quality) and as a refit
//           (RTC_BUILD_QUALITY_REFIT), in million triangles per second. The triangles: thesis
//           scene C (61562), once and four times over, all of them moving.
//   frames  frame time of a static scene (thesis B's room and cubes) against the same scene
//           with 1, 10 and 100 animated instances of a 528-triangle ball: Tracer::set_time
//           (pose, BVH rebuild, upload) plus Tracer::render, per backend, over F frames, the
//           scenes taking turns frame by frame; "vs first" divides by the first count's.
//           --bvh refit refits the first frame's tree instead.
#include <rill/rill.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "CommaList.h"
#include "Timing.h"
#include "UsableBackends.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Bvh.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Pose.h"

#ifdef RILL_BENCH_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

namespace {

using rill::bench::Clock;
using rill::bench::median;
using rill::bench::ms_since;

// Every triangle of `base`, `copies` times side by side, as one moving object that turns and
// slides over a second.
rt::Scene moving_scene(const rt::Scene& base, int copies) {
  rt::Scene s;
  for (int c = 0; c < copies; ++c) {
    rt::Scene part = base;
    for (glm::vec3& p : part.positions) p.x += 30.0f * static_cast<float>(c);
    s.append(part);
  }
  rt::AnimatedObject o;
  o.name = "all";
  o.count = s.triangle_count();
  rt::PoseKey a, b;
  b.time = 1.0;
  b.pose.translate = glm::dvec3(2.0, 0.5, -1.0);
  b.pose.rotation = glm::angleAxis(glm::radians(35.0), glm::normalize(glm::dvec3(0.2, 1.0, 0.1)));
  o.track.keys = {a, b};
  s.animation.objects = {o};
  s.animation.time = rt::TimeRange{0.0, 1.0, 24.0};
  return s;
}

#ifdef RILL_BENCH_HAVE_EMBREE
// One Embree triangle geometry over the scene's moving triangles, committed again after each
// pose: a rebuild at `quality`, or a refit (RTC_BUILD_QUALITY_REFIT).
class EmbreeDynamic {
 public:
  EmbreeDynamic(const rt::Scene& s, const std::vector<int32_t>& ids, RTCBuildQuality quality)
      : n_(ids.size()) {
    device_ = rtcNewDevice(nullptr);
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(scene_,
                            quality == RTC_BUILD_QUALITY_REFIT ? RTC_BUILD_QUALITY_LOW : quality);
    geom_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetGeometryBuildQuality(geom_, quality);
    vertices_ = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n_));
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n_));
    for (size_t k = 0; k < 3 * n_; ++k) idx[k] = static_cast<unsigned>(k);
    ids_ = ids;
    set_positions(s);
    rtcCommitGeometry(geom_);
    rtcAttachGeometry(scene_, geom_);
    rtcCommitScene(scene_);
  }
  ~EmbreeDynamic() {
    rtcReleaseGeometry(geom_);
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  EmbreeDynamic(const EmbreeDynamic&) = delete;
  EmbreeDynamic& operator=(const EmbreeDynamic&) = delete;
  // The vertices as posed in `s`, then the commit; returns the commit's milliseconds.
  double update(const rt::Scene& s) {
    set_positions(s);
    rtcUpdateGeometryBuffer(geom_, RTC_BUFFER_TYPE_VERTEX, 0);
    const auto t = Clock::now();
    rtcCommitGeometry(geom_);
    rtcCommitScene(scene_);
    return ms_since(t);
  }

 private:
  void set_positions(const rt::Scene& s) {
    for (size_t k = 0; k < n_; ++k)
      for (size_t c = 0; c < 3; ++c) {
        const glm::vec3& p = s.positions[3 * static_cast<size_t>(ids_[k]) + c];
        vertices_[9 * k + 3 * c] = p.x;
        vertices_[9 * k + 3 * c + 1] = p.y;
        vertices_[9 * k + 3 * c + 2] = p.z;
      }
  }
  size_t n_;
  std::vector<int32_t> ids_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCGeometry geom_ = nullptr;
  float* vertices_ = nullptr;
};
#endif

void build_section(int repeats) {
  std::printf("\n### BVH build and refit, median of %d (Mtris/s; ms in brackets)\n\n", repeats);
  std::printf("| triangles | Rill rebuild | Rill refit |");
#ifdef RILL_BENCH_HAVE_EMBREE
  std::printf(" Embree rebuild (medium) | Embree rebuild (low) | Embree refit |");
#endif
  std::printf("\n| ---: | ---: | ---: |");
#ifdef RILL_BENCH_HAVE_EMBREE
  std::printf(" ---: | ---: | ---: |");
#endif
  std::printf("\n");
  const rt::Scene c = rt::builtin_scene("thesis-c");
  for (int copies : {1, 4}) {
    const rt::Scene rest = moving_scene(c, copies);
    rt::Scene posed = rest;
    const std::vector<int32_t> ids = rt::moving_triangles(rest);
    rt::Bvh tree = rt::build_bvh(rest, ids), rebuilt = tree;
#ifdef RILL_BENCH_HAVE_EMBREE
    EmbreeDynamic em(rest, ids, RTC_BUILD_QUALITY_MEDIUM), el(rest, ids, RTC_BUILD_QUALITY_LOW),
        er(rest, ids, RTC_BUILD_QUALITY_REFIT);
#endif
    std::vector<double> rebuild, refit, e_med, e_low, e_refit;
    for (int r = 0; r < repeats; ++r) {
      rt::pose_objects(rest, (r % 8) / 8.0, posed);
      // Into the same tree each time, as Tracer::set_time does (and as Embree's dynamic scene
      // keeps its memory).
      auto t = Clock::now();
      rt::rebuild_bvh(rebuilt, posed, ids);
      rebuild.push_back(ms_since(t));
      t = Clock::now();
      if (!rt::refit_bvh(tree, posed, ids)) std::printf("error: refit refused\n");
      refit.push_back(ms_since(t));
#ifdef RILL_BENCH_HAVE_EMBREE
      e_med.push_back(em.update(posed));
      e_low.push_back(el.update(posed));
      e_refit.push_back(er.update(posed));
#endif
    }
    const double n = static_cast<double>(ids.size());
    auto cell = [&](const std::vector<double>& v) {
      const double ms = median(v);
      std::printf(" %.1f (%.2f) |", ms > 0 ? n / (ms * 1e3) : 0.0, ms);
    };
    std::printf("| %zu |", ids.size());
    cell(rebuild);
    cell(refit);
#ifdef RILL_BENCH_HAVE_EMBREE
    cell(e_med);
    cell(e_low);
    cell(e_refit);
#endif
    std::printf("\n");
  }
#ifndef RILL_BENCH_HAVE_EMBREE
  std::printf("\n(Embree 3 not found at build time: apt-get install libembree-dev)\n");
#endif
}

// Thesis B's room and cubes, with `n` balls (one 576-triangle sphere placed n times) each
// flying its own loop through the room.
rt::Scene room_with_balls(int n) {
  rt::Scene s = rt::builtin_scene("thesis-b");
  const int m = s.add_material(rt::Material{});
  for (int i = 0; i < n; ++i) {
    const size_t first = s.triangle_count();
    rt::add_sphere(s, glm::vec3(0.0f), 0.35f, 24, 12, m);
    rt::AnimatedObject o;
    o.name = "ball " + std::to_string(i);
    o.first = first;
    o.count = s.triangle_count() - first;
    const double phase = 6.283185307179586 * i / std::max(n, 1);
    for (int k = 0; k <= 8; ++k) {
      rt::PoseKey key;
      key.time = k / 8.0;
      const double a = phase + 6.283185307179586 * key.time;
      key.pose.translate = glm::dvec3((3.0 + 0.04 * i) * std::cos(a), 1.0 + 0.05 * (i % 40),
                                      (3.0 + 0.04 * i) * std::sin(a));
      o.track.keys.push_back(key);
    }
    s.animation.objects.push_back(o);
  }
  s.animation.time = rt::TimeRange{0.0, 1.0, 24.0};
  return s;
}

void frames_section(const std::vector<std::string>& backends, const std::vector<int>& counts,
                    int frames, int width, int height, rt::BvhUpdate how) {
  std::printf(
      "\n### Frame time with moving balls, %dx%d, strict, BVH %s, median of %d frames (ms)\n\n",
      width, height, how == rt::BvhUpdate::Refit ? "refitted" : "rebuilt", frames);
  std::printf(
      "| backend | balls | moving triangles | set_time (pose, BVH, upload) | render | frame | vs "
      "first |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  struct Setup {
    rt::Scene scene;
    rt::Grid grid;
    std::unique_ptr<rt::Tracer> tracer;
    std::vector<double> update, render, frame, pose, bvh, upload;
  };
  for (const std::string& be : backends) {
    rt::RenderSettings rs;
    rs.backend = be;
    rs.width = width;
    rs.height = height;
    rs.outputs.color = false;
    rs.outputs.rgb8 = true;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = false;
    std::vector<std::unique_ptr<Setup>> setups;
    rt::RenderResult r;
    for (int n : counts) {
      auto u = std::make_unique<Setup>();
      u->scene = room_with_balls(n);
      u->grid = rt::build_grid_for(u->scene, be);
      u->tracer = std::make_unique<rt::Tracer>(u->scene, u->grid);
      u->tracer->render(rs, u->scene.camera, r);  // compile, warm up
      setups.push_back(std::move(u));
    }
    // Frame by frame, every count in turn: they share the machine's moods.
    for (int f = 0; f < frames; ++f)
      for (auto& u : setups) {
        const rt::TimeRange& range = u->scene.animation.time;
        const double t = range.time_of(f % range.frame_count());
        const auto t0 = Clock::now();
        const rt::FrameUpdate fu = u->tracer->set_time(t, how);
        u->update.push_back(ms_since(t0));
        u->pose.push_back(fu.pose_ms);
        u->bvh.push_back(fu.bvh_ms);
        u->upload.push_back(fu.upload_ms);
        const auto t1 = Clock::now();
        u->tracer->render(rs, rt::camera_at(u->scene, t), r);
        u->render.push_back(ms_since(t1));
        u->frame.push_back(ms_since(t0));
      }
    const double first = median(setups.front()->frame);
    for (size_t i = 0; i < setups.size(); ++i) {
      const Setup& u = *setups[i];
      std::printf("| %s | %d | %zu | %.2f (%.2f, %.2f, %.2f) | %.2f | %.2f | %.2f |\n", be.c_str(),
                  counts[i], u.scene.animation.moving_triangles(), median(u.update), median(u.pose),
                  median(u.bvh), median(u.upload), median(u.render), median(u.frame),
                  first > 0 ? median(u.frame) / first : 0.0);
    }
    std::fflush(stdout);
  }
}

std::vector<std::string> all_backends() {
  std::vector<std::string> v;
  for (rill::Backend* b : rill::backends()) v.push_back(b->name());
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "rill-bench-dynamic: BVH rebuild and refit against Embree; frame time with moving objects"};
  std::string sections = "build,frames", backends = "cpu", instances = "0,1,10,100",
              size = "512x384";
  int repeats = 9, frames = 12;
  app.add_option("--sections", sections, "build,frames");
  app.add_option("--repeats", repeats, "build: repeats per builder")->check(CLI::Range(1, 1000));
  app.add_option("--backends", backends, "frames: backends (comma-separated, or all)");
  app.add_option("--instances", instances, "frames: ball counts (comma-separated)");
  app.add_option("--frames", frames, "frames: frames per count")->check(CLI::Range(1, 10000));
  app.add_option("--size", size, "frames: image size WxH");
  std::string bvh = "rebuild";
  app.add_option("--bvh", bvh, "frames: rebuild or refit the BVH each frame");
  int threads = 0;
  app.add_option("--threads", threads,
                 "oneTBB threads for every builder, Embree's too (default: one per core)")
      ->check(CLI::Range(1, 4096));
  CLI11_PARSE(app, argc, argv);
  std::optional<tbb::global_control> limit;
  if (threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  int w = 0, h = 0;
  if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w < 1 || h < 1) {
    std::fprintf(stderr, "rill-bench-dynamic: --size expects WxH\n");
    return 2;
  }
  const std::vector<std::string> secs = rill::bench::split_list(sections);
  auto has = [&](const char* s) { return std::find(secs.begin(), secs.end(), s) != secs.end(); };
  try {
    if (has("build")) build_section(repeats);
    if (has("frames")) {
      std::vector<int> counts;
      for (const std::string& c : rill::bench::split_list(instances))
        counts.push_back(std::stoi(c));
      frames_section(rill::bench::usable_backends(
                         backends == "all" ? all_backends() : rill::bench::split_list(backends)),
                     counts, frames, w, h, rt::parse_bvh_update(bvh));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-bench-dynamic: %s\n", e.what());
    return 1;
  }
  return 0;
}
