// The intersector's DSL functions (Intersector.h).
#include "rill/rt/kernel/Intersector.h"

#include <optional>

namespace rt {

using namespace rill;

// ---- the intersector ----------------------------------------------------------------------

Bool3 Intersector::flat_axes(const Float3& d) const {
  return abs(d) < 1.17549435e-38f;  // FLT_MIN
}

Float3 Intersector::inverse_dir(const Float3& d) const {
  return 1.0f / select(flat_axes(d), Float3(1.0f), d);
}

Int3 Intersector::step_dir(const Float3& d) const {
  return select(flat_axes(d), Int3(0),
                select(d > 0.0f, Int3(1), select(d < 0.0f, Int3(-1), Int3(0))));
}

Bool3 Intersector::nearest_axis(const Float3& t) const {
  Bool ax = t.x() <= t.y() && t.x() <= t.z();
  Bool ay = !ax && t.y() <= t.z();
  return Bool3(ax, ay, !ax && !ay);
}

DdaState Intersector::dda_start(const Float3& o, const Float3& d, const Float& t, const Float3& lo,
                                const Float3& cell, const Float3& last) const {
  Float3 vf = clamp(floor((o + t * d - lo) / cell), Float3(0.0f), last);
  Int3 vox = to_int(vf);
  Float3 bound = lo + (vf + select(d > 0.0f, Float3(1.0f), Float3(0.0f))) * cell;
  Float3 tmx = select(flat_axes(d), Float3(kBig), (bound - o) * inverse_dir(d));
  return DdaState{vox, tmx, Int(0), Bool(false)};
}

BoxSpan Intersector::ray_box(const Ray& ray) const {
  const Float3& o = ray.o;
  const Float3& d = ray.d;
  const Float& tmax = ray.tmax;
  Bool3 dz = flat_axes(d);
  Float3 inv = inverse_dir(d);
  Float3 t0 = (grid_.lo - o) * inv;
  Float3 t1 = (grid_.hi - o) * inv;
  Float3 tn = select(dz, Float3(-kBig), min(t0, t1));
  Float3 tf = select(dz, Float3(kBig), max(t0, t1));
  Bool outside = any(dz && ((o < grid_.lo) || (o > grid_.hi)));
  Float t_enter = max(max(tn.x(), tn.y()), max(tn.z(), 0.0f));
  Float t_exit = min(min(tf.x(), tf.y()), min(tf.z(), tmax));
  // A ray with a NaN or infinite component misses (the comparisons are false for NaN). In
  // `fast` the compiler may assume there are no NaNs and drop this; the traversal's step
  // limit still ends the loop (upload()).
  Bool finite = all(abs(o) <= 3.40282347e38f) && all(abs(d) <= 3.40282347e38f);
  return BoxSpan{finite && !outside && t_enter <= t_exit, t_enter, t_exit};
}

DdaState Intersector::dda_init(const Float3& o, const Float3& d, const Float& t_enter) const {
  DdaState st = dda_start(o, d, t_enter, grid_.lo, grid_.cell, to_float(grid_.res) - 1.0f);
  // Recompute: leave_voxel recomputes the boundaries from this and the cell index.
  if (K_.traversal == Traversal::Recompute) st.tmx = o - grid_.lo;
  return st;
}

namespace {

// Watertight ray-triangle intersection (Woop, Benthin & Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2013). The vertices are moved to the ray's origin, permuted so that the
// ray's dominant axis is z (the other two swapped when that component is negative, to keep
// the winding) and sheared so
// that the ray becomes the z axis; then three 2D edge functions decide. An edge shared by two
// triangles gives the same edge function with the opposite sign (the same products of the
// same bits, subtracted the other way round: exact without FMA contraction), and a ray on
// the edge (edge function 0) counts as inside both: no ray passes between them. (The paper
// redoes exactly-zero edge functions in double; GLSL has no double, and counting them as
// inside keeps the test watertight.) The per-ray set-up is recomputed for every triangle:
// the building block has no per-ray state to keep it in (the multipass strategy calls it
// from several kernels).
struct WatertightRay {
  Int kz = 0;
  Bool flip = false;
  Float sx = 0.0f, sy = 0.0f, sz = 0.0f;

