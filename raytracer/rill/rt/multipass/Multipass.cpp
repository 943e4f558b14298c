// The thesis's multipass strategy (sections 5.4-5.6): a sequence of small kernels over
// per-pixel state streams instead of one kernel with a loop.
//
//   ray generator    camera rays; the path state (colour, weight, depth)
//   voxel precalc    the ray against the grid's box, the entry voxel and tMax   (per trace)
//   traverser        active rays step through empty voxels to the next non-empty one,
//                    which puts them in the wait state (or they leave: finished)
//   intersector      waiting rays test the next few triangles of their voxel; after the
//                    last one they are done (hit within the voxel) or active again
//   surface          hit: shading state and AOVs; miss: background, the path ends
//   shadow gen/acc   per light: a shadow ray, traced like the others, then its Phong term
//   combine          eq. 5.1 and the reflected ray of the next bounce
//
// The per-pixel state lives in streams of records (Record.h), one stream per field: the ray
// (Ray), its closest hit (Hit), its traversal state (TraceState) and the path (PathState),
// plus the camera ray's AOVs (Aov). Every kernel names what it reads and writes ("tr.state",
// "hit", ...) and is bound by those names (Kernel::bind_fields), never by position.
//
// Traverser and intersector run in a host loop until neither has a ray left; the
// intersector runs again while at least 20% of the rays wait for it (thesis 5.6; the
// fraction is RenderSettings::wait_threshold, `--wait-threshold`), and when fewer than 5%
// are left, one kernel takes them to the end (the same steps in a loop). Every kernel
// discards the elements it has nothing to do for, so execute() counts the rays in each
// state. Masking (RenderSettings::masking, `--masking on|off`): each kernel is launched with
// rill::where() on a state field (tr.state: the ray's trace state; path.state: the path's),
// so the backend skips the other elements before running the body (GLSL: early stencil
// test, the thesis's early-z culling). The discards stay, so masking on and off give the
// same bits. Built from the same DSL functions as the single kernel, it gives the same bits
// (tested); glass (refraction) is left to the single kernel, as in the thesis (5.2.2).
//
// The kernels read only the fields they use and write only the fields they change: on GLSL
// every input and output is a texture unit, and a kernel with more outputs than draw buffers
// (8 on Mesa) is drawn once per group of outputs.
#include <optional>
#include <stdexcept>

#include "rill/rt/multipass/Multipass.h"
#include "rill/rt/multipass/States.h"

#include "rill/Record.h"
#include "rill/Reduce.h"
#include "rill/Stopwatch.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/PerBackend.h"

