// The Tracer facade (Tracer.h): the scene on the device, the render strategies registered by
// name (strategy/RenderStrategy.h), and what a frame does before its strategy runs.
#include "rill/rt/Tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include "rill/Stopwatch.h"
#include "rill/rt/accel/Bvh.h"
#include "rill/rt/accel/OccupiedBoxes.h"
#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/megakernel/Megakernel.h"
#include "rill/rt/multipass/Multipass.h"
#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/Pose.h"
#include "rill/rt/shaders/Registry.h"
#include "rill/rt/strategy/RenderStrategy.h"
#include "rill/rt/wavefront/Wavefront.h"

namespace rt {

using namespace rill;

namespace {

// The render strategies by name, in the order they were registered: the built-in ones first.
// A new strategy of the library is its folder and a line here; a program's, a call of
// register_strategy.
struct StrategyRegistry {
  std::mutex mutex;
  std::vector<std::pair<std::string, StrategyFactory>> entries;
  StrategyRegistry() {
    entries.emplace_back("megakernel",
                         [](DeviceScene& s) { return std::make_unique<Megakernel>(s); });
    entries.emplace_back("multipass",
                         [](DeviceScene& s) { return std::make_unique<Multipass>(s); });
    entries.emplace_back("wavefront",
                         [](DeviceScene& s) { return std::make_unique<Wavefront>(s); });
  }
};

StrategyRegistry& strategy_registry() {
  static StrategyRegistry* r = new StrategyRegistry;  // never destroyed: tracers may outlive main
  return *r;
}

// The factory registered under name; throws std::invalid_argument naming the strategies.
StrategyFactory strategy_factory(const std::string& name) {
  StrategyRegistry& r = strategy_registry();
  std::lock_guard lock(r.mutex);
  std::string names;
  for (const auto& [n, make] : r.entries) {
    if (n == name) return make;
    names += std::string(names.empty() ? "" : " or ") + n;
  }
  throw std::invalid_argument("--strategy expects " + names + " (got '" + name + "')");
}

// The kernels generate one kind of camera ray, the scene's camera's (Features::camera).
void check_camera_kind(const Features& F, const Camera& camera) {
  const CameraKind k = camera_kind(camera);
  if (k != F.camera)
    throw std::runtime_error(std::string("render: a ") + camera_kind_name(k) +
                             " camera, and this tracer's kernels were made for the scene's " +
                             camera_kind_name(F.camera) +
                             " camera: make the tracer from a scene with that kind of camera");
}

}  // namespace

void register_strategy(const std::string& name, StrategyFactory make) {
  if (name.empty()) throw std::invalid_argument("register_strategy: the strategy has no name");
  if (!make)
    throw std::invalid_argument("register_strategy: strategy '" + name + "' has no factory");
  StrategyRegistry& r = strategy_registry();
  std::lock_guard lock(r.mutex);
  for (const auto& [n, m] : r.entries)
    if (n == name)
      throw std::invalid_argument("register_strategy: a strategy named '" + name +
                                  "' is registered already");
  r.entries.emplace_back(name, std::move(make));
}

std::vector<std::string> strategy_names() {
  StrategyRegistry& r = strategy_registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [n, m] : r.entries) names.push_back(n);
  return names;
}

Strategy parse_strategy(const std::string& s) {
  (void)strategy_factory(s);  // throws for an unknown name
  return Strategy{s};
}

