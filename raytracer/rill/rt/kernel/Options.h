// The tracer's accuracy knobs, fixed when a tracer is built: each selects different DSL code
// in the generated kernels (and so a different kernel; docs/accuracy.md, "The ray tracer's
// accuracy knobs"). The defaults are the recommended settings.
#pragma once

#include <string>

#include "rill/rt/kernel/Features.h"

namespace rt {

enum class TriangleTest {
  MollerTrumbore,  // Moller & Trumbore 1997: edges from v0, the determinant, u, v, t
  Watertight,      // Woop, Benthin & Wald 2013: shear to ray space, three 2D edge functions
};
enum class SelfIntersection {
  Epsilon,  // new rays start at P + eps * n, eps fixed per scene (its size)
  Scaled,   // Wachter & Binder 2019: P from the barycentrics, then a few ulps along n
};
enum class Traversal {
  Incremental,  // 3D-DDA: tMax += tDelta at each step (Amanatides & Woo)
  Recompute,    // tMax recomputed from the cell index at each step (no accumulated error)
};
// Whether a lane group walks the grid together (Intersector::walk_grid_together): the group
// visits one voxel at a time, the one of its rays furthest behind, and every ray tests that
// voxel's triangles. Auto: packets_for's rule (today off on every backend: measured slower,
// docs/benchmarks/2026-12-07-coherent.md); On: everywhere (a group of one walks alone: the
// same voxels as Off, in other code); Off: each ray walks alone. The hits are the same bits
// whichever (docs/raytracer.md, "Coherent traversal").
enum class Packets { Auto, On, Off };
// Deliberately broken variants of the path integrator, for its validation tests only
// (tests/raytracer/integrator/): each must be rejected by them. None is the integrator.
enum class PathMutation {
  None,
  NeeTwice,        // light samples counted twice
  NoMisAtHits,     // BSDF-sampled hits of lights weighed 1 although NEE counts them too
  NoRouletteBoost  // Russian roulette without dividing by the survival probability
};

// Defaults as measured (docs/accuracy.md): the scaled offset is far more accurate at no
// measurable cost; the watertight test costs 5-20% on the CPU for the rare hole; the
// recomputed traversal costs 5-30% and gains nothing measurable.
struct TracerOptions {
  TriangleTest triangle = TriangleTest::MollerTrumbore;
  SelfIntersection offset = SelfIntersection::Scaled;
  Traversal traversal = Traversal::Incremental;
  Packets packets = Packets::Auto;  // not an accuracy knob: the same bits either way
  Features extra_features;          // kernel features forced on (see the Tracer constructor)
  PathMutation mutation = PathMutation::None;  // tests only (above)
  std::string str() const;                     // "moller epsilon incremental"
};
// Parse the command-line names (moller|watertight, epsilon|scaled, incremental|recompute);
// throw std::invalid_argument naming the bad value.
TriangleTest parse_triangle_test(const std::string& s);
SelfIntersection parse_self_intersection(const std::string& s);
Traversal parse_traversal(const std::string& s);
Packets parse_packets(const std::string& s);  // auto|on|off
const char* packets_name(Packets p);
// Whether kernels for `backend` walk lane groups together under setting p. Auto resolves to
// off everywhere: on simd (8 lockstep lanes) the shared walk traced primary rays at 0.70-0.90x
// the speed of each lane walking alone (thesis A, B, C; full frames 0.81x on B and C); the
// other backends run groups of one, where it only adds code.
bool packets_for(Packets p, const std::string& backend);

}  // namespace rt
