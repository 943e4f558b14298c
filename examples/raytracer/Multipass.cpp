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
// Traverser and intersector run in a host loop until neither has a ray left; the
// intersector runs again while at least 20% of the rays wait for it (thesis 5.6; the
// fraction is RenderSettings::wait_threshold, `--wait-threshold`), and when fewer than 5%
// are left, one kernel takes them to the end (the same steps in a loop). Every kernel
// discards the elements it has nothing to do for, so execute() counts the rays in each
// state. Masking (RenderSettings::masking, `--masking on|off`): two Int state streams
// mirror the states kept in tr_vox.w and path_i (tr_state: the ray's trace state;
// path_state: 0 path ended, 1 alive, 2 alive with a surface to shade), and each kernel is
// launched with rill::where() on its state, so the backend skips the other elements before
// running the body (GLSL: early stencil test, the thesis's early-z culling). The discards
// stay, so masking on and off give the same bits. Built from the same DSL functions as the
// single kernel, it gives the same bits (tested); glass (refraction) is left to the single
// kernel, as in the thesis (5.2.2).
#include <chrono>
#include <optional>

#include "TracerImpl.h"

namespace rt {

namespace {

// Ray states, in the low 3 bits of tr_vox.w; bit 3: any-hit (shadow) ray; bits 4-: steps.
constexpr int kNone = 0, kPending = 1, kEnter = 2, kWait = 3, kFinished = 4;
constexpr int kAnyHit = 8;
// Path states (path_state), for masking the shading kernels.
constexpr int kPathEnded = 0, kPathAlive = 1, kPathSurface = 2;
constexpr int kBatch = 8;               // triangles an intersector pass tests per ray
constexpr double kTailFraction = 0.05;  // fewer rays than this left: one kernel finishes them

}  // namespace

struct Multipass {
  Uniform<Int> light{0, "light_index"};
  Program raygen, setup, traverse, intersect, finish, surface, shadow_gen, shadow_acc, combine;

  struct Kernels {
    Kernel raygen, setup, traverse, intersect, finish, surface, shadow_gen, shadow_acc, combine;
  };
  std::map<std::string, Kernels> compiled;

  struct Buffers {
    Buffers(int64_t w, int64_t h)
        : ray_o(w, h),
          sh_o(w, h),
          tr_tmx(w, h),
          ray_d(w, h),
          hit_tuv(w, h),
          sh_d(w, h),
          sh_tuv(w, h),
          color(w, h),
          local(w, h),
          aov_normal(w, h),
          hit_id(w, h),
          sh_id(w, h),
          aov_prim(w, h),
          tr_vox(w, h),
          path_i(w, h),
          tr_cur(w, h),
          path_w(w, h),
          aov_depth(w, h),
          tr_state(w, h),
          path_state(w, h) {}
    Stream<Float4> ray_o, sh_o, tr_tmx;
    Stream<Float3> ray_d, hit_tuv, sh_d, sh_tuv, color, local, aov_normal;
    Stream<Int> hit_id, sh_id, aov_prim;
    Stream<Int4> tr_vox, path_i;  // path_i: depth, alive, rays, has a surface
    Stream<Int2> tr_cur;
    Stream<Float> path_w, aov_depth;
    Stream<Int> tr_state, path_state;  // masks: tr_vox.w & 7 and the path's state (above)
  };

