// The wavefront strategy's work items as they wait in streams between its kernels
// (Wavefront.h): the path integrator's records (integrator/PathIntegrator.h); the camera ray's
// AOVs are kernel/Records.h's Aov. Streams hold Float and Int fields only, so the Bool fields are
// stored as Int (0 or 1); and fields are packed into vectors of up to four (the ray's origin with
// its extent, the path's integers together), since on the glsl backend every field of a kernel's
// records is a texture unit, of which a kernel has 32 with the scene's arrays. The state fields the
// launches are masked on (done, active) stay fields of their own. Loading and storing move
// values and nothing else: a float goes to its stream and comes back with the same bits, so
// the stages compute what the megakernel's loop computes.
#pragma once

#include <rill/Record.h>
#include <rill/rill.h>

#include "rill/rt/integrator/PathIntegrator.h"
#include "rill/rt/render/BounceRays.h"

namespace rt {
namespace wf {

using rill::Bool;
using rill::Float;
using rill::Float3;
using rill::Float4;
using rill::Int;
using rill::Int3;

// PathItem: o = (ray.o, ray.tmax), d = (ray.d, bsdf_pdf), ints = (depth, delta, rays), done.
RILL_STRUCT(PathRecord, (Float4, o), (Float4, d), (Float3, radiance), (Float3, throughput),
            (Int3, ints), (Int, done));
// ShadowQuery: o = (ray.o, ray.tmax), d = ray.d, contribution, active (the shadow kernel sets
// it to 0 once traced).
RILL_STRUCT(ShadowRecord, (Float4, o), (Float3, d), (Float3, contribution), (Int, active));
// Hit: tuv = (t, uv), id.
RILL_STRUCT(HitRecord, (Float3, tuv), (Int, id));

inline Int as_int(const Bool& b) {
  return select(b, Int(1), Int(0));
}

// `done` given: the shade stage runs only on the paths not done and need not read it.
inline PathItem load(const PathRecord& r, const Bool& done) {
  return PathItem{Ray{r.o.xyz(), r.d.xyz(), r.o.w()},
                  r.radiance,
                  r.throughput,
                  r.ints.x(),
                  r.d.w(),
                  r.ints.y() != 0,
                  done,
                  r.ints.z()};
}
inline PathRecord store(const PathItem& p) {
  return PathRecord{Float4(p.ray.o, p.ray.tmax),
                    Float4(p.ray.d, p.bsdf_pdf),
                    p.radiance,
                    p.throughput,
                    Int3(p.depth, as_int(p.delta), p.rays),
                    as_int(p.done)};
}
inline ShadowRecord store(const ShadowQuery& q) {
  return ShadowRecord{Float4(q.ray.o, q.ray.tmax), q.ray.d, q.contribution, as_int(q.active)};
}
inline Hit load(const HitRecord& r) {
  return Hit{r.tuv.x(), r.tuv(1, 2), r.id};
}
inline HitRecord store(const Hit& h) {
  return HitRecord{Float3(h.t, h.uv), h.id};
}

// Appends to `out` the rays of the paths in `paths` (the window's width x height) that are not
// done, as sample `sample`'s (render/BounceRays.h: BounceRays.cpp). Each must have taken
// out.bounce scatterings; std::logic_error if one has not (the strategy read it back at the
// wrong stage).
void append_bounce_rays(const rill::Stream<PathRecord>& paths, int width, int height, int sample,
                        BounceRays& out);

}  // namespace wf
}  // namespace rt
