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
#include <chrono>
#include <optional>
#include <stdexcept>

#include "rill/rt/multipass/Multipass.h"

#include "rill/Record.h"
#include "rill/Reduce.h"

namespace rt {

using namespace rill;

namespace {

// Trace states (TraceState::state).
constexpr int kNone = 0, kPending = 1, kEnter = 2, kWait = 3, kFinished = 4;
// Path states (PathState::state): ended, alive (a ray to trace or shade), alive with a
// surface to shade (shadow rays and combine).
constexpr int kPathEnded = 0, kPathAlive = 1, kPathSurface = 2;
constexpr int kBatch = 8;               // triangles an intersector pass tests per ray
constexpr double kTailFraction = 0.05;  // fewer rays than this left: one kernel finishes them

}  // namespace

// A pixel's path: its state (kPathEnded...), bounce depth, rays traced, weight and colour.
RILL_STRUCT(PathState, (Int, state), (Int, depth), (Int, rays), (Float, weight), (Float3, color));
// The camera ray's AOVs.
RILL_STRUCT(Aov, (Float, depth), (Int, prim), (Float3, normal));

struct Multipass::Buffers {
  Buffers(int64_t w, int64_t h)
      : ray(w, h, "ray"),
        shadow(w, h, "shadow"),
        hit(w, h, "hit"),
        shadow_hit(w, h, "shadow_hit"),
        tr(w, h, "tr"),
        path(w, h, "path"),
        aov(w, h, "aov"),
        local(w, h, "local") {}
  Stream<Ray> ray, shadow;      // the path's ray; the shadow ray towards the current light
  Stream<Hit> hit, shadow_hit;  // their hits
  Stream<TraceState> tr;        // the traversal of the ray being traced (either)
  Stream<PathState> path;
  Stream<Aov> aov;
  Stream<Float3> local;  // local light at the path's surface
};

Multipass::Multipass(DeviceScene& scene) : S_(scene) {
  if (S_.F.refraction)
    throw std::runtime_error(
        "--strategy multipass: glass (transmit > 0) needs the ray stack of the single kernel; "
        "use --strategy megakernel (the thesis's multipass tracer has no refraction either)");
  capture();
  // Without geometry there is nothing to trace.
  if (!S_.F.geometry) setup_ = traverse_ = intersect_ = Program();
}

void Multipass::capture() {
  const Features& F = S_.F;
  const Intersector& X = S_.intersector;
  const Shading& sh = S_.shading;
  raygen_ = rill::program("mp_raygen", [&] {
    Output<Ray> ray("ray");
    Output<PathState> path("path");
    Output<Aov> aov("aov");
    Output<Int> ts("tr.state");
    Float3 eye = S_.camera.eye;
    ray = Ray{eye, S_.camera.direction(element_coord()), Float(kBig)};
    path = PathState{Int(kPathAlive), Int(0), Int(1), Float(1.0f), Float3(0.0f)};
    aov = Aov{as_float(Int(0x7f800000)), Int(-1), Float3(0.0f)};
    ts = kPending;
  });

  // ---- the trace loop: voxel precalculation, traverser, intersector ----------------------
  // A voxel's cursor (c, end) is a subgrid's entry (base, -m) when end < 0: the intersector
  // walks the whole subgrid in one pass (then the cursor is empty). Generated only when the
  // grid has subgrids.
  auto walk_pending_subgrid = [&](const Float3& o, const RaySteps& r, const Float& t_exit,
                                  const Bool& any_hit, const DdaState& at, Int& c, Int& end,
                                  Hit& best) {
    if (S_.grid.subgrids == 0) return;
    RILL_IF(end < 0) {
      X.walk_subgrid(o, r, t_exit, any_hit, Int2(c, end), at, best);
      c = 0;
      end = 0;
    }
    RILL_ENDIF;
  };
  setup_ = rill::program("mp_voxel_precalc", [&] {
    Input<Ray> ray("ray");
    Input<Int> state("tr.state");
    Output<Int> state_out("tr.state");
    Output<Int3> vout("tr.voxel");
    Output<Float3> tmx_out("tr.t_next");
    Output<Float> exit_out("tr.t_exit");
    Output<Int> steps_out("tr.steps");
    Output<Hit> hit("hit");
    RILL_IF(state != kPending) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Bool inside = false;
    Float t_enter = 0.0f, t_exit = 0.0f;
    X.ray_box(ray, inside, t_enter, t_exit);
    hit = Hit{ray.tmax, Float2(0.0f), Int(-1)};
    steps_out = 0;
    RILL_IF(inside) {
      DdaState st = X.dda_init(ray.o, ray.d, t_enter);
      vout = st.vox;
      state_out = kEnter;
      tmx_out = st.tmx;
      exit_out = t_exit;
    }
    RILL_ELSE {
      vout = Int3(0);
      state_out = kFinished;
      tmx_out = Float3(0.0f);
      exit_out = 0.0f;
    }
    RILL_ENDIF;
  });

  traverse_ = rill::program("mp_traverser", [&] {
    Input<Float3> d("ray.d");
    Input<TraceState> tr("tr");
    Input<Float> hit_t("hit.t");
    Input<Int> hit_id("hit.id");
    Output<Int> state_out("tr.state");
    Output<Int3> vout("tr.voxel");
    Output<Float3> tmx_out("tr.t_next");
    Output<Int> steps_out("tr.steps");
    Output<Int2> cur("tr.cursor");
    RILL_IF(tr.state != kEnter) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    DdaState st{tr.voxel, tr.t_next, tr.steps, Bool(false)};
    Bool any_hit = any_hit_ != 0;
    const RaySteps rs = X.ray_steps(d);  // once, not per step
    const Hit best{hit_t, Float2(0.0f), hit_id};
    Bool found = false;
    Int2 range(0);
    // Empty voxels are stepped over here; leave_voxel's step limit ends the loop.
    RILL_WHILE(!st.done && !found) {
      range = S_.grid.voxel_range(st.vox);
      RILL_IF(range.y() != 0) {  // triangles, or a subgrid
        found = true;
      }
      RILL_ELSE {
        X.leave_voxel(rs, tr.t_exit, best, any_hit, range, st);
      }
      RILL_ENDIF;
    }
    RILL_ENDWHILE;
    state_out = select(found, Int(kWait), Int(kFinished));
    vout = st.vox;
    tmx_out = st.tmx;
    steps_out = st.steps;
    // The cursor over the voxel's list, or a subgrid's entry (base, -m) as it is.
    cur = select(range.y() < 0, range, Int2(range.x(), range.x() + range.y()));
  });

  intersect_ = rill::program("mp_intersector", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<TraceState> tr("tr");
    Input<Hit> hit("hit");
    Output<Int> state_out("tr.state");
    Output<Int3> vout("tr.voxel");
    Output<Float3> tmx_out("tr.t_next");
    Output<Int> steps_out("tr.steps");
    Output<Int2> cur_out("tr.cursor");
    Output<Hit> hit_out("hit");
    RILL_IF(tr.state != kWait) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    const RaySteps rs = X.ray_steps(d);
    Hit best = hit;
    Int c = tr.cursor.x();
    Int end = tr.cursor.y();
    DdaState st{tr.voxel, tr.t_next, tr.steps, Bool(false)};
    Bool any_hit = any_hit_ != 0;
    walk_pending_subgrid(o, rs, tr.t_exit, any_hit, st, c, end, best);
    RILL_FOR(Int k = 0, k < kBatch && c < end, k += 1) {
      X.test_triangle(o, d, c, best);
      c += 1;
    }
    RILL_ENDFOR;
    Int state = kWait;
    RILL_IF(c >= end) {  // the voxel's list is done
      // A voxel with triangles: a plain step.
      X.leave_voxel(rs, tr.t_exit, best, any_hit, Int2(0), st);
      state = select(st.done, Int(kFinished), Int(kEnter));
    }
    RILL_ENDIF;
    state_out = state;
    vout = st.vox;
    tmx_out = st.tmx;
    steps_out = st.steps;
    cur_out = Int2(c, end);
    hit_out = best;
  });