  void capture(const Tracer::Impl& I);
  Kernels& kernels(const std::string& backend, Accuracy a);
};

void Multipass::capture(const Tracer::Impl& I) {
  const Features& F = I.F;
  raygen = rill::program("mp_raygen", [&] {
    Output<Float4> o("ray_o");
    Output<Float3> d("ray_d");
    Output<Int4> vox("tr_vox");
    Output<Float> w("path_w");
    Output<Int4> pi("path_i");
    Output<Float3> color("color");
    Output<Float> ad("aov_depth");
    Output<Int> ap("aov_prim");
    Output<Float3> an("aov_normal");
    Output<Int> ts("tr_state");
    Output<Int> ps("path_state");
    Float3 eye = I.eye;
    o = Float4(eye, kBig);
    d = I.camera_ray(element_coord());
    vox = Int4(0, 0, 0, kPending);
    w = 1.0f;
    pi = Int4(0, 1, 1, 0);
    color = Float3(0.0f);
    ad = as_float(Int(0x7f800000));
    ap = -1;
    an = Float3(0.0f);
    ts = kPending;
    ps = kPathAlive;
  });

  // ---- the trace loop: voxel precalculation, traverser, intersector ----------------------
  // A voxel's cursor (c, end) is a subgrid's entry (base, -m) when end < 0: the intersector
  // walks the whole subgrid in one pass (then the cursor is empty). Generated only when the
  // grid has subgrids.
  auto walk_pending_subgrid = [&](const Float3& o, const RaySteps& r, const Float& t_exit,
                                  const Bool& any_hit, const Int3& vox, const Float3& tmx, Int& c,
                                  Int& end, Float& best_t, Int& best_id, Float& best_u,
                                  Float& best_v) {
    if (I.grid.subgrids == 0) return;
    RILL_IF(end < 0) {
      I.walk_subgrid(o, r, t_exit, any_hit, Int2(c, end), vox, tmx, best_t, best_id, best_u,
                     best_v);
      c = 0;
      end = 0;
    }
    RILL_ENDIF;
  };
  setup = rill::program("mp_voxel_precalc", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Int4> vin("tr_vox");
    Output<Int4> vout("tr_vox_out");
    Output<Float4> tout("tr_tmx");
    Output<Float3> tuv("hit_tuv");
    Output<Int> id("hit_id");
    Output<Int> ts("tr_state");
    Int w = vin.w();
    RILL_IF((w & 7) != kPending) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Float3 o = o4(0, 1, 2);
    Float tmax = o4.w();
    Bool inside = false;
    Float t_enter = 0.0f, t_exit = 0.0f;
    I.ray_box(o, d, tmax, inside, t_enter, t_exit);
    tuv = Float3(tmax, 0.0f, 0.0f);
    id = -1;
    RILL_IF(inside) {
      Int3 vox(0);
      Float3 tmx(0.0f);
      I.dda_init(o, d, t_enter, vox, tmx);
      vout = Int4(vox, (w & kAnyHit) | kEnter);
      ts = kEnter;
      tout = Float4(tmx, t_exit);
    }
    RILL_ELSE {
      vout = Int4(0, 0, 0, (w & kAnyHit) | kFinished);
      ts = kFinished;
      tout = Float4(0.0f);
    }
    RILL_ENDIF;
  });

