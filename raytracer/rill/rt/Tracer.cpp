// The ray tracing kernel, written once in the DSL (see Tracer.h for the outline).
#include "rill/rt/Tracer.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "rill/rt/kernel/TracerImpl.h"
#include "rill/Reduce.h"

namespace rt {

namespace {

bool any_positive(const glm::vec3& v) {
  return v.x > 0.0f || v.y > 0.0f || v.z > 0.0f;
}

}  // namespace

std::string Features::str() const {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (on) s += (s.empty() ? "" : " ") + std::string(name);
  };
  add(geometry, "geometry");
  add(lights, "lights");
  add(shadows, "shadows");
  add(specular, "specular");
  add(reflection, "reflection");
  add(refraction, "refraction");
  add(vertex_normals, "vertex-normals");
  add(vertex_colors, "vertex-colors");
  if (stack > 0) s += " stack=" + std::to_string(stack);
  return s.empty() ? "none" : s;
}

Features scene_features(const Scene& s) {
  Features f;
  std::vector<bool> used(s.materials.size());
  for (size_t t = 0; t < s.triangle_count(); ++t)
    if (triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2])) {
      f.geometry = true;
      used[static_cast<size_t>(s.material[t])] = true;
    }
  f.lights = !s.lights.empty() && f.geometry;
  f.shadows = f.lights && s.options.shadows;
  for (size_t m = 0; m < s.materials.size(); ++m) {
    if (!used[m]) continue;
    const Material& mat = s.materials[m];
    f.specular = f.specular || (f.lights && any_positive(mat.specular));
    f.reflection = f.reflection || mat.reflect > 0.0f;
    f.refraction = f.refraction || mat.transmit > 0.0f;
  }
  // Refraction always needs the reflection code too (Fresnel, total internal reflection).
  if (f.refraction) {
    f.reflection = true;
    f.stack = kRayStack;
  }
  f.vertex_normals = f.geometry && !s.normals.empty() && s.options.smooth_normals;
  f.vertex_colors = f.geometry && !s.colors.empty();
  return f;
}

std::string TracerOptions::str() const {
  return std::string(triangle == TriangleTest::Watertight ? "watertight" : "moller") +
         (offset == SelfIntersection::Scaled ? " scaled" : " epsilon") +
         (traversal == Traversal::Recompute ? " recompute" : " incremental");
}

TriangleTest parse_triangle_test(const std::string& s) {
  if (s == "moller") return TriangleTest::MollerTrumbore;
  if (s == "watertight") return TriangleTest::Watertight;
  throw std::invalid_argument("--triangle expects moller or watertight (got '" + s + "')");
}

SelfIntersection parse_self_intersection(const std::string& s) {
  if (s == "epsilon") return SelfIntersection::Epsilon;
  if (s == "scaled") return SelfIntersection::Scaled;
  throw std::invalid_argument("--offset expects epsilon or scaled (got '" + s + "')");
}

Traversal parse_traversal(const std::string& s) {
  if (s == "incremental") return Traversal::Incremental;
  if (s == "recompute") return Traversal::Recompute;
  throw std::invalid_argument("--traversal expects incremental or recompute (got '" + s + "')");
}

glm::vec2 sample_offset(int k) {
  if (k == 0) return glm::vec2(0.5f);
  // Halton (2, 3): a low-discrepancy sequence, the same on every machine.
  auto halton = [](int i, int b) {
    double f = 1.0, r = 0.0;
    for (; i > 0; i /= b) {
      f /= b;
      r += f * (i % b);
    }
    return static_cast<float>(r);
  };
  return glm::vec2(halton(k, 2), halton(k, 3));
}

// ---- scene data and uniforms ---------------------------------------------------------------

