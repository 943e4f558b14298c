// The wavefront strategy (Wavefront.h): its kernels, compiled together, and the render loop
// over samples and bounces.
#include "rill/rt/wavefront/Wavefront.h"

#include <optional>
#include <stdexcept>
#include <vector>

#include "rill/Reduce.h"
#include "rill/Stopwatch.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/PerBackend.h"
#include "rill/rt/wavefront/Records.h"

namespace rt {

using namespace rill;
using namespace wf;

Wavefront::Wavefront(DeviceScene& scene) : S_(scene) {
  if (S_.options.integrator != Integrator::Path)
    throw std::runtime_error(
        "the wavefront strategy runs the path integrator; use megakernel or multipass for "
        "whitted");
  path_ = std::make_unique<PathIntegrator>(S_, S_.path_lights, S_.options);
  (void)programs();  // a shader's misuse of its parameters is an error of the first frame
}

Wavefront::~Wavefront() = default;

const Wavefront::Programs& Wavefront::programs() {
  if (programs_) return *programs_;
  Programs p;
  p.camera = capture_camera();
  if (S_.F.geometry) p.intersect = capture_intersect();
  p.shade = capture_shade();
  if (path_->shadow_rays()) p.shadow = capture_shadow();
  return programs_.emplace(std::move(p));
}

Wavefront::Kernels& Wavefront::kernels(const std::string& backend_name, Accuracy a) {
  const std::string key = backend_key(backend_name, a);
  auto it = kernels_.find(key);
  if (it != kernels_.end()) return it->second;
  const Programs& p = programs();
  check_backend(backend_name, a);
  CompileOptions opt;
  opt.accuracy = a;
  Kernels k;
  // Independent kernels: compiled together, the C compiler runs on every core.
  std::vector<std::pair<Kernel*, const Program*>> wanted{{&k.camera, &p.camera},
                                                         {&k.shade, &p.shade}};
  if (p.intersect.valid()) wanted.emplace_back(&k.intersect, &p.intersect);
  if (p.shadow.valid()) wanted.emplace_back(&k.shadow, &p.shadow);
  std::vector<CompileRequest> requests;
  for (const auto& [kernel, program] : wanted) requests.push_back({*program, backend_name, opt});
  std::vector<Kernel> built = compile_all(requests);
  for (size_t i = 0; i < wanted.size(); ++i) *wanted[i].first = std::move(built[i]);
  return kernels_.emplace(key, std::move(k)).first->second;
}

// One backend's streams, kept for its next frame of the same size (PerBackend.h).
struct Wavefront::Buffers {
  Buffers(int w, int h)
      : path(w, h, "path"),
        hit(w, h, "hit"),
        shadow(w, h, "shadow"),
        aov(w, h, "aov"),
        albedo(w, h, "albedo"),
        width(w),
        height(h) {}
  Stream<PathRecord> path;
  Stream<HitRecord> hit;
  Stream<ShadowRecord> shadow;
  Stream<Aov> aov;
  Stream<Float3> albedo;
  int width, height;
};

void Wavefront::render(const Frame& frame, RenderResult& r) {
  const RenderSettings& rs = frame.settings;
  const int width = frame.width, height = frame.height, depth = frame.depth, spp = frame.spp;
  Film& film = frame.film;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  Stopwatch since_start;
  Kernels& K = kernels(rs.backend, rs.accuracy);
  r.from_cache = K.camera.info().cache_hit || K.camera.info().from_disk_cache;
  for (const Kernel* k : {&K.camera, &K.intersect, &K.shade, &K.shadow})
    if (!k->backend_name().empty()) add_stages(r, k->info());
  const bool geometry = !K.intersect.backend_name().empty();
  const bool shadows = !K.shadow.backend_name().empty();

  S_.shading.max_depth.set(depth);
  Stopwatch setup;
  Buffers& B = buffers_for(buffers_, backend_key(rs.backend, rs.accuracy), width, height);
  K.camera.bind_fields("path", B.path);
  K.shade.bind_fields("path", B.path);
  if (geometry) {
    K.intersect.bind_fields("path", B.path).bind_fields("hit", B.hit);
    K.shade.bind_fields("hit", B.hit);
  }
  if (shadows) {
    K.camera.bind_fields("shadow", B.shadow);
    K.shade.bind_fields("shadow", B.shadow);
    K.shadow.bind_fields("shadow", B.shadow).bind_fields("path", B.path);
  }
  K.camera.bind_fields("aov", B.aov);
  K.shade.bind_fields("aov", B.aov);
  K.camera.bind("albedo", B.albedo);
  K.shade.bind("albedo", B.albedo);
  film.begin(rs.backend, rs.accuracy, width, height, spp, rs.resume, frame.summing(),
             rs.outputs.variance);
  r.times.setup = setup.ms();

  // The masks: the paths not done (intersect, shade), the active shadow queries (shadow).
  const Stream<Int> done = B.path.field<Int>("done");
  const Stream<Int> active = B.shadow.field<Int>("active");
  const StateMask alive = where(done, 0), queried = where(active, 1);
  const Stream<Int3> ints = B.path.field<Int3>("ints");  // (depth, delta, rays)
  // Drivers that finish compiling at the first launch of a size (PoCL, Mesa), or at the
  // first masked one, do it here, so that the trace time below is tracing alone; the ray
  // count's reduction kernels compile here too.
  const auto warm_key =
      std::make_pair(backend_key(rs.backend, rs.accuracy), int64_t{width} * height);
  if (!warmed_.count(warm_key)) {
    Stopwatch first_launch;
    K.camera.warm_up();
    if (geometry) K.intersect.warm_up(alive);
    K.shade.warm_up(alive);
    if (shadows) K.shadow.warm_up(queried);
    (void)rill::sum(ints, rs.backend);
    warmed_.insert(warm_key);
    r.first_launch_ms = first_launch.ms();
  }
  r.compile_ms = since_start.ms() - r.times.setup;

  enum Stage { kCamera, kIntersect, kShade, kShadow, kStages };
  static const char* const kStageNames[kStages] = {"camera", "intersect", "shade", "shadow"};
  r.passes.assign(kStages, PassStats{});
  for (int p = 0; p < kStages; ++p) r.passes[static_cast<size_t>(p)].name = kStageNames[p];
  auto run = [&](Kernel& k, Stage stage, const std::optional<StateMask>& mask) {
    return run_pass(k, mask, r.passes[static_cast<size_t>(stage)], r);
  };

  // The rays after `scatterings` bounces, if asked for (render/BounceRays.h): the paths not
  // done once the stage that made those rays ran (the camera stage for 0 bounces, else the
  // shade stage of that many hits), read back before the intersect stage traces them.
  BounceRays* const capture = rs.bounce_rays;
  if (capture != nullptr) capture->clear();
  auto capture_after = [&](int scatterings, int s) {
    if (capture != nullptr && capture->bounce == scatterings)
      append_bounce_rays(B.path, width, height, s, *capture);
  };

  Stopwatch since_samples;
  // Sample 0's camera rays, traced once more in a resumed frame that asks for AOVs: the
  // camera stage and the first shade stage write them (the film adds nothing).
  const AovStreams aovs = aov_streams(B.aov, &B.albedo);
  if (frame.retrace_aovs()) {
    S_.camera.offset.set(sample_offset(0));
    S_.camera.lens_sample.set(0);
    path_->sample_index.set(0);
    run(K.camera, kCamera, std::nullopt);
    if (geometry && run(K.intersect, kIntersect, alive) > 0) run(K.shade, kShade, alive);
    film.read_aovs(aovs, rs.outputs, r);
  }
  for (int s = frame.first_sample; s < spp; ++s) {
    S_.camera.offset.set(sample_offset(s));
    S_.camera.lens_sample.set(s);
    path_->sample_index.set(s);
    run(K.camera, kCamera, std::nullopt);
    capture_after(0, s);
    // The megakernel's loop takes at most depth + 2 iterations, one bounce each: the camera
    // ray and depth bounces end every path (PathIntegrator::shade), the last is a backstop.
    for (int bounce = 0; bounce < depth + 2; ++bounce) {
      // The paths not done: the intersect stage's count, or without geometry (every ray
      // misses and its path ends) all of them at the first bounce and none after.
      if (geometry) {
        if (run(K.intersect, kIntersect, alive) == 0) break;
      } else if (bounce > 0) {
        break;
      }
      run(K.shade, kShade, alive);
      capture_after(bounce + 1, s);
      if (shadows) run(K.shadow, kShadow, queried);
    }
    Stopwatch reduce;
    r.rays += rill::sum(ints).z;  // on the device: only the total comes back
    r.times.reduce += reduce.ms();
    // Sample 0's AOVs, before the next sample's stages write over them.
    if (s == 0) film.read_aovs(aovs, rs.outputs, r);
    film.add_sample(B.path.field<Float3>("radiance"), s);
    if (!frame.more_after(s)) break;
  }
  finish_passes(film, rs.outputs, r);
  r.trace_ms = since_samples.ms();
}

}  // namespace rt