  WatertightRay(const Float3& d) {
    Float3 ad = abs(d);
    kz = select(ad.x() >= ad.y() && ad.x() >= ad.z(), Int(0),
                select(ad.y() >= ad.z(), Int(1), Int(2)));
    Float3 dp = permute(d, false);
    flip = dp.z() < 0.0f;
    dp = permute(d, true);
    sz = 1.0f / dp.z();
    sx = dp.x() / dp.z();
    sy = dp.y() / dp.z();
  }
  // (v[kx], v[ky], v[kz]) with kx = kz + 1, ky = kz + 2 (mod 3), kx and ky swapped on flip.
  Float3 permute(const Float3& v, bool use_flip) const {
    Float a = select(kz == 0, v.y(), select(kz == 1, v.z(), v.x()));
    Float b = select(kz == 0, v.z(), select(kz == 1, v.x(), v.y()));
    Float c = select(kz == 0, v.x(), select(kz == 1, v.y(), v.z()));
    if (!use_flip) return Float3(a, b, c);
    return Float3(select(flip, b, a), select(flip, a, b), c);
  }
};

}  // namespace

void Intersector::test_triangle(const Float3& o, const Float3& d, const Int& ref, Hit& best) const {
  test_primitive(o, d, grid_.elements[ref], best);
}

void Intersector::test_primitive(const Float3& o, const Float3& d, const Int& tri,
                                 Hit& best) const {
  if (K_.triangle == TriangleTest::Watertight) {
    WatertightRay r(d);
    Float3 a = r.permute(tris_.v0[tri] - o, true), b = r.permute(tris_.v1[tri] - o, true),
           c = r.permute(tris_.v2[tri] - o, true);
    Float ax = a.x() - r.sx * a.z(), ay = a.y() - r.sy * a.z();
    Float bx = b.x() - r.sx * b.z(), by = b.y() - r.sy * b.z();
    Float cx = c.x() - r.sx * c.z(), cy = c.y() - r.sy * c.z();
    Float eu = cx * by - cy * bx;  // the edge functions: barycentrics of a, b, c times det
    Float ev = ax * cy - ay * cx;
    Float ew = bx * ay - by * ax;
    Bool mixed = (eu < 0.0f || ev < 0.0f || ew < 0.0f) && (eu > 0.0f || ev > 0.0f || ew > 0.0f);
    Float det = eu + ev + ew;
    Bool ok = !mixed && det != 0.0f;
    Float tt = eu * (r.sz * a.z()) + ev * (r.sz * b.z()) + ew * (r.sz * c.z());
    Float inv_det = 1.0f / select(ok, det, 1.0f);
    Float t = tt * inv_det;
    ok = ok && t > 0.0f;
    RILL_IF(ok && (t < best.t || (t == best.t && tri < best.id))) {
      best.t = t;
      best.id = tri;
      best.uv = Float2(ev * inv_det, ew * inv_det);
    }
    RILL_ENDIF;
    return;
  }
  Float3 v0 = tris_.v0[tri], e1 = tris_.e1[tri], e2 = tris_.e2[tri];
  Float3 pv = cross(d, e2);
  Float det = dot(e1, pv);
  Float3 tv = o - v0;
  Float3 qv = cross(tv, e1);
  Bool ok = det != 0.0f;
  Float inv_det = 1.0f / select(ok, det, 1.0f);
  Float u = dot(tv, pv) * inv_det;
  Float v = dot(d, qv) * inv_det;
  Float t = dot(e2, qv) * inv_det;
  ok = ok && u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f;
  RILL_IF(ok && (t < best.t || (t == best.t && tri < best.id))) {
    best.t = t;
    best.id = tri;
    best.uv = Float2(u, v);
  }
  RILL_ENDIF;
}

void Intersector::test_list(const Float3& o, const Float3& d, const Int2& range,
                            const Bool& any_hit, Hit& best) const {
  RILL_FOR(Int k = 0, k < range.y(), k += 1) {
    test_triangle(o, d, range.x() + k, best);
    // A shadow ray needs only whether something is in the way: the first hit settles it
    // (leave_voxel would end the walk after this voxel anyway). Closest-hit rays pass a
    // constant false, and the optimizer removes the test.
    RILL_IF(any_hit && best.id >= 0) {
      RILL_BREAK;
    }
    RILL_ENDIF;
  }
  RILL_ENDFOR;
}

RaySteps Intersector::ray_steps(const Float3& d) const {
  RaySteps r;
  r.d = d;
  r.flat = flat_axes(d);
  r.inv = inverse_dir(d);
  r.step = step_dir(d);
  r.tdl = select(r.flat, Float3(kBig), grid_.cell * abs(r.inv));
  return r;
}

Float3 Intersector::voxel_exits(const RaySteps& r, const Int3& vox, const Float3& tmx) const {
  if (K_.traversal == Traversal::Incremental) return tmx;
  Float3 plane = (to_float(vox) + select(r.d > 0.0f, Float3(1.0f), Float3(0.0f))) * grid_.cell;
  return select(r.flat, Float3(kBig), (plane - tmx) * r.inv);
}

// A second 3D-DDA, over the voxel's m^3 subgrid, from where the ray enters the voxel (or its
// origin, if inside) to where it leaves it or ends. Sub-voxels are visited in the ray's order
// and the walk stops once the best hit lies within the current one, exactly as on the top
// level; a hit beyond the voxel stays the best so far and the top-level walk goes on. Where
// rounding makes the entry point or the last exit fall within ulps of a sub-voxel face, the
// sub-voxels' margin (Grid.cpp) holds the triangles near it, as on the top level.
void Intersector::walk_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit,
                               const Bool& any_hit, const Int2& entry, const DdaState& at,
                               Hit& best) const {
  const Int3& vox = at.vox;
  const Float3& tmx = at.tmx;
  const Float3& d = r.d;
  const Bool3& dz = r.flat;
  const Float3& inv = r.inv;
  const Int3& step = r.step;
  Int m = -entry.y();
  Float fm = to_float(m);
  Float3 sub = grid_.cell / Float3(fm);
  Float3 corner = grid_.lo + to_float(vox) * grid_.cell;
  Float3 entry_plane = corner + select(d > 0.0f, Float3(0.0f), grid_.cell);
  Float3 t_in3 = select(dz, Float3(-kBig), (entry_plane - o) * inv);
  Float t_in = max(max(t_in3.x(), t_in3.y()), max(t_in3.z(), 0.0f));
  Float3 tb = voxel_exits(r, vox, tmx);
  Float t_out = min(min(tb.x(), tb.y()), min(tb.z(), t_exit));
  DdaState inner = dda_start(o, d, t_in, corner, sub, Float3(fm - 1.0f));
  Int3& sv = inner.vox;
  Float3& smx = inner.tmx;
  Int& sub_steps = inner.steps;
  Bool& done = inner.done;
  Float3 sdl = select(dz, Float3(kBig), sub * abs(inv));
  RILL_DO {
    test_list(o, d, grid_.voxels[entry.x() + sv.x() + m * (sv.y() + m * sv.z())], any_hit, best);
    Float s_leave = min(min(smx.x(), smx.y()), smx.z());
    done = best.id >= 0 && (best.t <= s_leave || any_hit);
    done = done || s_leave >= t_out;
    Bool3 sm = nearest_axis(smx);
    sv = sv + select(sm, step, Int3(0));
    smx = select(sm, smx + sdl, smx);
    sub_steps += 1;
    // At most 3 (m - 1) + 1 steps inside (the argument of upload()'s step limit).
    done = done || any(sv < 0) || any(sv >= Int3(m)) || sub_steps > 3 * m;
  }
  RILL_UNTIL(done);
}