void Tracer::Impl::upload() {
  const size_t n = scene.triangle_count();
  std::vector<glm::vec3> v0(n), e1(n), e2(n), ng(n);
  for (size_t t = 0; t < n; ++t) {
    const glm::vec3* p = &scene.positions[3 * t];
    v0[t] = p[0];
    e1[t] = p[1] - p[0];
    e2[t] = p[2] - p[0];
    glm::dvec3 c = glm::cross(glm::dvec3(e1[t]), glm::dvec3(e2[t]));
    double l = glm::length(c);
    ng[t] = (std::isfinite(l) && l > 0) ? glm::vec3(c / l) : glm::vec3(0.0f, 1.0f, 0.0f);
  }
  auto up3 = [](Array<Float3>& a, std::vector<glm::vec3> v) {
    v = padded<Float3>(std::move(v));
    a.resize(static_cast<int64_t>(v.size()));
    a.upload(v);
  };
  up3(tri_v0, v0);
  up3(tri_e1, e1);
  up3(tri_e2, e2);
  up3(tri_ng, ng);
  if (K.triangle == TriangleTest::Watertight) {
    std::vector<glm::vec3> v1(n), v2(n);
    for (size_t t = 0; t < n; ++t) {
      v1[t] = scene.positions[3 * t + 1];
      v2[t] = scene.positions[3 * t + 2];
    }
    up3(tri_v1, v1);
    up3(tri_v2, v2);
  }
  if (F.vertex_normals) {
    std::vector<glm::vec3> n0(n), n1(n), n2(n);
    for (size_t t = 0; t < n; ++t) {
      const bool has = !scene.normals.empty();  // else forced on (Tracer's `extra`)
      n0[t] = has ? scene.normals[3 * t] : ng[t];
      n1[t] = has ? scene.normals[3 * t + 1] : ng[t];
      n2[t] = has ? scene.normals[3 * t + 2] : ng[t];
    }
    up3(tri_n0, n0);
    up3(tri_n1, n1);
    up3(tri_n2, n2);
  }
  if (F.vertex_colors) {
    std::vector<glm::vec3> c0(n), c1(n), c2(n);
    for (size_t t = 0; t < n; ++t) {
      const bool has = !scene.colors.empty();
      c0[t] = has ? scene.colors[3 * t] : glm::vec3(1.0f);
      c1[t] = has ? scene.colors[3 * t + 1] : glm::vec3(1.0f);
      c2[t] = has ? scene.colors[3 * t + 2] : glm::vec3(1.0f);
    }
    up3(tri_c0, c0);
    up3(tri_c1, c1);
    up3(tri_c2, c2);
  }
  {
    auto m = padded<Int>(std::vector<int32_t>(scene.material));
    tri_mat.resize(static_cast<int64_t>(m.size()));
    tri_mat.upload(m);
  }
  std::vector<glm::vec3> kd, ks;
  std::vector<glm::vec4> mp;
  for (const Material& m : scene.materials) {
    kd.push_back(m.diffuse);
    ks.push_back(m.specular);
    mp.emplace_back(m.shininess, m.reflect, m.transmit, m.ior);
  }
  up3(mat_kd, kd);
  up3(mat_ks, ks);
  mp = padded<Float4>(mp);
  mat_p.resize(static_cast<int64_t>(mp.size()));
  mat_p.upload(mp);
  std::vector<glm::vec3> lp, lc;
  for (const Light& l : scene.lights) {
    lp.push_back(l.position);
    lc.push_back(l.color);
  }
  up3(light_pos, lp);
  up3(light_col, lc);
  nlights.set(static_cast<int32_t>(scene.lights.size()));

  auto vox = padded<Int2>(grid.voxels);
  voxels.resize(static_cast<int64_t>(vox.size()));
  voxels.upload(vox);
  auto el = padded<Int>(grid.elements);
  elements.resize(static_cast<int64_t>(el.size()));
  elements.upload(el);
  grid_lo.set(grid.lo);
  grid_hi.set(grid.hi);
  grid_cell.set(grid.cell);
  grid_res.set(grid.res);
  // The traversal's step limit, a proof rather than a guess: every step moves the voxel by
  // one along one axis, never against the sign of d, and the loop ends when the voxel
  // leaves [0, res). So a ray (any ray, whatever rounding did to tMax) takes at most
  // (res.x - 1) + (res.y - 1) + (res.z - 1) steps inside and one more out: res.x + res.y +
  // res.z - 2 steps. The limit (with 5 to spare) never cuts a real traversal short; it ends
  // the loop for rays whose steps are 0 on the chosen axis (NaN directions), which would
  // otherwise stay in one voxel forever. Every loop iteration counts a step, so the loop
  // runs at most max_voxel_steps + 1 times on any input.
  max_steps.set(grid.res.x + grid.res.y + grid.res.z + 3);

  // Secondary rays start a little off the surface: 2e-5 of the scene's size (and at least
  // a few ulps of its coordinates).
  glm::vec3 lo, hi;
  float e = 1e-4f;
  if (scene_bounds(scene, lo, hi)) {
    double diag = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
    double mag = std::max(glm::length(glm::dvec3(lo)), glm::length(glm::dvec3(hi)));
    e = static_cast<float>(std::max(2e-5 * diag, 1e-6 * mag));
    if (!(e > 0)) e = 1e-4f;
  }
  eps.set(e);
  ambient.set(scene.options.ambient);
  background.set(scene.background);
}

// ---- the intersector ----------------------------------------------------------------------

Bool3 Tracer::Impl::flat_axes(const Float3& d) const {
  return abs(d) < 1.17549435e-38f;  // FLT_MIN
}

Float3 Tracer::Impl::inverse_dir(const Float3& d) const {
  return 1.0f / select(flat_axes(d), Float3(1.0f), d);
}

Int3 Tracer::Impl::step_dir(const Float3& d) const {
  return select(flat_axes(d), Int3(0),
                select(d > 0.0f, Int3(1), select(d < 0.0f, Int3(-1), Int3(0))));
}

Bool3 Tracer::Impl::nearest_axis(const Float3& t) const {
  Bool ax = t.x() <= t.y() && t.x() <= t.z();
  Bool ay = !ax && t.y() <= t.z();
  return Bool3(ax, ay, !ax && !ay);
}