namespace {

// The scene's features, with options.extra_features forced on (Tracer.h).
Features tracer_features(const Scene& scene, const MaterialShaders& shaders,
                         const TracerOptions& options) {
  Features f = scene_features(scene, shaders);
  if (scene.options.integrator == Integrator::Path) {
    // Whitted's machinery is not the path integrator's: no recursive rays, no ray stack, no
    // light buffer (its shadow rays walk the grid), no Phong highlights.
    f.shadows = f.specular = f.reflection = f.refraction = false;
    f.stack = 0;
    return f;
  }
  if (f.geometry) {
    const Features& extra = options.extra_features;
    f.specular = f.specular || ((f.lights || f.area_lights) && extra.specular);
    f.refraction = f.refraction || extra.refraction;
    f.reflection = f.reflection || extra.reflection || f.refraction;
    f.stack = std::max(f.stack, f.refraction ? kRayStack : extra.stack);
    f.vertex_normals = f.vertex_normals || extra.vertex_normals;
    f.vertex_colors = f.vertex_colors || extra.vertex_colors;
  }
  return f;
}

// The shaders, each used material's checked against the integrator: the path integrator needs
// a BSDF (Shader.h).
MaterialShaders checked_for_integrator(const Scene& scene, MaterialShaders shaders) {
  if (scene.options.integrator != Integrator::Path) return shaders;
  const std::vector<bool> used = used_materials(scene);
  for (size_t m = 0; m < shaders.size(); ++m)
    if (used[m] && !shaders[m]->bsdf)
      throw SceneError("material '" + clipped(scene.materials[m].name) + "': shader '" +
                       shaders[m]->name +
                       "' has no BSDF (eval, sample and pdf), which the path integrator needs");
  return shaders;
}

// A dynamic scene as it is at the start of its time range (the Tracer's first frame), or
// none for a static scene.
std::unique_ptr<Scene> posed_at_start(const Scene& scene, const Features& f) {
  if (!f.dynamic) return nullptr;
  auto posed = std::make_unique<Scene>(scene);
  pose_objects(scene, scene.animation.time.start, *posed);
  return posed;
}

// Grows [lo, hi] by a dynamic scene's moving triangles, or by its static ones, each counted as
// scene_bounds counts them (three finite corners); returns whether it counted any. Both
// together are scene_bounds (min and max do not depend on the order), so a frame's ray offset
// (Shading::set_eps) is that of the scene baked at its time.
bool grow_bounds(const Scene& s, bool moving, glm::vec3& lo, glm::vec3& hi) {
  std::vector<bool> in_object(moving ? 0 : s.triangle_count(), false);
  std::vector<std::pair<size_t, size_t>> ranges;
  for (const AnimatedObject& o : s.animation.objects) {
    if (moving) ranges.emplace_back(o.first, o.first + o.count);
    for (size_t t = o.first; !moving && t < o.first + o.count; ++t) in_object[t] = true;
  }
  if (!moving) ranges.emplace_back(0, s.triangle_count());
  bool any = false;
  auto finite = [](const glm::vec3& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  };
  for (const auto& range : ranges)
    for (size_t t = range.first; t < range.second; ++t) {
      const glm::vec3* p = &s.positions[3 * t];
      if ((!moving && in_object[t]) || !finite(p[0]) || !finite(p[1]) || !finite(p[2])) continue;
      for (int k = 0; k < 3; ++k) {
        lo = glm::min(lo, p[k]);
        hi = glm::max(hi, p[k]);
      }
      any = true;
    }
  return any;
}

using rill::ms_since;

}  // namespace

BvhUpdate parse_bvh_update(const std::string& s) {
  if (s == "rebuild") return BvhUpdate::Rebuild;
  if (s == "refit") return BvhUpdate::Refit;
  throw std::invalid_argument("unknown BVH update '" + s + "' (rebuild, refit)");
}

struct Tracer::Impl {
  Impl(const Scene& scene, const Grid& grid, const TracerOptions& options)
      : options(scene.options),
        width(scene.width),
        height(scene.height),
        shaders(checked_for_integrator(scene, resolve_shaders(scene))),
        features(tracer_features(scene, shaders, options)),
        rest(features.dynamic ? std::make_unique<Scene>(scene) : nullptr),
        posed(posed_at_start(scene, features)),
        device(posed ? *posed : scene, grid, options, features, shaders),
        static_boxes(occupied_boxes(scene, grid)) {
    strategies["megakernel"] = std::make_unique<Megakernel>(device);
    if (posed) {
      bvh = build_bvh(*posed, moving_triangles(*posed));
      device.bvh.upload(bvh);
      static_any = grow_bounds(*posed, false, static_lo, static_hi);
    }
  }

