// The multipass strategy's trace passes (Multipass.h): voxel precalculation, traverser,
// intersector, and the kernel that finishes the last few rays. Each is built from the
// Intersector's steps (kernel/Intersector.h), so a ray ends with the megakernel's hit.
#include "rill/rt/multipass/Multipass.h"
#include "rill/rt/multipass/States.h"

namespace rt {

using namespace rill;
using namespace mp;

// A voxel's cursor (c, end) is a subgrid's entry (base, -m) when end < 0: the intersector
// walks the whole subgrid in one pass (then the cursor is empty). Generated only when the
// grid has subgrids.
void Multipass::walk_pending_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit,
                                     const Bool& any_hit, const DdaState& at, Int& c, Int& end,
                                     Hit& best) const {
  if (S_.grid.subgrids == 0) return;
  RILL_IF(end < 0) {
    S_.intersector.walk_subgrid(o, r, t_exit, any_hit, Int2(c, end), at, best);
    c = 0;
    end = 0;
  }
  RILL_ENDIF;
}

Program Multipass::capture_setup() const {
  const Intersector& X = S_.intersector;
  return rill::program("mp_voxel_precalc", [&] {
    Input<Ray> ray("ray");
    Input<Int> state("tr.state");
    Output<Int> state_out("tr.state");
    Output<Int3> vout("tr.voxel");
    Output<Float3> tmx_out("tr.t_next");
    Output<Float> exit_out("tr.t_exit");
    Output<Int> steps_out("tr.steps");
    Output<Hit> hit("hit");
    skip_where(state != kPending);
    const BoxSpan box = X.ray_box(ray);
    Bool inside = box.inside;
    Hit best{ray.tmax, Float2(0.0f), Int(-1)};
    if (S_.F.dynamic) {
      // The moving triangles' BVH in one go; the grid's passes then go on from its hit, as
      // the megakernel's intersect() does. A shadow ray it blocks is finished.
      Bool any_hit = any_hit_ != 0;
      X.walk_bvh(ray.o, X.ray_steps(ray.d), any_hit, best);
      inside = inside && !(any_hit && best.id >= 0);
    }
    if (S_.grid.empty) inside = false;
    if (X.has_light_buffer() && S_.F.shadows) {
      // A shadow ray whose light buffer cell lists its possible blockers is settled here,
      // as in the megakernel's intersect(); the others walk the grid.
      RILL_IF(any_hit_ != 0 && inside) {
        Bool listed = X.occluders(ray, light_, best);
        inside = !listed;
      }
      RILL_ENDIF;
    }
    hit = best;
    steps_out = 0;
    RILL_IF(inside) {
      DdaState st = X.dda_init(ray.o, ray.d, box.t_enter);
      vout = st.vox;
      state_out = kEnter;
      tmx_out = st.tmx;
      exit_out = box.t_exit;
    }
    RILL_ELSE {
      vout = Int3(0);
      state_out = kFinished;
      tmx_out = Float3(0.0f);
      exit_out = 0.0f;
    }
    RILL_ENDIF;
  });
}

Program Multipass::capture_traverse() const {
  const Intersector& X = S_.intersector;
  return rill::program("mp_traverser", [&] {
    Input<Float3> d("ray.d");
    Input<TraceState> tr("tr");
    Input<Float> hit_t("hit.t");
    Input<Int> hit_id("hit.id");
    Output<Int> state_out("tr.state");
    Output<Int3> vout("tr.voxel");
    Output<Float3> tmx_out("tr.t_next");
    Output<Int> steps_out("tr.steps");
    Output<Int2> cur("tr.cursor");
    skip_where(tr.state != kEnter);
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
}

Program Multipass::capture_intersect() const {
  const Intersector& X = S_.intersector;
  return rill::program("mp_intersector", [&] {
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
    skip_where(tr.state != kWait);
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
}

// The tail: the last few rays run traverser and intersector steps in one loop (the same
// steps in the same order, so the same result), instead of many nearly empty passes. It
// writes the state and the hit only: nothing reads a finished ray's voxel or steps.
Program Multipass::capture_finish() const {
  const Intersector& X = S_.intersector;
  return rill::program("mp_finish", [&] {
    Input<Float3> o("ray.o");
    Input<Float3> d("ray.d");
    Input<TraceState> tr("tr");
    Input<Hit> hit("hit");
    Output<Int> state_out("tr.state");
    Output<Hit> hit_out("hit");
    Int state = tr.state;
    skip_where(state != kEnter && state != kWait);
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
}

}  // namespace rt