void Tracer::Impl::dda_start(const Float3& o, const Float3& d, const Float& t, const Float3& lo,
                             const Float3& cell, const Float3& last, Int3& vox, Float3& tmx) const {
  Float3 vf = clamp(floor((o + t * d - lo) / cell), Float3(0.0f), last);
  vox = to_int(vf);
  Float3 bound = lo + (vf + select(d > 0.0f, Float3(1.0f), Float3(0.0f))) * cell;
  tmx = select(flat_axes(d), Float3(kBig), (bound - o) * inverse_dir(d));
}

void Tracer::Impl::ray_box(const Float3& o, const Float3& d, const Float& tmax, Bool& inside,
                           Float& t_enter, Float& t_exit) const {
  Bool3 dz = flat_axes(d);
  Float3 inv = inverse_dir(d);
  Float3 t0 = (grid_lo - o) * inv;
  Float3 t1 = (grid_hi - o) * inv;
  Float3 tn = select(dz, Float3(-kBig), min(t0, t1));
  Float3 tf = select(dz, Float3(kBig), max(t0, t1));
  Bool outside = any(dz && ((o < grid_lo) || (o > grid_hi)));
  t_enter = max(max(tn.x(), tn.y()), max(tn.z(), 0.0f));
  t_exit = min(min(tf.x(), tf.y()), min(tf.z(), tmax));
  // A ray with a NaN or infinite component misses (the comparisons are false for NaN). In
  // `fast` the compiler may assume there are no NaNs and drop this; the traversal's step
  // limit still ends the loop (upload()).
  Bool finite = all(abs(o) <= 3.40282347e38f) && all(abs(d) <= 3.40282347e38f);
  inside = finite && !outside && t_enter <= t_exit;
}

void Tracer::Impl::dda_init(const Float3& o, const Float3& d, const Float& t_enter, Int3& vox,
                            Float3& tmx) const {
  dda_start(o, d, t_enter, grid_lo, grid_cell, to_float(grid_res) - 1.0f, vox, tmx);
  // Recompute: leave_voxel recomputes the boundaries from this and the cell index.
  if (K.traversal == Traversal::Recompute) tmx = o - grid_lo;
}

