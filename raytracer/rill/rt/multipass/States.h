// The multipass strategy's per-pixel states (Multipass.h): the trace and path state values
// its kernels switch on and mask launches by, and the path records kept in streams between
// them (the ray, hit, AOV and traversal records are kernel/Records.h's).
#pragma once

#include <rill/Record.h>
#include <rill/rill.h>

namespace rt {
namespace mp {

// Trace states (TraceState::state).
constexpr int kNone = 0, kPending = 1, kEnter = 2, kWait = 3, kFinished = 4;
// Path states (PathState::state): ended, alive (a ray to trace or shade), alive with a
// surface to shade (shadow rays and combine).
constexpr int kPathEnded = 0, kPathAlive = 1, kPathSurface = 2;
constexpr int kBatch = 8;               // triangles an intersector pass tests per ray
constexpr double kTailFraction = 0.05;  // fewer rays than this left: one kernel finishes them

using rill::Float;
using rill::Float3;
using rill::Int;

// A pixel's path: its state (kPathEnded...), bounce depth, rays traced, weight and colour.
RILL_STRUCT(PathState, (Int, state), (Int, depth), (Int, rays), (Float, weight), (Float3, color));

// Every pass's prologue: an element whose state is not one this pass works on (`skip`) is
// left as it is, its outputs unwritten. With masked launches (Multipass.cpp) such elements
// are never run; without, they stop here.
inline void skip_where(const rill::Bool& skip) {
  RILL_IF(skip) {
    RILL_DISCARD;
  }
  RILL_ENDIF;
}

}  // namespace mp
}  // namespace rt