namespace rt {

using namespace rill;

using namespace mp;

struct Multipass::Buffers {
  Buffers(int w, int h)
      : ray(w, h, "ray"),
        shadow(w, h, "shadow"),
        hit(w, h, "hit"),
        shadow_hit(w, h, "shadow_hit"),
        tr(w, h, "tr"),
        path(w, h, "path"),
        aov(w, h, "aov"),
        local(w, h, "local"),
        width(w),
        height(h) {}            // shape of every stream (PerBackend.h: buffers_for)
  Stream<Ray> ray, shadow;      // the path's ray; the shadow ray towards the current light
  Stream<Hit> hit, shadow_hit;  // their hits
  Stream<TraceState> tr;        // the traversal of the ray being traced (either)
  Stream<PathState> path;
  Stream<Aov> aov;
  Stream<Float3> local;  // local light at the path's surface
  int width, height;
};

Multipass::Multipass(DeviceScene& scene) : S_(scene) {
  // Its passes are Whitted's (surface, a shadow ray per light, combine): under the path
  // integrator they would render another image than the one asked for.
  if (S_.options.integrator == Integrator::Path)
    throw std::runtime_error(
        "--strategy multipass runs the Whitted tracer, not the path integrator; use "
        "--strategy megakernel or wavefront for the path integrator");
  // Its shadow passes are per point light (a light index per pass, the light buffer's), and
  // the surface pass has no random numbers: Whitted's area lights are the megakernel's.
  if (S_.F.area_lights)
    throw std::runtime_error(
        "--strategy multipass: emitting materials are area lights under Whitted, sampled with "
        "random shadow rays (options.light_samples) that only the megakernel traces; use "
        "--strategy megakernel");
  if (S_.F.refraction)
    throw std::runtime_error(
        "--strategy multipass: glass (transmit > 0) needs the ray stack of the single kernel; "
        "use --strategy megakernel (the thesis's multipass tracer has no refraction either)");
  raygen_ = capture_raygen();
  if (S_.F.geometry) {  // without geometry there is nothing to trace
    setup_ = capture_setup();
    traverse_ = capture_traverse();
    intersect_ = capture_intersect();
    finish_ = capture_finish();
  }
  surface_ = capture_surface();
  if (S_.F.shadows) {
    shadow_gen_ = capture_shadow_gen();
    shadow_acc_ = capture_shadow_acc();
  }
  combine_ = capture_combine();
}

Multipass::~Multipass() = default;

Multipass::Kernels& Multipass::kernels(const std::string& backend, Accuracy a) {
  const std::string key = backend_key(backend, a);
  auto it = compiled_.find(key);
  if (it != compiled_.end()) return it->second;
  CompileOptions opt;
  opt.accuracy = a;
  Kernels k;
  // The passes' kernels are independent: compiled together, the C compiler runs on every
  // core (about 2x faster on two cores than one after another).
  std::vector<std::pair<Kernel*, const Program*>> wanted{
      {&k.raygen, &raygen_}, {&k.surface, &surface_}, {&k.combine, &combine_}};
  if (setup_.valid())
    wanted.insert(wanted.end(), {{&k.setup, &setup_},
                                 {&k.traverse, &traverse_},
                                 {&k.intersect, &intersect_},
                                 {&k.finish, &finish_}});
  if (shadow_gen_.valid())
    wanted.insert(wanted.end(), {{&k.shadow_gen, &shadow_gen_}, {&k.shadow_acc, &shadow_acc_}});
  std::vector<CompileRequest> requests;
  for (const auto& [kernel, program] : wanted) requests.push_back({*program, backend, opt});
  std::vector<Kernel> built = compile_all(requests);
  for (size_t i = 0; i < wanted.size(); ++i) *wanted[i].first = std::move(built[i]);
  return compiled_.emplace(key, std::move(k)).first->second;
}

void Multipass::render(const Frame& frame, RenderResult& r) {
  const RenderSettings& rs = frame.settings;
  const int width = frame.width, height = frame.height, depth = frame.depth, spp = frame.spp;
  Film& film = frame.film;
  const Features& F = S_.F;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  Stopwatch since_start;
  check_backend(rs.backend, rs.accuracy);
  Kernels& K = kernels(rs.backend, rs.accuracy);
  r.from_cache = K.raygen.info().cache_hit || K.raygen.info().from_disk_cache;
  for (const Kernel* k : {&K.raygen, &K.setup, &K.traverse, &K.intersect, &K.finish, &K.surface,
                          &K.shadow_gen, &K.shadow_acc, &K.combine})
    if (!k->backend_name().empty()) add_stages(r, k->info());

  S_.shading.max_depth.set(depth);
  Stopwatch setup;
  Buffers& B = buffers_for(buffers_, backend_key(rs.backend, rs.accuracy), width, height);
  film.begin(rs.backend, rs.accuracy, width, height, spp, rs.resume, frame.summing(),
             rs.outputs.variance);
  r.times.setup = setup.ms();
  // The ray count is a reduction on the device (rill::sum): its kernels compile here, not in
  // the first sample's trace time.
  const Stream<Int> path_rays = B.path.field<Int>("rays");
  (void)rill::sum(path_rays, rs.backend);
  r.compile_ms = since_start.ms() - r.times.setup;

  if (!(rs.wait_threshold > 0.0 && rs.wait_threshold <= 1.0))
    throw std::runtime_error("multipass: the wait threshold must be in (0, 1] (got " +
                             std::to_string(rs.wait_threshold) + ")");
  // Per-pass statistics, in the order the passes first run.
  enum Pass {
    kRaygen,
    kSetup,
    kTraverse,
    kIntersect,
    kFinish,
    kSurface,
    kShadowGen,
    kShadowAcc,
    kCombine,
    kPasses
  };
  static const char* const kPassNames[kPasses] = {"raygen",      "voxel_precalc", "traverser",
                                                  "intersector", "finish",        "surface",
                                                  "shadow_rays", "shadow_light",  "combine"};
  r.passes.assign(kPasses, PassStats{});
  for (int p = 0; p < kPasses; ++p) r.passes[static_cast<size_t>(p)].name = kPassNames[p];

  // Runs one pass, masked to the elements in `state` when masking is on.
  auto run = [&](Kernel& k, Pass pass, const std::optional<rill::StateMask>& mask) {
    return run_pass(k, rs.masking ? mask : std::nullopt, r.passes[static_cast<size_t>(pass)], r);
  };
  // The state fields the launches are masked on.
  const Stream<Int> tr_state = B.tr.field<Int>("state");
  const Stream<Int> path_state = B.path.field<Int>("state");
  // Traces the rays of `ray` whose trace state is pending; the hits go to `hit`.
  auto trace = [&](const Stream<Ray>& ray, const Stream<Hit>& hit, bool any_hit) {
    any_hit_.set(any_hit ? 1 : 0);
    for (Kernel* k : {&K.setup, &K.traverse, &K.intersect, &K.finish})
      k->bind_fields("ray", ray).bind_fields("hit", hit).bind_fields("tr", B.tr);
    const double n = static_cast<double>(run(K.setup, kSetup, where(tr_state, kPending)));
    for (int64_t pass = 0; n > 0; ++pass) {
      if (pass > 100000000) throw std::runtime_error("multipass: the trace loop does not end");
      const int64_t active = run(K.traverse, kTraverse, where(tr_state, kEnter));
      auto intersect = [&] { return run(K.intersect, kIntersect, where(tr_state, kWait)); };
      int64_t waiting = intersect();
      while (static_cast<double>(waiting) >= rs.wait_threshold * n) waiting = intersect();
      if (active == 0 && waiting == 0) break;
      if (static_cast<double>(active + waiting) < kTailFraction * n) {
        run(K.finish, kFinish, where(tr_state, {kEnter, kWait}));
        break;
      }
    }
  };

  // The shading kernels bind the record fields they declare, by name (the trace kernels
  // are bound per trace, above).
  K.raygen.bind_fields("ray", B.ray).bind_fields("path", B.path).bind_fields("aov", B.aov);
  K.raygen.bind_fields("tr", B.tr);
  K.surface.bind_fields("ray", B.ray).bind_fields("hit", B.hit).bind_fields("path", B.path);
  K.surface.bind_fields("aov", B.aov).bind("local", B.local);
  K.combine.bind_fields("ray", B.ray).bind_fields("hit", B.hit).bind_fields("path", B.path);
  K.combine.bind_fields("tr", B.tr).bind("local", B.local);
  if (F.shadows) {
    K.shadow_gen.bind_fields("ray", B.ray).bind_fields("hit", B.hit).bind_fields("path", B.path);
    K.shadow_gen.bind_fields("shadow", B.shadow).bind_fields("tr", B.tr);
    K.shadow_acc.bind_fields("ray", B.ray).bind_fields("hit", B.hit).bind_fields("path", B.path);
    K.shadow_acc.bind_fields("tr", B.tr).bind_fields("shadow_hit", B.shadow_hit);
    K.shadow_acc.bind("local", B.local);
  }
  Stopwatch since_samples;
  // Sample 0's camera rays, traced once more in a resumed frame that asks for AOVs: the
  // surface pass of the first bounce writes them (the film adds nothing).
  const AovStreams aovs = aov_streams(B.aov);
  if (frame.retrace_aovs()) {
    S_.camera.offset.set(sample_offset(0));
    S_.camera.lens_sample.set(0);
    run(K.raygen, kRaygen, std::nullopt);
    if (F.geometry) trace(B.ray, B.hit, false);
    run(K.surface, kSurface, where(path_state, {kPathAlive, kPathSurface}));
    film.read_aovs(aovs, rs.outputs, r);
  }
  for (int sample = frame.first_sample; sample < spp; ++sample) {
    S_.camera.offset.set(sample_offset(sample));
    S_.camera.lens_sample.set(sample);
    run(K.raygen, kRaygen, std::nullopt);
    const rill::StateMask with_surface = where(path_state, kPathSurface);
    for (int bounce = 0; bounce <= depth; ++bounce) {
      if (F.geometry) trace(B.ray, B.hit, false);
      if (run(K.surface, kSurface, where(path_state, {kPathAlive, kPathSurface})) == 0) break;
      if (F.shadows) {
        for (int l = 0; l < S_.light_count; ++l) {
          light_.set(static_cast<int32_t>(l));
          run(K.shadow_gen, kShadowGen, with_surface);
          trace(B.shadow, B.shadow_hit, true);
          run(K.shadow_acc, kShadowAcc, with_surface);
        }
      }
      run(K.combine, kCombine, with_surface);
    }
    Stopwatch reduce;
    r.rays += rill::sum(path_rays);
    r.times.reduce += reduce.ms();
    // Sample 0's AOVs, before the next sample's passes write over them.
    if (sample == 0) film.read_aovs(aovs, rs.outputs, r);
    film.add_sample(B.path.field<Float3>("color"), sample);
    if (!frame.more_after(sample)) break;
  }
  finish_passes(film, rs.outputs, r);
  r.trace_ms = since_samples.ms();
}

}  // namespace rt