  SceneOptions options;  // depth and samples per pixel by default
  int width, height;     // the image size by default
  // The materials' shaders as registered when the tracer was built: its kernels are generated
  // from these, whatever is registered later (shaders/Registry.h).
  MaterialShaders shaders;
  Features features;
  // Dynamic scenes: the scene at rest (as given), as posed now, and the BVH of its moving
  // triangles; null / empty for a static scene.
  std::unique_ptr<Scene> rest, posed;
  Bvh bvh;
  // The bounds of the static triangles (whether there are any), for each frame's ray offset.
  bool static_any = false;
  glm::vec3 static_lo{INFINITY}, static_hi{-INFINITY};
  DeviceScene device;
  // The strategies made so far, by name: the megakernel with the tracer, the others at their
  // first frame (StrategyRegistry).
  std::map<std::string, std::unique_ptr<RenderStrategy>> strategies;
  // The frames traced so far, as "strategy/backend/accuracy/loop/WxH": a frame not among them
  // is cold (RenderResult::cold).
  std::set<std::string> traced;
  // Boxes that hold every static triangle that can be hit (accel/OccupiedBoxes.h).
  std::vector<Aabb> static_boxes;
  std::vector<Aabb> frame_boxes;  // static_boxes widened for the frame's eye
  Film film;                      // every strategy's samples meet here
  Program intersect_programs[2];  // without and with packets (Intersector::set_packets)
  Program camera_program;

  // The megakernel, whose programs and source the Tracer also gives out.
  Megakernel& megakernel() { return static_cast<Megakernel&>(*strategies.at("megakernel")); }
  RenderStrategy& strategy(const Strategy& s) {
    if (auto it = strategies.find(s.name); it != strategies.end()) return *it->second;
    std::unique_ptr<RenderStrategy> made = strategy_factory(s.name)(device);  // throws if unknown
    if (!made) throw std::runtime_error("strategy '" + s.name + "': its factory made none");
    return *strategies.emplace(s.name, std::move(made)).first->second;
  }
};

Tracer::Tracer(const Scene& scene, const Grid& grid, const TracerOptions& options) {
  scene.validate();
  // A grid built from another scene (a baked copy, say) would hold the moving triangles at
  // rest: ghosts that never move.
  if (grid.moving != scene.animation.moving_triangles())
    throw std::invalid_argument("Tracer: the grid leaves out " + std::to_string(grid.moving) +
                                " moving triangles but the scene has " +
                                std::to_string(scene.animation.moving_triangles()) +
                                "; build the grid from this scene (build_grid_for)");
  d_ = std::make_unique<Impl>(scene, grid, options);
}

Tracer::~Tracer() = default;

const Program& Tracer::program(MegakernelLoop loop) const {
  return d_->megakernel().program(loop == MegakernelLoop::Auto ? MegakernelLoop::Ray : loop);
}
const Features& Tracer::features() const {
  return d_->device.F;
}
const TracerOptions& Tracer::options() const {
  return d_->device.K;
}
const LightBufferStats& Tracer::light_buffer() const {
  return d_->device.light_buffer.stats;
}
std::vector<std::string> Tracer::shaders() const {
  return d_->device.materials.used_shaders();
}

std::string Tracer::source(const std::string& backend, Accuracy a, MegakernelLoop loop,
                           const FrameOutputs&, int) {
  return d_->megakernel().kernel(backend, a, megakernel_loop_for(loop, backend)).source();
}

FrameUpdate Tracer::set_time(double time, BvhUpdate how) {
  Impl& I = *d_;
  FrameUpdate u;
  if (!std::isfinite(time))
    throw std::invalid_argument("Tracer::set_time: the time must be finite");
  if (!I.rest) return u;
  auto t = std::chrono::steady_clock::now();
  pose_objects(*I.rest, time, *I.posed);
  // Secondary rays leave surfaces by an offset relative to the scene's size, which moving
  // triangles change: the size now, as the scene baked at this time has it.
  glm::vec3 lo = I.static_lo, hi = I.static_hi;
  const bool any = grow_bounds(*I.posed, true, lo, hi) || I.static_any;
  I.device.shading.set_eps(any, lo, hi);
  u.pose_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  const std::vector<int32_t> ids = moving_triangles(*I.posed);
  u.rebuilt = how == BvhUpdate::Rebuild || !refit_bvh(I.bvh, *I.posed, ids);
  if (u.rebuilt) rebuild_bvh(I.bvh, *I.posed, ids);
  u.bvh_ms = ms_since(t);
  t = std::chrono::steady_clock::now();
  I.device.bvh.upload(I.bvh);
  // Only the span of the moving triangles: the static ones stay as they are, on the host and
  // on the device.
  if (!ids.empty()) {
    const auto [lo, hi] = std::minmax_element(ids.begin(), ids.end());
    const auto first = static_cast<size_t>(*lo), end = static_cast<size_t>(*hi) + 1;
    I.device.tris.update_geometry(*I.posed, I.device.K, I.device.F, first, end);
    u.uploaded = end - first;
  }
  u.upload_ms = ms_since(t);
  u.moving = ids.size();
  u.bvh_nodes = static_cast<int>(I.bvh.nodes.size());
  u.bvh_depth = I.bvh.depth;
  return u;
}