void Intersector::leave_voxel(const RaySteps& r, const Float& t_exit, const Hit& best,
                              const Bool& any_hit, const Int2& entry, DdaState& st) const {
  Int3& vox = st.vox;
  Float3& tmx = st.tmx;
  Int& steps = st.steps;
  Bool& done = st.done;
  const Bool3& dz = r.flat;
  const Int3& step = r.step;
  const Float3& tdl = r.tdl;
  Float3 tb = voxel_exits(r, vox, tmx);
  Float t_leave = min(min(tb.x(), tb.y()), tb.z());
  done = best.id >= 0 && (best.t <= t_leave || any_hit);
  done = done || t_leave >= t_exit;  // the ray ends inside this voxel
  // An empty voxel at chessboard distance s >= 3 from the nearest listed triangle: every
  // voxel within s - 1 of it is empty, so the ray may jump k = s - 1 voxel shells at once
  // (Grid.h). The jump lands where the ray crosses from shell k - 1 into shell k: at
  // T = min over the axes of tb + (k - 1) tdl, k boundaries along that axis and, along each
  // other axis, the boundaries crossed before T. Rounding can make such a count one too
  // many or too few only where T falls within ulps of a boundary; the voxels the ray then
  // skips or adds are within k of this one, still empty, so the closest hit is unchanged
  // (the shell k - 1 bound, rather than s - 1, is that margin). Shorter jumps cost more
  // than the plain step they replace.
  Int k = select(entry.y() == 0 && entry.x() >= 3, entry.x() - 1, Int(1));
  RILL_IF(k > 1) {
    Float3 tk = select(dz, Float3(kBig), tb + to_float(k - 1) * tdl);
    Bool3 m = nearest_axis(tk);
    Float T = min(min(tk.x(), tk.y()), tk.z());
    done = done || T >= t_exit;  // the ray ends inside the empty region
    // Boundaries crossed before T on each other axis: ceil((T - tb) / tdl), 0 to k - 1
    // (NaN from infinite distances counts as none).
    Float3 q = (T - tb) / tdl;
    Float3 crossed = select(q > 0.0f, min(ceil(q), to_float(k - 1)), Float3(0.0f));
    Int3 n = select(m, Int3(k), to_int(crossed));
    vox = vox + step * n;
    if (K_.traversal == Traversal::Incremental) tmx = select(n > 0, tmx + to_float(n) * tdl, tmx);
  }
  RILL_ELSE {  // a plain step, along the axis whose boundary is nearest (the first of equals)
    Bool3 m = nearest_axis(tb);
    vox = vox + select(m, step, Int3(0));
    if (K_.traversal == Traversal::Incremental) tmx = select(m, tmx + tdl, tmx);
  }
  RILL_ENDIF;
  steps += 1;
  done = done || any(vox < 0) || any(vox >= grid_.res) || steps > grid_.max_steps;
}