  traverse = rill::program("mp_traverser", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Int4> vin("tr_vox");
    Input<Float4> tin("tr_tmx");
    Input<Float3> tuv("hit_tuv");
    Input<Int> id("hit_id");
    Output<Int4> vout("tr_vox_out");
    Output<Float4> tout("tr_tmx_out");
    Output<Int2> cur("tr_cur");
    Output<Int> ts("tr_state");
    Int w = vin.w();
    RILL_IF((w & 7) != kEnter) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Int3 vox = vin(0, 1, 2);
    Float3 tmx = tin(0, 1, 2);
    Float t_exit = tin.w();
    Int steps = w >> 4;
    Bool any_hit = (w & kAnyHit) != 0;
    const RaySteps rs = I.ray_steps(d);  // once, not per step
    Float best_t = tuv.x();
    Int best_id = id;
    Bool done = false, found = false;
    Int2 range(0);
    // Empty voxels are stepped over here; leave_voxel's step limit ends the loop.
    RILL_WHILE(!done && !found) {
      range = I.voxel_range(vox);
      RILL_IF(range.y() != 0) {  // triangles, or a subgrid
        found = true;
      }
      RILL_ELSE {
        I.leave_voxel(rs, t_exit, best_t, best_id, any_hit, range, vox, tmx, steps, done);
      }
      RILL_ENDIF;
    }
    RILL_ENDWHILE;
    vout = Int4(vox, select(found, Int(kWait), Int(kFinished)) | (w & kAnyHit) | (steps << 4));
    ts = select(found, Int(kWait), Int(kFinished));
    tout = Float4(tmx, t_exit);
    // The cursor over the voxel's list, or a subgrid's entry (base, -m) as it is.
    cur = select(range.y() < 0, range, Int2(range.x(), range.x() + range.y()));
  });

  intersect = rill::program("mp_intersector", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Int4> vin("tr_vox");
    Input<Float4> tin("tr_tmx");
    Input<Int2> cin("tr_cur");
    Input<Float3> tuv_in("hit_tuv");
    Input<Int> id_in("hit_id");
    Output<Int4> vout("tr_vox_out");
    Output<Float4> tout("tr_tmx_out");
    Output<Int2> cout("tr_cur_out");
    Output<Float3> tuv("hit_tuv_out");
    Output<Int> id("hit_id_out");
    Output<Int> ts("tr_state_out");
    Int w = vin.w();
    RILL_IF((w & 7) != kWait) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Float3 o = o4(0, 1, 2);
    const RaySteps rs = I.ray_steps(d);
    Float best_t = tuv_in.x(), best_u = tuv_in.y(), best_v = tuv_in.z();
    Int best_id = id_in;
    Int c = cin.x();
    Int end = cin.y();
    Int3 vox = vin(0, 1, 2);
    Float3 tmx = tin(0, 1, 2);
    walk_pending_subgrid(o, rs, tin.w(), (w & kAnyHit) != 0, vox, tmx, c, end, best_t, best_id,
                         best_u, best_v);
    RILL_FOR(Int k = 0, k < kBatch && c < end, k += 1) {
      I.test_triangle(o, d, c, best_t, best_id, best_u, best_v);
      c += 1;
    }
    RILL_ENDFOR;
    Int state = kWait;
    Int steps = w >> 4;
    RILL_IF(c >= end) {  // the voxel's list is done
      Bool done = false;
      // A voxel with triangles: a plain step.
      I.leave_voxel(rs, tin.w(), best_t, best_id, (w & kAnyHit) != 0, Int2(0), vox, tmx, steps,
                    done);
      state = select(done, Int(kFinished), Int(kEnter));
    }
    RILL_ENDIF;
    vout = Int4(vox, state | (w & kAnyHit) | (steps << 4));
    ts = state;
    tout = Float4(tmx, tin.w());
    cout = Int2(c, end);
    tuv = Float3(best_t, best_u, best_v);
    id = best_id;
  });

  // The tail: the last few rays run traverser and intersector steps in one loop (the same
  // steps in the same order, so the same result), instead of many nearly empty passes.
  finish = rill::program("mp_finish", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Int4> vin("tr_vox");
    Input<Float4> tin("tr_tmx");
    Input<Int2> cin("tr_cur");
    Input<Float3> tuv_in("hit_tuv");
    Input<Int> id_in("hit_id");
    Output<Int4> vout("tr_vox_out");
    Output<Float3> tuv("hit_tuv_out");
    Output<Int> id("hit_id_out");
    Output<Int> ts("tr_state_out");
    Int w = vin.w();
    Int state = w & 7;
    RILL_IF(state != kEnter && state != kWait) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Float3 o = o4(0, 1, 2);
    const RaySteps rs = I.ray_steps(d);
    Float best_t = tuv_in.x(), best_u = tuv_in.y(), best_v = tuv_in.z();
    Int best_id = id_in;
    Int c = cin.x();
    Int end = cin.y();
    Int3 vox = vin(0, 1, 2);
    Float3 tmx = tin(0, 1, 2);
    Int steps = w >> 4;
    Bool any_hit = (w & kAnyHit) != 0;
    Int2 entry(0);  // a resumed voxel (kWait) has triangles: a plain step after it
    RILL_WHILE(state != kFinished) {
      RILL_IF(state == kEnter) {
        entry = I.voxel_range(vox);
        c = entry.x();
        end = select(entry.y() < 0, entry.y(), entry.x() + entry.y());
      }
      RILL_ENDIF;
      // A subgrid entered here or by the traverser.
      walk_pending_subgrid(o, rs, tin.w(), any_hit, vox, tmx, c, end, best_t, best_id, best_u,
                           best_v);
      RILL_WHILE(c < end) {
        I.test_triangle(o, d, c, best_t, best_id, best_u, best_v);
        c += 1;
      }
      RILL_ENDWHILE;
      Bool done = false;
      I.leave_voxel(rs, tin.w(), best_t, best_id, any_hit, entry, vox, tmx, steps, done);
      state = select(done, Int(kFinished), Int(kEnter));
    }
    RILL_ENDWHILE;
    vout = Int4(vox, kFinished | (w & kAnyHit) | (steps << 4));
    ts = kFinished;
    tuv = Float3(best_t, best_u, best_v);
    id = best_id;
  });

  // ---- shading ---------------------------------------------------------------------------
  surface = rill::program("mp_surface", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Float3> tuv("hit_tuv");
    Input<Int> id("hit_id");
    Input<Float> w("path_w");
    Input<Int4> pi("path_i");
    Input<Float3> color("color");
    Output<Float3> local("local");
    Output<Float3> color_out("color_out");
    Output<Int4> pi_out("path_i_out");
    Output<Float> ad("aov_depth");
    Output<Int> ap("aov_prim");
    Output<Float3> an("aov_normal");
    Output<Int> ps("path_state");
    RILL_IF(pi.y() == 0) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Int hid = -1;
    if (F.geometry) hid = id;
    RILL_IF(hid >= 0) {
      Surface s;
      I.surface(o4(0, 1, 2), d, tuv.x(), hid, tuv.y(), tuv.z(), s);
      Float3 loc = I.ambient * s.kd;
      RILL_IF(pi.x() == 0) {  // AOVs of the camera ray
        ad = tuv.x();
        ap = hid;
        an = s.ns;
      }
      RILL_ENDIF;
      if (!F.shadows) loc += I.unshadowed_light(s);
      local = loc;
      pi_out = Int4(pi.x(), 1, pi.z(), 1);
      ps = kPathSurface;
    }
    RILL_ELSE {
      color_out = color + w * I.background;
      pi_out = Int4(pi.x(), 0, pi.z(), 0);
      ps = kPathEnded;
    }
    RILL_ENDIF;
  });

  if (F.shadows) {
    shadow_gen = rill::program("mp_shadow_rays", [&] {
      Input<Float4> o4("ray_o");
      Input<Float3> d("ray_d");
      Input<Float3> tuv("hit_tuv");
      Input<Int> id("hit_id");
      Input<Int4> pi("path_i");
      Output<Float4> so("shadow_o");
      Output<Float3> sd("shadow_d");
      Output<Int4> vox("tr_vox");
      Output<Int4> pi_out("path_i_out");
      Output<Int> ts("tr_state");
      RILL_IF(pi.y() == 0 || pi.w() == 0) {
        RILL_DISCARD;
      }
      RILL_ENDIF;
      Surface s;
      I.surface(o4(0, 1, 2), d, tuv.x(), id, tuv.y(), tuv.z(), s);
      Float3 ro(0.0f), rd(0.0f);
      Float tmax = 0.0f;
      Bool active = false;
      I.shadow_ray(light, s, ro, rd, tmax, active);
      so = Float4(ro, tmax);
      sd = rd;
      vox = Int4(0, 0, 0, select(active, Int(kPending | kAnyHit), Int(kNone)));
      ts = select(active, Int(kPending), Int(kNone));
      pi_out = Int4(pi.x(), pi.y(), pi.z() + select(active, Int(1), Int(0)), pi.w());
    });
    shadow_acc = rill::program("mp_shadow_light", [&] {
      Input<Float4> o4("ray_o");
      Input<Float3> d("ray_d");
      Input<Float3> tuv("hit_tuv");
      Input<Int> id("hit_id");
      Input<Int4> pi("path_i");
      Input<Int4> vox("tr_vox");
      Input<Int> sid("shadow_id");
      Input<Float3> local("local");
      Output<Float3> local_out("local_out");
      RILL_IF(pi.y() == 0 || pi.w() == 0 || (vox.w() & 7) != kFinished || sid >= 0) {
        RILL_DISCARD;
      }
      RILL_ENDIF;
      Surface s;
      I.surface(o4(0, 1, 2), d, tuv.x(), id, tuv.y(), tuv.z(), s);
      local_out = local + I.phong(light, s);
    });
  }

  combine = rill::program("mp_combine", [&] {
    Input<Float4> o4("ray_o");
    Input<Float3> d("ray_d");
    Input<Float3> tuv("hit_tuv");
    Input<Int> id("hit_id");
    Input<Float> w("path_w");
    Input<Int4> pi("path_i");
    Input<Float3> color("color");
    Input<Float3> local("local");
    Output<Float3> color_out("color_out");
    Output<Float> w_out("path_w_out");
    Output<Int4> pi_out("path_i_out");
    Output<Float4> o_out("ray_o_out");
    Output<Float3> d_out("ray_d_out");
    Output<Int4> vox("tr_vox");
    Output<Int> ts("tr_state");
    Output<Int> ps("path_state");
    RILL_IF(pi.y() == 0 || pi.w() == 0) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Surface s;
    I.surface(o4(0, 1, 2), d, tuv.x(), id, tuv.y(), tuv.z(), s);
    Float3 c = color;
    Float weight = w;
    Int depth = pi.x();
    Float3 ro(0.0f), rd(0.0f);
    Bool go = false;
    I.shade(s, local, c, weight, depth, ro, rd, go, nullptr, nullptr);
    color_out = c;
    w_out = weight;
    RILL_IF(go) {
      o_out = Float4(ro, kBig);
      d_out = rd;
      vox = Int4(0, 0, 0, kPending);
      ts = kPending;
      pi_out = Int4(depth, 1, pi.z() + 1, 0);
      ps = kPathAlive;
    }
    RILL_ELSE {
      pi_out = Int4(depth, 0, pi.z(), 0);
      ps = kPathEnded;
    }
    RILL_ENDIF;
  });
}