RenderResult Tracer::render(const RenderSettings& rs, const Camera& camera) {
  RenderResult r;
  render(rs, camera, r);
  return r;
}

void Tracer::render(const RenderSettings& rs, const Camera& camera, RenderResult& r) {
  // A fresh frame's result, but with the memory of the last frame's images (whose read-back
  // must have ended first).
  r.wait_outputs();
  RenderResult fresh;
  fresh.color.swap(r.color);
  fresh.rgb8.swap(r.rgb8);
  fresh.depth.swap(r.depth);
  fresh.prim.swap(r.prim);
  fresh.normal.swap(r.normal);
  r = std::move(fresh);
  Impl& I = *d_;
  // 0 is the scene's (RenderSettings.h); any other size is held to the limits every image is.
  const int width = rs.width != 0 ? rs.width : I.width;
  const int height = rs.height != 0 ? rs.height : I.height;
  if (!image_size_fits(width, height))
    throw std::runtime_error("render: image size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is out of range (" + image_size_limits() +
                             "; 0 for the scene's)");
  const int depth = rs.max_depth >= 0 ? rs.max_depth : I.options.max_depth;
  const int spp = rs.spp > 0 ? rs.spp : I.options.spp;
  RenderSettings::Window win = rs.window;
  if (win.empty()) win = {0, 0, width, height};
  if (win.x < 0 || win.y < 0 || win.width > width - win.x || win.height > height - win.y)
    throw std::runtime_error("render: window " + std::to_string(win.width) + "x" +
                             std::to_string(win.height) + " at (" + std::to_string(win.x) + ", " +
                             std::to_string(win.y) + ") is not inside the " +
                             std::to_string(width) + "x" + std::to_string(height) + " image");
  // The camera spans the whole image; the launches cover the window. What a camera ray can
  // hit: the grid's triangles and the moving ones' BVH, as they are now.
  std::optional<Aabb> moving;
  if (!I.bvh.nodes.empty()) moving = Aabb{I.bvh.nodes.front().lo, I.bvh.nodes.front().hi};
  // Widened by the triangle test's rounding as seen from this eye (hit_margin).
  // (From the farthest a ray's origin lies: an orthographic or thin-lens ray's is off the eye.)
  check_camera_kind(I.device.F, camera);
  const CameraFrame view = camera_frame(camera, width, height);
  const glm::vec3 from = view.kind == CameraKind::Pinhole
                             ? camera.eye
                             : glm::vec3(camera_origin_reach(view), 0.0f, 0.0f);
  const float margin = hit_margin(I.static_boxes, moving ? &*moving : nullptr, from);
  I.frame_boxes.resize(I.static_boxes.size());
  std::transform(I.static_boxes.begin(), I.static_boxes.end(), I.frame_boxes.begin(),
                 [&](const Aabb& b) { return widened(b, margin); });
  if (moving) moving = widened(*moving, margin);
  I.device.camera.set(camera, width, height, glm::ivec2(win.x, win.y), &I.frame_boxes,
                      moving ? &*moving : nullptr);
  Frame frame{rs, win.width, win.height, depth, spp, I.film};
  if (rs.resume != nullptr) {
    if (rs.resume->samples > spp)
      throw std::runtime_error(
          "render: the accumulation to resume has " + std::to_string(rs.resume->samples) +
          " samples per pixel, more than the " + std::to_string(spp) + " asked for");
    frame.first_sample = rs.resume->samples;
  }
  // Only the wavefront keeps its paths in streams between bounces (render/BounceRays.h).
  if (rs.bounce_rays != nullptr && !(rs.strategy == Strategy::Wavefront))
    throw std::runtime_error(
        "render: the bounce rays are read back by the wavefront strategy "
        "only, not by '" +
        rs.strategy.name + "'");
  if (rs.bounce_rays != nullptr && rs.bounce_rays->bounce < 0)
    throw std::runtime_error("render: the bounce rays' bounce must be 0 or more (got " +
                             std::to_string(rs.bounce_rays->bounce) + ")");
  const std::string traced_key = rs.strategy.name + "/" + rs.backend + "/" +
                                 rill::accuracy_name(rs.accuracy) + "/" +
                                 megakernel_loop_name(rs.loop) + "/" + std::to_string(win.width) +
                                 "x" + std::to_string(win.height);
  I.film.read_back_later(rs.read_back_later);
  try {
    I.strategy(rs.strategy).render(frame, r);
  } catch (...) {
    I.film.wait_read_backs();  // read into r, which the caller may drop now
    throw;
  }
  r.cold = I.traced.insert(traced_key).second;
}