Int2 Tracer::Impl::voxel_range(const Int3& vox) const {
  return voxels[vox.x() + grid_res.x() * (vox.y() + grid_res.y() * vox.z())];
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

void Tracer::Impl::test_triangle(const Float3& o, const Float3& d, const Int& ref, Float& best_t,
                                 Int& best_id, Float& best_u, Float& best_v) const {
  Int tri = elements[ref];
  if (K.triangle == TriangleTest::Watertight) {
    WatertightRay r(d);
    Float3 a = r.permute(tri_v0[tri] - o, true), b = r.permute(tri_v1[tri] - o, true),
           c = r.permute(tri_v2[tri] - o, true);
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
    RILL_IF(ok && (t < best_t || (t == best_t && tri < best_id))) {
      best_t = t;
      best_id = tri;
      best_u = ev * inv_det;
      best_v = ew * inv_det;
    }
    RILL_ENDIF;
    return;
  }
  Float3 v0 = tri_v0[tri], e1 = tri_e1[tri], e2 = tri_e2[tri];
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
  RILL_IF(ok && (t < best_t || (t == best_t && tri < best_id))) {
    best_t = t;
    best_id = tri;
    best_u = u;
    best_v = v;
  }
  RILL_ENDIF;
}

RaySteps Tracer::Impl::ray_steps(const Float3& d) const {
  RaySteps r;
  r.d = d;
  r.flat = flat_axes(d);
  r.inv = inverse_dir(d);
  r.step = step_dir(d);
  r.tdl = select(r.flat, Float3(kBig), grid_cell * abs(r.inv));
  return r;
}

Float3 Tracer::Impl::voxel_exits(const RaySteps& r, const Int3& vox, const Float3& tmx) const {
  if (K.traversal == Traversal::Incremental) return tmx;
  Float3 plane = (to_float(vox) + select(r.d > 0.0f, Float3(1.0f), Float3(0.0f))) * grid_cell;
  return select(r.flat, Float3(kBig), (plane - tmx) * r.inv);
}

// A second 3D-DDA, over the voxel's m^3 subgrid, from where the ray enters the voxel (or its
// origin, if inside) to where it leaves it or ends. Sub-voxels are visited in the ray's order
// and the walk stops once the best hit lies within the current one, exactly as on the top
// level; a hit beyond the voxel stays the best so far and the top-level walk goes on. Where
// rounding makes the entry point or the last exit fall within ulps of a sub-voxel face, the
// sub-voxels' margin (Grid.cpp) holds the triangles near it, as on the top level.
void Tracer::Impl::walk_subgrid(const Float3& o, const RaySteps& r, const Float& t_exit,
                                const Bool& any_hit, const Int2& entry, const Int3& vox,
                                const Float3& tmx, Float& best_t, Int& best_id, Float& best_u,
                                Float& best_v) const {
  const Float3& d = r.d;
  const Bool3& dz = r.flat;
  const Float3& inv = r.inv;
  const Int3& step = r.step;
  Int m = -entry.y();
  Float fm = to_float(m);
  Float3 sub = grid_cell / Float3(fm);
  Float3 corner = grid_lo + to_float(vox) * grid_cell;
  Float3 entry_plane = corner + select(d > 0.0f, Float3(0.0f), grid_cell);
  Float3 t_in3 = select(dz, Float3(-kBig), (entry_plane - o) * inv);
  Float t_in = max(max(t_in3.x(), t_in3.y()), max(t_in3.z(), 0.0f));
  Float3 tb = voxel_exits(r, vox, tmx);
  Float t_out = min(min(tb.x(), tb.y()), min(tb.z(), t_exit));
  Int3 sv(0);
  Float3 smx(0.0f);
  dda_start(o, d, t_in, corner, sub, Float3(fm - 1.0f), sv, smx);
  Float3 sdl = select(dz, Float3(kBig), sub * abs(inv));
  Int sub_steps = 0;
  Bool done = false;
  RILL_DO {
    Int2 range = voxels[entry.x() + sv.x() + m * (sv.y() + m * sv.z())];
    RILL_FOR(Int k = 0, k < range.y(), k += 1) {
      test_triangle(o, d, range.x() + k, best_t, best_id, best_u, best_v);
    }
    RILL_ENDFOR;
    Float s_leave = min(min(smx.x(), smx.y()), smx.z());
    done = best_id >= 0 && (best_t <= s_leave || any_hit);
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

void Tracer::Impl::leave_voxel(const RaySteps& r, const Float& t_exit, const Float& best_t,
                               const Int& best_id, const Bool& any_hit, const Int2& entry,
                               Int3& vox, Float3& tmx, Int& steps, Bool& done) const {
  const Bool3& dz = r.flat;
  const Int3& step = r.step;
  const Float3& tdl = r.tdl;
  Float3 tb = voxel_exits(r, vox, tmx);
  Float t_leave = min(min(tb.x(), tb.y()), tb.z());
  done = best_id >= 0 && (best_t <= t_leave || any_hit);
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
    if (K.traversal == Traversal::Incremental) tmx = select(n > 0, tmx + to_float(n) * tdl, tmx);
  }
  RILL_ELSE {  // a plain step, along the axis whose boundary is nearest (the first of equals)
    Bool3 m = nearest_axis(tb);
    vox = vox + select(m, step, Int3(0));
    if (K.traversal == Traversal::Incremental) tmx = select(m, tmx + tdl, tmx);
  }
  RILL_ENDIF;
  steps += 1;
  done = done || any(vox < 0) || any(vox >= grid_res) || steps > max_steps;
}

// The grid's bounding box, then a 3D-DDA from voxel to voxel, testing the triangles listed
// in each (Moller-Trumbore). The closest hit wins (ties: the smaller id, so the result does
// not depend on the order of the lists); a hit counts once its distance is within the
// current voxel. With *any_hit true, the first hit before tmax ends the search.
void Tracer::Impl::intersect(const Float3& o, const Float3& d, const Float& tmax,
                             const Bool* any_hit, Bool& hit, Float& best_t, Int& best_id,
                             Float& best_u, Float& best_v) const {
  hit = false;
  best_t = tmax;
  best_id = -1;
  if (!F.geometry) return;
  Bool inside = false;
  Float t_enter = 0.0f, t_exit = 0.0f;
  ray_box(o, d, tmax, inside, t_enter, t_exit);
  RILL_IF(inside) {
    Int3 vox(0);
    Float3 tmx(0.0f);
    dda_init(o, d, t_enter, vox, tmx);
    const Bool no(false);
    const RaySteps rs = ray_steps(d);
    Int steps = 0;
    Bool done = false;
    RILL_DO {
      Int2 range = voxel_range(vox);
      RILL_FOR(Int k = 0, k < range.y(), k += 1) {
        test_triangle(o, d, range.x() + k, best_t, best_id, best_u, best_v);
      }
      RILL_ENDFOR;
      if (grid.subgrids > 0) {  // the second level's code only where the grid has one
        RILL_IF(range.y() < 0) {
          walk_subgrid(o, rs, t_exit, any_hit != nullptr ? *any_hit : no, range, vox, tmx, best_t,
                       best_id, best_u, best_v);
        }
        RILL_ENDIF;
      }
      leave_voxel(rs, t_exit, best_t, best_id, any_hit != nullptr ? *any_hit : no, range, vox, tmx,
                  steps, done);
    }
    RILL_UNTIL(done);
    hit = best_id >= 0;
  }
  RILL_ENDIF;
}

// ---- shading -------------------------------------------------------------------------------

// Wachter & Binder, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
// Gems, ch. 6): move each coordinate a number of ulps proportional to the normal (integer
// steps on the float's bits, so the offset scales with the coordinate's magnitude: it
// suffices at 1e4 as at 1e-4); where a coordinate is near zero and its ulps are tiny, a
// fixed step instead. Two changes from the published constants, both measured (HardCases
// tests, docs/accuracy.md): the point comes from the barycentrics (surface()), so its error
// is about 2 ulps per coordinate and kIntScale = 8 ulps suffices where the paper's 256
// (for points from o + t d after instance transforms) moved rays 0.25 units at 1e4 and lost
// contact shadows; and the near-zero step is the scene-relative eps instead of 2^-16
// absolute, which was 15% of a scene scaled to 1e-3 units.
Float3 Tracer::Impl::offset_origin(const Float3& p, const Float3& n) const {
  if (K.offset == SelfIntersection::Epsilon) return p + n * eps;
  constexpr float kOrigin = 1.0f / 32.0f, kIntScale = 8.0f;
  Int3 of = to_int(kIntScale * n);
  Float3 pi = as_float(as_int(p) + select(p < 0.0f, -of, of));
  return select(abs(p) < kOrigin, p + n * eps, pi);
}

void Tracer::Impl::surface(const Float3& ro, const Float3& rd, const Float& ht, const Int& hid,
                           const Float& hu, const Float& hv, Surface& s) const {
  if (K.offset == SelfIntersection::Scaled) {
    // On the triangle, from the barycentrics: the error does not grow with the distance.
    s.P = tri_v0[hid] + hu * tri_e1[hid] + hv * tri_e2[hid];
  } else {
    s.P = ro + ht * rd;
  }
  Float3 ng = tri_ng[hid];
  Float3 ns = ng;
  if (F.vertex_normals) {
    Float w = 1.0f - hu - hv;
    Float3 nn = tri_n0[hid] * w + tri_n1[hid] * hu + tri_n2[hid] * hv;
    Float nl = length(nn);
    ns = select(nl > 0.0f, nn / select(nl > 0.0f, nl, 1.0f), ng);
    ng = select(dot(ng, ns) < 0.0f, -ng, ng);  // the vertex normals tell outside
  }
  s.ns = ns;
  s.entering = dot(ng, rd) < 0.0f;
  s.nf = select(s.entering, ns, -ns);
  s.ngf = select(s.entering, ng, -ng);
  s.V = -rd;
  Int m = tri_mat[hid];
  s.kd = mat_kd[m];
  if (F.vertex_colors) {
    Float w = 1.0f - hu - hv;
    s.kd = s.kd * (tri_c0[hid] * w + tri_c1[hid] * hu + tri_c2[hid] * hv);
  }
  if (F.specular) s.ks = mat_ks[m];
  Float4 mp = mat_p[m];
  s.shin = mp.x();
  s.refl = mp.y();
  s.trans = mp.z();
  s.ior = mp.w();
}

Float3 Tracer::Impl::phong(const Int& l, const Surface& s) const {
  Float3 L = normalize(light_pos[l] - s.P);
  Float ndl = dot(s.nf, L);
  Float3 c = s.kd * max(ndl, 0.0f);
  if (F.specular) {
    Float3 R = reflect(-L, s.nf);
    Float rv = max(dot(R, s.V), 0.0f);
    c = c + select(ndl > 0.0f, s.ks * pow(rv, s.shin), Float3(0.0f));
  }
  return Float3(c * light_col[l]);
}

Float3 Tracer::Impl::unshadowed_light(const Surface& s) const {
  Float3 sum(0.0f);
  if (F.lights) {
    RILL_FOR(Int l = 0, l < nlights, l += 1) {
      sum += phong(l, s);
    }
    RILL_ENDFOR;
  } else {
    sum = s.kd * max(dot(s.nf, s.V), 0.0f);  // no lights: a headlight at the eye
  }
  return sum;
}

void Tracer::Impl::shadow_ray(const Int& l, const Surface& s, Float3& ro, Float3& rd, Float& tmax,
                              Bool& active) const {
  Float3 so = offset_origin(s.P, s.ngf);
  Float3 L = light_pos[l] - so;
  Float dist = length(L);
  ro = so;
  rd = L / dist;
  // Stop short of the light by the same offset: a light on a surface (as on an area
  // light's quad) is not shadowed by that surface.
  tmax = dist - eps;
  active = dist > 0.0f && dot(s.nf, rd) > 0.0f;
}

void Tracer::Impl::shade(const Surface& s, const Float3& local, Float3& color, Float& weight,
                         Int& depth, Float3& ro, Float3& rd, Bool& go, Bool* has_second,
                         Branch* second) const {
  // Eq. 5.1: this surface contributes M_j (1 - r_j) times the product of the earlier
  // coefficients; with glass, 1 - reflect - transmit.
  color += weight * (1.0f - s.refl - s.trans) * local;
  go = false;
  if (has_second != nullptr) *has_second = false;
  if (!F.reflection) return;
  RILL_IF(depth < max_depth) {
    const Float3 inc = -s.V;
    Float3 rdir = reflect(inc, s.nf);
    Float wr = weight * s.refl;
    Float wt = 0.0f;
    Float3 tdir(0.0f);
    if (F.refraction) {
      // Refraction with Schlick's Fresnel term; total internal reflection sends everything
      // to the reflected ray.
      Float eta = select(s.entering, 1.0f / s.ior, s.ior);
      Float cosi = dot(s.V, s.nf);
      Float k = 1.0f - eta * eta * (1.0f - cosi * cosi);
      Bool tir = k < 0.0f;
      Float sk = sqrt(max(k, 0.0f));
      tdir = eta * inc + (eta * cosi - sk) * s.nf;
      Float r0 = (s.ior - 1.0f) / (s.ior + 1.0f);
      r0 = r0 * r0;
      Float c = 1.0f - select(s.entering, cosi, sk);
      Float c2 = c * c;
      Float fres = select(tir, 1.0f, r0 + (1.0f - r0) * (c2 * c2 * c));
      wr = weight * (s.refl + s.trans * fres);
      wt = weight * s.trans * (1.0f - fres);
    }
    Bool go_r = wr > kMinWeight;
    Bool go_t = wt > kMinWeight;
    if (second != nullptr) {  // both: the reflection is the second branch
      *has_second = go_r && go_t;
      second->o = offset_origin(s.P, s.ngf);
      second->d = rdir;
      second->w = wr;
    }
    RILL_IF(go_t) {
      ro = offset_origin(s.P, -s.ngf);
      rd = tdir;
      weight = wt;
      go = true;
    }
    RILL_ELSE_IF(go_r) {
      ro = offset_origin(s.P, s.ngf);
      rd = rdir;
      weight = wr;
      go = true;
    }
    RILL_ENDIF;
    depth += 1;
  }
  RILL_ENDIF;
}

// ---- the single kernel ---------------------------------------------------------------------

Program Tracer::Impl::capture_tracer() const {
  return rill::program("rill_trace", [&] {
    Output<Float3> out_color("color");
    Output<Float> out_depth("depth");
    Output<Int> out_prim("prim");
    Output<Float3> out_normal("normal");
    Output<Int> out_rays("rays");

    const Float inf = as_float(Int(0x7f800000));
    out_depth = inf;
    out_prim = -1;
    out_normal = Float3(0.0f);

    Float3 ro = eye;
    Float3 rd = camera_ray(element_coord());
    Float ray_tmax = kBig;
    Bool ray_active = true;

    Float3 color(0.0f);
    Float weight = 1.0f;  // eq. 5.1: the product of the reflection coefficients so far
    Int depth = 0;
    Int mode = 0;  // 0: camera or secondary ray, 1: shadow ray towards light li
    Int li = 0;
    Int rays = 0, iter = 0;
    Bool finished = false;
    Surface surf;
    Float3 local(0.0f);

    // The ray stack (refraction: the reflected branch waits here).
    std::vector<Float3> st_o, st_d;
    std::vector<Float> st_w;
    std::vector<Int> st_depth;
    for (int s = 0; s < F.stack; ++s) {
      st_o.emplace_back(0.0f);
      st_d.emplace_back(0.0f);
      st_w.emplace_back(0.0f);
      st_depth.emplace_back(0);
    }
    Int sp = 0;

    // max_iter = 0 skips all tracing: render() uses that for a warm-up launch.
    RILL_IF(max_iter > 0) {
      RILL_DO {
        Bool hit = false;
        Float ht = 0.0f, hu = 0.0f, hv = 0.0f;
        Int hid = -1;
        if (F.geometry) {
          RILL_IF(ray_active) {
            Bool any_hit = mode == 1;
            intersect(ro, rd, ray_tmax, F.shadows ? &any_hit : nullptr, hit, ht, hid, hu, hv);
            rays += 1;
          }
          RILL_ENDIF;
        } else {
          rays += 1;
        }
        Bool shade_done = false, path_done = false;
        Int cur_mode = mode;  // the branches below may change mode for the next iteration

        auto shade_hit = [&] {
          surface(ro, rd, ht, hid, hu, hv, surf);
          local = ambient * surf.kd;
          RILL_IF(depth == 0) {  // AOVs of the camera ray
            out_depth = ht;
            out_prim = hid;
            out_normal = surf.ns;
          }
          RILL_ENDIF;
          if (F.shadows) {
            mode = 1;
            li = 0;
            shadow_ray(li, surf, ro, rd, ray_tmax, ray_active);
          } else {
            local += unshadowed_light(surf);
            shade_done = true;
          }
        };
        auto miss = [&] {
          color += weight * background;
          path_done = true;
        };
        RILL_IF(cur_mode == 0) {
          if (F.geometry) {
            RILL_IF(hit) {
              shade_hit();
            }
            RILL_ELSE {
              miss();
            }
            RILL_ENDIF;
          } else {
            miss();
          }
        }
        RILL_ENDIF;
        if (F.shadows) {
          RILL_IF(cur_mode == 1) {  // a shadow ray came back
            RILL_IF(ray_active && !hit) {
              local += phong(li, surf);
            }
            RILL_ENDIF;
            li += 1;
            RILL_IF(li < nlights) {
              shadow_ray(li, surf, ro, rd, ray_tmax, ray_active);
            }
            RILL_ELSE {
              mode = 0;
              shade_done = true;
            }
            RILL_ENDIF;
          }
          RILL_ENDIF;
        }

        RILL_IF(shade_done) {
          Bool go = false, second = false;
          Branch b;
          shade(surf, local, color, weight, depth, ro, rd, go, F.stack > 0 ? &second : nullptr,
                F.stack > 0 ? &b : nullptr);
          if (F.stack > 0) {
            RILL_IF(second && sp < F.stack) {  // the reflection waits on the stack
              for (int s = 0; s < F.stack; ++s) {
                RILL_IF(sp == s) {
                  st_o[static_cast<size_t>(s)] = b.o;
                  st_d[static_cast<size_t>(s)] = b.d;
                  st_w[static_cast<size_t>(s)] = b.w;
                  st_depth[static_cast<size_t>(s)] = depth;
                }
                RILL_ENDIF;
              }
              sp += 1;
            }
            RILL_ENDIF;
          }
          RILL_IF(go) {
            ray_active = true;
            ray_tmax = kBig;
          }
          RILL_ELSE {
            path_done = true;
          }
          RILL_ENDIF;
        }
        RILL_ENDIF;

        RILL_IF(path_done) {
          if (F.stack > 0) {
            RILL_IF(sp > 0) {
              for (int s = 0; s < F.stack; ++s) {
                RILL_IF(sp == s + 1) {
                  ro = st_o[static_cast<size_t>(s)];
                  rd = st_d[static_cast<size_t>(s)];
                  weight = st_w[static_cast<size_t>(s)];
                  depth = st_depth[static_cast<size_t>(s)];
                }
                RILL_ENDIF;
              }
              sp -= 1;
              ray_active = true;
              ray_tmax = kBig;
            }
            RILL_ELSE {
              finished = true;
            }
            RILL_ENDIF;
          } else {
            finished = true;
          }
        }
        RILL_ENDIF;
        iter += 1;
        finished = finished || iter >= max_iter;
      }
      RILL_UNTIL(finished);
    }
    RILL_ENDIF;

    out_color = color;
    out_rays = rays;
  });
}

// The camera ray through pixel pix (docs/camera.md, float32, in this order).
Float3 Tracer::Impl::camera_ray(const Int2& pix) const {
  Float sx = ((to_float(pix.x()) + offset.x()) / size.x() * 2.0f - 1.0f) * tan_half * aspect;
  Float sy = (1.0f - (to_float(pix.y()) + offset.y()) / size.y() * 2.0f) * tan_half;
  return normalize(forward + sx * right + sy * up);
}

void Tracer::Impl::set_camera(const Camera& camera, int width, int height) {
  const CameraFrame f = camera_frame(camera, width, height);
  eye.set(f.eye);
  forward.set(f.forward);
  right.set(f.right);
  up.set(f.up);
  tan_half.set(f.tan_half);
  aspect.set(f.aspect);
  size.set(glm::vec2(f.width, f.height));
}

Program Tracer::Impl::capture_camera() const {
  return rill::program("rill_camera_rays", [&] {
    Output<Float3> dir("direction");
    dir = camera_ray(element_coord());
  });
}

Program Tracer::Impl::capture_intersector() const {
  return rill::program("rill_intersect", [&] {
    Input<Float3> o("origin");
    Input<Float3> d("direction");
    Output<Int> prim("prim");
    Output<Float> dist("dist");
    Bool hit = false;
    Float t = 0.0f, u = 0.0f, v = 0.0f;
    Int id = -1;
    intersect(o, d, Float(kBig), nullptr, hit, t, id, u, v);
    prim = select(hit, id, -1);
    dist = select(hit, t, as_float(Int(0x7f800000)));
  });
}

Kernel& Tracer::Impl::kernel(const std::string& backend_name, Accuracy a) {
  const std::string key = backend_name + "/" + accuracy_name(a);
  auto it = kernels.find(key);
  if (it != kernels.end()) return it->second;
  Backend& be = backend(backend_name);
  if (std::string why = be.unavailable_reason(); !why.empty())
    throw std::runtime_error("backend " + backend_name + " cannot run here: " + why);
  if (!be.supports(a))
    throw std::runtime_error(std::string("backend ") + backend_name + " has no " +
                             accuracy_name(a) + " accuracy mode");
  CompileOptions opt;
  opt.accuracy = a;
  return kernels.emplace(key, compile(trace_program, backend_name, opt)).first->second;
}

void add_stages(RenderResult& r, const rill::CompileInfo& k) {
  rill::CompileInfo& s = r.stages;
  if (r.kernels++ == 0) s.origin = k.origin;
  s.capture_ms += k.capture_ms;
  s.optimize_ms += k.optimize_ms;
  s.codegen_ms += k.codegen_ms;
  s.backend_compile_ms += k.backend_compile_ms;
  s.driver_finish_ms += k.driver_finish_ms;
  s.compile_ms += k.compile_ms;
}

// ---- Tracer --------------------------------------------------------------------------------

Tracer::Tracer(const Scene& scene, const Grid& grid, const TracerOptions& options)
    : d_(std::make_unique<Impl>()) {
  scene.validate();
  d_->K = options;
  d_->scene.materials = scene.materials;
  d_->scene.lights = scene.lights;
  d_->scene.options = scene.options;
  d_->scene.background = scene.background;
  d_->scene.positions = scene.positions;
  d_->scene.normals = scene.normals;
  d_->scene.colors = scene.colors;
  d_->scene.material = scene.material;
  d_->grid = grid;
  d_->F = scene_features(scene);
  if (d_->F.geometry) {
    Features& f = d_->F;
    const Features& extra = options.extra_features;
    f.specular = f.specular || (f.lights && extra.specular);
    f.refraction = f.refraction || extra.refraction;
    f.reflection = f.reflection || extra.reflection || f.refraction;
    f.stack = std::max(f.stack, f.refraction ? kRayStack : extra.stack);
    f.vertex_normals = f.vertex_normals || extra.vertex_normals;
    f.vertex_colors = f.vertex_colors || extra.vertex_colors;
  }
  d_->upload();
  // The triangle data is in the arrays now; keep only what shading needs.
  d_->scene.positions.clear();
  d_->scene.normals.clear();
  d_->scene.colors.clear();
  d_->trace_program = d_->capture_tracer();
}

Tracer::~Tracer() = default;

const Program& Tracer::program() const {
  return d_->trace_program;
}
const Features& Tracer::features() const {
  return d_->F;
}
const TracerOptions& Tracer::options() const {
  return d_->K;
}

std::string Tracer::source(const std::string& backend, Accuracy a) {
  return d_->kernel(backend, a).source();
}

RenderResult Tracer::render(const RenderSettings& rs, const Camera& camera) {
  Impl& I = *d_;
  const Scene& sc = I.scene;
  RenderResult r;
  r.backend = rs.backend;
  r.width = rs.width > 0 ? rs.width : 0;
  r.height = rs.height > 0 ? rs.height : 0;
  if (r.width == 0 || r.height == 0) throw std::runtime_error("render: image size not set");
  const int depth = rs.max_depth >= 0 ? rs.max_depth : sc.options.max_depth;
  const int spp = rs.spp > 0 ? rs.spp : sc.options.spp;
  if (rs.strategy == Strategy::Multipass) {
    I.set_camera(camera, r.width, r.height);
    return I.render_multipass(rs, r.width, r.height, depth, spp);
  }

  const auto t0 = std::chrono::steady_clock::now();
  Kernel& k = I.kernel(rs.backend, rs.accuracy);
  r.from_cache = k.info().cache_hit || k.info().from_disk_cache;
  add_stages(r, k.info());

  I.set_camera(camera, r.width, r.height);

  I.max_depth.set(depth);
  const int stack_factor = I.F.stack + 1;
  const int64_t iters =
      int64_t{depth + 1} * (static_cast<int64_t>(sc.lights.size()) + 1) * stack_factor * 2 + 8;

  Stream<Float3> color(r.width, r.height), normal(r.width, r.height);
  Stream<Float> dist(r.width, r.height);
  Stream<Int> prim(r.width, r.height), rays(r.width, r.height);
  k.outputs(color, dist, prim, normal, rays);
  // A first launch at this size that traces nothing (max_iter = 0): drivers that finish
  // compiling at the first launch of a size (PoCL, Mesa) do it here, so that the trace time
  // below is tracing alone. The ray count's reduction kernels compile here too.
  const auto warm_key =
      std::make_pair(rs.backend + "/" + accuracy_name(rs.accuracy), r.width * r.height);
  if (!I.warmed.count(warm_key)) {
    I.max_iter.set(0);
    k.execute();
    (void)rill::sum(rays);
    I.warmed.insert(warm_key);
  }
  I.max_iter.set(static_cast<int32_t>(std::min<int64_t>(iters, 1 << 30)));
  r.compile_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  const size_t npix = static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
  std::vector<glm::dvec3> sum(spp > 1 ? npix : 0, glm::dvec3(0.0));
  const auto start = std::chrono::steady_clock::now();
  for (int s = 0; s < spp; ++s) {
    I.offset.set(sample_offset(s));
    k.execute();
    ++r.launches;
    r.rays += rill::sum(rays);  // on the device: only the total comes back
    if (s == 0) {
      r.color = color.download();
      r.depth = dist.download();
      r.prim = prim.download();
      r.normal = normal.download();
      if (spp > 1)
        for (size_t p = 0; p < npix; ++p) sum[p] = glm::dvec3(r.color[p]);
    } else {
      std::vector<glm::vec3> c = color.download();
      for (size_t p = 0; p < npix; ++p) sum[p] += glm::dvec3(c[p]);
    }
  }
  if (spp > 1)
    for (size_t p = 0; p < npix; ++p) r.color[p] = glm::vec3(sum[p] / static_cast<double>(spp));
  r.trace_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<glm::vec3> Tracer::camera_rays(const std::string& backend, const Camera& camera,
                                           int width, int height, glm::vec2 offset) {
  Impl& I = *d_;
  if (!I.camera_program.valid()) I.camera_program = I.capture_camera();
  I.set_camera(camera, width, height);
  I.offset.set(offset);
  Kernel k = compile(I.camera_program, backend);
  Stream<Float3> dirs(width, height);
  k.outputs(dirs);
  k.execute();
  std::vector<glm::vec3> d = dirs.download();
  d.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  return d;
}

Kernel Tracer::intersect_kernel(const std::string& backend, Accuracy accuracy) {
  Impl& I = *d_;
  if (!I.intersect_program.valid()) I.intersect_program = I.capture_intersector();
  CompileOptions opt;
  opt.accuracy = accuracy;
  return compile(I.intersect_program, backend, opt);
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