// The grid's bounding box, then a 3D-DDA from voxel to voxel, testing the triangles listed
// in each (Moller-Trumbore). The closest hit wins (ties: the smaller id, so the result does
// not depend on the order of the lists); a hit counts once its distance is within the
// current voxel. With *any_hit true, the first hit before tmax ends the search.
Hit Intersector::intersect(const Ray& ray, const Bool* any_hit, const Int* light) const {
  Hit best{ray.tmax, Float2(0.0f), Int(-1)};
  if (!F_.geometry) return best;
  const Float3& o = ray.o;
  const Float3& d = ray.d;
  const Bool no(false);
  const Bool& any = any_hit != nullptr ? *any_hit : no;
  // The grid first: its hit, usually a near one in a static room, then bounds the BVH walk,
  // which skips every box beyond it.
  if (!grid_.empty && light != nullptr && any_hit != nullptr && lb_.enabled()) {
    Bool listed = false;
    // With area lights, light -1 is an area light sample's shadow ray: no light buffer.
    std::optional<Bool> area_buffered;
    if (F_.area_lights) area_buffered.emplace(any && *light >= 0);
    RILL_IF(area_buffered ? *area_buffered : any) {
      listed = occluders(ray, *light, best);
    }
    RILL_ENDIF;
    RILL_IF(!listed) {
      walk_grid(ray, any, best);
    }
    RILL_ENDIF;
  } else if (!grid_.empty) {
    walk_grid(ray, any, best);
  }
  if (F_.dynamic) walk_bvh(o, ray_steps(d), any, best);
  return best;
}

Bool Intersector::occluders(const Ray& ray, const Int& light, Hit& best) const {
  const Float3 q = ray.o - light_pos_[light];
  const Int2 c = lb_.cell(light, q);
  // Points of the ray before the light are at most |q| from it: an entry farther away (its
  // distance is a lower bound, LightBuffer.cpp) cannot block it, nor can the rest. An origin
  // farther than the light buffer's margins cover (a moving object far outside the static
  // scene) walks the grid.
  const Float reach = length(q);
  const Bool listed = c.y() >= 0 && reach <= lb_.reach;
  RILL_IF(listed) {
    RILL_FOR(Int k = 0, k < c.y(), k += 1) {
      RILL_IF(lb_.near[c.x() + k] > reach) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      test_primitive(ray.o, ray.d, lb_.tris[c.x() + k], best);
      RILL_IF(best.id >= 0) {
        RILL_BREAK;
      }
      RILL_ENDIF;
    }
    RILL_ENDFOR;
  }
  RILL_ENDIF;
  return listed;
}

void Intersector::walk_grid(const Ray& ray, const Bool& any, Hit& best) const {
  const Float3& o = ray.o;
  const Float3& d = ray.d;
  const BoxSpan box = ray_box(ray);
  const Float& t_exit = box.t_exit;
  RILL_IF(box.inside) {
    DdaState st = dda_init(o, d, box.t_enter);
    const RaySteps rs = ray_steps(d);
    if (packets_) {
      // Rays that step the same way on every axis walk together; a group with any other
      // direction walks ray by ray (`together` is the same in every lane of the group).
      Bool together = true;
      for (int a = 0; a < 3; ++a)
        together = together && group_min(Int(rs.step[a])) == group_max(Int(rs.step[a]));
      RILL_IF(together) {
        walk_grid_together(o, rs, t_exit, any, st, best);
      }
      RILL_ELSE {
        walk_alone(o, d, rs, t_exit, any, st, best);
      }
      RILL_ENDIF;
    } else {
      walk_alone(o, d, rs, t_exit, any, st, best);
    }
  }
  RILL_ENDIF;
}

void Intersector::walk_alone(const Float3& o, const Float3& d, const RaySteps& rs,
                             const Float& t_exit, const Bool& any, DdaState& st, Hit& best) const {
  RILL_DO {
    Int2 range = grid_.voxel_range(st.vox);
    test_list(o, d, range, any, best);
    if (grid_.subgrids > 0) {  // the second level's code only where the grid has one
      RILL_IF(range.y() < 0) {
        walk_subgrid(o, rs, t_exit, any, range, st, best);
      }
      RILL_ENDIF;
    }
    leave_voxel(rs, t_exit, best, any, range, st);
  }
  RILL_UNTIL(st.done);
}

}  // namespace rt