std::vector<glm::vec3> Tracer::camera_rays(const std::string& backend, const Camera& camera,
                                           int width, int height, glm::vec2 offset,
                                           std::vector<glm::vec3>* origins, int sample) {
  Impl& I = *d_;
  check_camera_kind(I.device.F, camera);
  if (!I.camera_program.valid())
    I.camera_program = rill::program("rill_camera_rays", [&] {
      Output<Float3> o("origin");
      Output<Float3> dir("direction");
      Ray r{I.device.camera.eye, Float3(0.0f, 0.0f, 1.0f), Float(kBig)};
      I.device.camera.aim(r, element_coord());
      o = r.o;
      dir = r.d;
    });
  I.device.camera.set(camera, width, height);
  I.device.camera.offset.set(offset);
  I.device.camera.lens_sample.set(sample);
  Kernel k = compile(I.camera_program, backend);
  Stream<Float3> origin_stream(width, height), dirs(width, height);
  k.outputs(origin_stream, dirs);
  k.execute();
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<glm::vec3> d = dirs.download();
  d.resize(n);
  if (origins) {
    *origins = origin_stream.download();
    origins->resize(n);
  }
  return d;
}

Kernel Tracer::intersect_kernel(const std::string& backend, Accuracy accuracy) {
  Impl& I = *d_;
  const bool packets = packets_for(I.device.K.packets, backend);
  Program& intersect_program = I.intersect_programs[packets ? 1 : 0];
  if (!intersect_program.valid()) {
    I.device.intersector.set_packets(packets);  // for this program's capture alone
    intersect_program = rill::program("rill_intersect", [&] {
      Input<Float3> o("origin");
      Input<Float3> d("direction");
      Output<Int> prim("prim");
      Output<Float> dist("dist");
      Hit hit = I.device.intersector.intersect(Ray{o, d, Float(kBig)}, nullptr);
      Bool found = hit.id >= 0;
      prim = select(found, hit.id, -1);
      dist = select(found, hit.t, as_float(Int(0x7f800000)));
    });
    I.device.intersector.set_packets(false);
  }
  CompileOptions opt;
  opt.accuracy = accuracy;
  return compile(intersect_program, backend, opt);
}

void Tracer::intersect(const std::string& backend, const std::vector<glm::vec3>& origins,
                       const std::vector<glm::vec3>& dirs, std::vector<int32_t>& prim,
                       std::vector<float>& dist, Accuracy accuracy) {
  Kernel k = intersect_kernel(backend, accuracy);
  if (origins.size() != dirs.size())
    throw std::invalid_argument("intersect: origins and directions differ in size");
  const size_t n = origins.size();
  prim.clear();
  dist.clear();
  if (n == 0) return;
  Stream<Float3> o(origins), d(dirs);
  Stream<Int> p(static_cast<int64_t>(n));
  Stream<Float> t(static_cast<int64_t>(n));
  k.inputs(o, d).outputs(p, t);
  k.execute();
  prim = p.download();
  dist = t.download();
}

}  // namespace rt
