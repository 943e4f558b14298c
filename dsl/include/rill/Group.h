// Lane-group operations: what an element may learn from the other elements that run together
// with it (its lane group), as a SIMD backend's lanes or a GPU's sub-group.
//
// Which elements form a group, and how many, is the backend's (docs/programming-model.md has
// the table): the simd backend's lanes, the device's subgroups on vulkan and glsl-compute where
// the driver has the operations, and a group of one (the element alone) everywhere else;
// OpenCL sub-groups may come where a device has them. A lane is active when it holds an
// element that runs the operation, under the same control flow; inactive lanes contribute the
// identity: false to group_any, true to group_all, bit 0 to group_ballot and group_count,
// INT32_MAX to group_min, INT32_MIN to group_max, 0 to group_sum.
//
// Results are exact for the group the backend reports: a program whose outputs do not depend
// on the group (or that uses group_size() and lane_index() to make them not) gives the same
// bits on every backend. Float reductions are not offered: their rounding would depend on the
// group size.
#pragma once

#include "rill/Value.h"

namespace rill {

// How many lanes this element's group has (1 where the backend runs elements alone). Uniform
// over a launch on a given backend and device.
Int group_size();
// This element's lane in its group, 0 .. group_size() - 1.
Int lane_index();

// Whether b holds in some active lane / in every active lane of the group.
Bool group_any(const Bool& b);
Bool group_all(const Bool& b);
// The active lanes where b holds, as a 128-bit mask: bit (l % 32) of component l / 32 is
// lane l (component 0 is lanes 0..31). Bits of inactive lanes and of lanes past
// group_size() are 0.
Int4 group_ballot(const Bool& b);
// How many active lanes have b (the ballot's population count).
Int group_count(const Bool& b);

// The minimum, maximum and wrapping (two's complement) sum of x over the active lanes.
Int group_min(const Int& x);
Int group_max(const Int& x);
Int group_sum(const Int& x);

// x in lane `lane` of the group when that lane is active; otherwise (an inactive lane, or a
// lane outside 0 .. group_size() - 1) the element's own x.
Int group_broadcast(const Int& x, const Int& lane);
Float group_broadcast(const Float& x, const Int& lane);
Bool group_broadcast(const Bool& x, const Int& lane);

}  // namespace rill