Tracer::Impl::Impl() = default;
Tracer::Impl::~Impl() = default;

Multipass::Kernels& Multipass::kernels(const std::string& backend, Accuracy a) {
  const std::string key = backend + "/" + accuracy_name(a);
  auto it = compiled.find(key);
  if (it != compiled.end()) return it->second;
  CompileOptions opt;
  opt.accuracy = a;
  Kernels k;
  k.raygen = compile(raygen, backend, opt);
  k.surface = compile(surface, backend, opt);
  k.combine = compile(combine, backend, opt);
  if (setup.valid()) {
    k.setup = compile(setup, backend, opt);
    k.traverse = compile(traverse, backend, opt);
    k.intersect = compile(intersect, backend, opt);
    k.finish = compile(finish, backend, opt);
  }
  if (shadow_gen.valid()) {
    k.shadow_gen = compile(shadow_gen, backend, opt);
    k.shadow_acc = compile(shadow_acc, backend, opt);
  }
  return compiled.emplace(key, std::move(k)).first->second;
}

RenderResult Tracer::Impl::render_multipass(const RenderSettings& rs, int width, int height,
                                            int depth, int spp) {
  if (F.refraction)
    throw std::runtime_error(
        "--strategy multipass: glass (transmit > 0) needs the ray stack of the single kernel; "
        "use --strategy megakernel (the thesis's multipass tracer has no refraction either)");
  RenderResult r;
  r.backend = rs.backend;
  r.width = width;
  r.height = height;
  const auto t0 = std::chrono::steady_clock::now();
  if (!multipass) {
    multipass = std::make_unique<Multipass>();
    multipass->capture(*this);
    // Without geometry there is nothing to trace.
    if (!F.geometry) multipass->setup = multipass->traverse = multipass->intersect = Program();
  }
  Backend& be = backend(rs.backend);
  if (std::string why = be.unavailable_reason(); !why.empty())
    throw std::runtime_error("backend " + rs.backend + " cannot run here: " + why);
  if (!be.supports(rs.accuracy))
    throw std::runtime_error(std::string("backend ") + rs.backend + " has no " +
                             accuracy_name(rs.accuracy) + " accuracy mode");
  Multipass& M = *multipass;
  Multipass::Kernels& K = M.kernels(rs.backend, rs.accuracy);
  r.from_cache = K.raygen.info().cache_hit || K.raygen.info().from_disk_cache;

  max_depth.set(depth);
  Multipass::Buffers B(width, height);
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
  // Traces the rays in (o, d) whose state is pending; the hits go to (tuv, id).
  auto trace = [&](Stream<Float4>& o, Stream<Float3>& d, Stream<Float3>& tuv, Stream<Int>& id) {
    K.setup.inputs(o, d, B.tr_vox).outputs(B.tr_vox, B.tr_tmx, tuv, id, B.tr_state);
    K.traverse.inputs(o, d, B.tr_vox, B.tr_tmx, tuv, id)
        .outputs(B.tr_vox, B.tr_tmx, B.tr_cur, B.tr_state);
    K.intersect.inputs(o, d, B.tr_vox, B.tr_tmx, B.tr_cur, tuv, id)
        .outputs(B.tr_vox, B.tr_tmx, B.tr_cur, tuv, id, B.tr_state);
    K.finish.inputs(o, d, B.tr_vox, B.tr_tmx, B.tr_cur, tuv, id)
        .outputs(B.tr_vox, tuv, id, B.tr_state);
    const double n = static_cast<double>(run(K.setup, kSetup, where(B.tr_state, kPending)));
    for (int64_t pass = 0; n > 0; ++pass) {
      if (pass > 100000000) throw std::runtime_error("multipass: the trace loop does not end");
      const int64_t active = run(K.traverse, kTraverse, where(B.tr_state, kEnter));
      auto intersect = [&] { return run(K.intersect, kIntersect, where(B.tr_state, kWait)); };
      int64_t waiting = intersect();
      while (static_cast<double>(waiting) >= rs.wait_threshold * n) waiting = intersect();
      if (active == 0 && waiting == 0) break;
      if (static_cast<double>(active + waiting) < kTailFraction * n) {
        run(K.finish, kFinish, where(B.tr_state, {kEnter, kWait}));
        break;
      }
    }
  };

  const size_t npix = static_cast<size_t>(width) * static_cast<size_t>(height);
  std::vector<glm::dvec3> sum(spp > 1 ? npix : 0, glm::dvec3(0.0));
  const auto start = std::chrono::steady_clock::now();
  for (int sample = 0; sample < spp; ++sample) {
    offset.set(sample_offset(sample));
    K.raygen.outputs(B.ray_o, B.ray_d, B.tr_vox, B.path_w, B.path_i, B.color, B.aov_depth,
                     B.aov_prim, B.aov_normal, B.tr_state, B.path_state);
    run(K.raygen, kRaygen, std::nullopt);
    K.surface.inputs(B.ray_o, B.ray_d, B.hit_tuv, B.hit_id, B.path_w, B.path_i, B.color)
        .outputs(B.local, B.color, B.path_i, B.aov_depth, B.aov_prim, B.aov_normal, B.path_state);
    K.combine.inputs(B.ray_o, B.ray_d, B.hit_tuv, B.hit_id, B.path_w, B.path_i, B.color, B.local)
        .outputs(B.color, B.path_w, B.path_i, B.ray_o, B.ray_d, B.tr_vox, B.tr_state, B.path_state);
    const rill::StateMask with_surface = where(B.path_state, kPathSurface);
    for (int bounce = 0; bounce <= depth; ++bounce) {
      if (F.geometry) trace(B.ray_o, B.ray_d, B.hit_tuv, B.hit_id);
      if (run(K.surface, kSurface, where(B.path_state, {kPathAlive, kPathSurface})) == 0) break;
      if (F.shadows) {
        for (size_t l = 0; l < scene.lights.size(); ++l) {
          M.light.set(static_cast<int32_t>(l));
          K.shadow_gen.inputs(B.ray_o, B.ray_d, B.hit_tuv, B.hit_id, B.path_i)
              .outputs(B.sh_o, B.sh_d, B.tr_vox, B.path_i, B.tr_state);
          run(K.shadow_gen, kShadowGen, with_surface);
          trace(B.sh_o, B.sh_d, B.sh_tuv, B.sh_id);
          K.shadow_acc
              .inputs(B.ray_o, B.ray_d, B.hit_tuv, B.hit_id, B.path_i, B.tr_vox, B.sh_id, B.local)
              .outputs(B.local);
          run(K.shadow_acc, kShadowAcc, with_surface);
        }
      }
      run(K.combine, kCombine, with_surface);
    }
    std::vector<glm::ivec4> pi = B.path_i.download();
    for (const glm::ivec4& p : pi) r.rays += p.z;
    std::vector<glm::vec3> c = B.color.download();
    if (sample == 0) {
      r.color = c;
      r.depth = B.aov_depth.download();
      r.prim = B.aov_prim.download();
      r.normal = B.aov_normal.download();
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