  // The tail: the last few rays run traverser and intersector steps in one loop (the same
  // steps in the same order, so the same result), instead of many nearly empty passes. It
  // writes the state and the hit only: nothing reads a finished ray's voxel or steps.
  finish_ = rill::program("mp_finish", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<TraceState> tr("tr");
    Input<Hit> hit("hit");
    Output<Int> state_out("tr.state");
    Output<Hit> hit_out("hit");
    Int state = tr.state;
    RILL_IF(state != kEnter && state != kWait) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    const RaySteps rs = X.ray_steps(d);
    Hit best = hit;
    Int c = tr.cursor.x();
    Int end = tr.cursor.y();
    DdaState st{tr.voxel, tr.t_next, tr.steps, Bool(false)};
    Bool any_hit = any_hit_ != 0;
    Int2 entry(0);  // a resumed voxel (kWait) has triangles: a plain step after it
    RILL_WHILE(state != kFinished) {
      RILL_IF(state == kEnter) {
        entry = S_.grid.voxel_range(st.vox);
        c = entry.x();
        end = select(entry.y() < 0, entry.y(), entry.x() + entry.y());
      }
      RILL_ENDIF;
      // A subgrid entered here or by the traverser.
      walk_pending_subgrid(o, rs, tr.t_exit, any_hit, st, c, end, best);
      RILL_WHILE(c < end) {
        X.test_triangle(o, d, c, best);
        c += 1;
      }
      RILL_ENDWHILE;
      st.done = false;
      X.leave_voxel(rs, tr.t_exit, best, any_hit, entry, st);
      state = select(st.done, Int(kFinished), Int(kEnter));
    }
    RILL_ENDWHILE;
    state_out = kFinished;
    hit_out = best;
  });

  // ---- shading ---------------------------------------------------------------------------
  surface_ = rill::program("mp_surface", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<Int> state("path.state");
    Input<Int> depth("path.depth");
    Input<Float> w("path.weight");
    Input<Float3> color("path.color");
    Output<Float3> local("local");
    Output<Float3> color_out("path.color");
    Output<Int> state_out("path.state");
    Output<Aov> aov("aov");
    RILL_IF(state == kPathEnded) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Int hid = -1;
    if (F.geometry) hid = hit.id;
    RILL_IF(hid >= 0) {
      Surface s = sh.surface(Ray{o, d, Float(kBig)}, Hit{hit.t, hit.uv, hid});
      Float3 loc = sh.emitted(s);
      RILL_IF(depth == 0) {  // AOVs of the camera ray
        aov = Aov{hit.t, hid, s.ns};
      }
      RILL_ENDIF;
      if (!F.shadows) loc += sh.unshadowed_light(s);
      local = loc;
      state_out = kPathSurface;
    }
    RILL_ELSE {
      color_out = color + w * sh.background;
      state_out = kPathEnded;
    }
    RILL_ENDIF;
  });

  if (F.shadows) {
    shadow_gen_ = rill::program("mp_shadow_rays", [&] {
      Input<Float3> o("ray.o");
      Input<Float3> d("ray.d");
      Input<Hit> hit("hit");
      Input<Int> state("path.state");
      Input<Int> rays("path.rays");
      Output<Ray> shadow("shadow");
      Output<Int> ts("tr.state");
      Output<Int> rays_out("path.rays");
      RILL_IF(state != kPathSurface) {
        RILL_DISCARD;
      }
      RILL_ENDIF;
      Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
      Bool active = false;
      shadow = sh.shadow_ray(light_, s, active);
      ts = select(active, Int(kPending), Int(kNone));
      rays_out = rays + select(active, Int(1), Int(0));
    });
    shadow_acc_ = rill::program("mp_shadow_light", [&] {
      Input<Float3> o("ray.o");
      Input<Float3> d("ray.d");
      Input<Hit> hit("hit");
      Input<Int> state("path.state");
      Input<Int> ts("tr.state");
      Input<Int> sid("shadow_hit.id");
      Input<Float3> local("local");
      Output<Float3> local_out("local");
      RILL_IF(state != kPathSurface || ts != kFinished || sid >= 0) {
        RILL_DISCARD;
      }
      RILL_ENDIF;
      Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
      local_out = local + sh.light(light_, s);
    });
  }

  // The path's ray keeps tmax = kBig from the ray generator: combine writes o and d only.
  combine_ = rill::program("mp_combine", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<Hit> hit("hit");
    Input<PathState> path("path");
    Input<Float3> local("local");
    Output<PathState> path_out("path");
    Output<Float3> o_out("ray.o");
    Output<Float3> d_out("ray.d");
    Output<Int> ts("tr.state");
    RILL_IF(path.state != kPathSurface) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Surface s = sh.surface(Ray{o, d, Float(kBig)}, hit);
    Float3 c = path.color;
    Float weight = path.weight;
    Int depth = path.depth;
    Ray next{Float3(0.0f), Float3(0.0f), Float(kBig)};
    Bool go = false;
    sh.shade(s, local, c, weight, depth, next, go, nullptr);
    RILL_IF(go) {
      o_out = next.o;
      d_out = next.d;
      ts = kPending;
    }
    RILL_ENDIF;
    path_out = PathState{select(go, Int(kPathAlive), Int(kPathEnded)), depth,
                         path.rays + select(go, Int(1), Int(0)), weight, c};
  });
}

