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
  Features extra_features;  // kernel features forced on (see the Tracer constructor)
  PathMutation mutation = PathMutation::None;  // tests only (above)
  std::string str() const;                     // "moller epsilon incremental"
};
// Parse the command-line names (moller|watertight, epsilon|scaled, incremental|recompute);
// throw std::invalid_argument naming the bad value.
TriangleTest parse_triangle_test(const std::string& s);
SelfIntersection parse_self_intersection(const std::string& s);
Traversal parse_traversal(const std::string& s);

}  // namespace rt