Multipass::Kernels& Multipass::kernels(const std::string& backend, Accuracy a) {
  const std::string key = backend + "/" + accuracy_name(a);
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

RenderResult Multipass::render(const RenderSettings& rs, int width, int height, int depth,
                               int spp) {
  const Features& F = S_.F;
  RenderResult r;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  const auto t0 = std::chrono::steady_clock::now();
  Backend& be = backend(rs.backend);
  if (std::string why = be.unavailable_reason(); !why.empty())
    throw std::runtime_error("backend " + rs.backend + " cannot run here: " + why);
  if (!be.supports(rs.accuracy))
    throw std::runtime_error(std::string("backend ") + rs.backend + " has no " +
                             accuracy_name(rs.accuracy) + " accuracy mode");
  Kernels& K = kernels(rs.backend, rs.accuracy);
  r.from_cache = K.raygen.info().cache_hit || K.raygen.info().from_disk_cache;
  for (const Kernel* k : {&K.raygen, &K.setup, &K.traverse, &K.intersect, &K.finish, &K.surface,
                          &K.shadow_gen, &K.shadow_acc, &K.combine})
    if (!k->backend_name().empty()) add_stages(r, k->info());

  S_.shading.max_depth.set(depth);
  Buffers B(width, height);
  // The ray count is a reduction on the device (rill::sum): its kernels compile here, not in
  // the first sample's trace time.
  const Stream<Int> path_rays = B.path.field<Int>("rays");
  (void)rill::sum(path_rays, rs.backend);
  r.compile_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

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

  int64_t launches = 0;
  // Runs one pass, masked to the elements in `state` when masking is on.
  auto run = [&](Kernel& k, Pass pass, const std::optional<rill::StateMask>& mask) {
    ++launches;
    const auto t = std::chrono::steady_clock::now();
    const int64_t written = mask && rs.masking ? k.execute(*mask) : k.execute();
    PassStats& st = r.passes[static_cast<size_t>(pass)];
    st.ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
    ++st.calls;
    st.processed += k.last_launch().processed;
    st.written += written;
    return written;
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

  const size_t npix = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<glm::dvec3> sum(spp > 1 ? npix : 0, glm::dvec3(0.0));
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
  const auto start = std::chrono::steady_clock::now();
  for (int sample = 0; sample < spp; ++sample) {
    S_.camera.offset.set(sample_offset(sample));
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
    r.rays += rill::sum(path_rays);
    std::vector<glm::vec3> c = B.path.field<Float3>("color").download();
    if (sample == 0) {
      r.color = c;
      r.depth = B.aov.field<Float>("depth").download();
      r.prim = B.aov.field<Int>("prim").download();
      r.normal = B.aov.field<Float3>("normal").download();
    }
    if (spp > 1)
      for (size_t p = 0; p < npix; ++p) sum[p] += glm::dvec3(c[p]);
  }
  if (spp > 1)
    for (size_t p = 0; p < npix; ++p) r.color[p] = glm::vec3(sum[p] / static_cast<double>(spp));
  r.launches = launches;
  r.trace_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace rt
