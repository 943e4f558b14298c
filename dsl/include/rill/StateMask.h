// Masked launches: run a kernel only on the elements whose state is in a set.
//
//   rill::Stream<Int> state(n);                        // one small integer per element
//   k.execute(rill::where(state, kWait));              // only where state == kWait
//   k.execute(rill::where(state, {kEnter, kWait}));    // where state is one of these
//
// This is the thesis's per-state pass (sections 4.3, 5.5): a multipass algorithm keeps a
// state per element and each pass should cost only what its own elements cost. A kernel
// could discard the others itself (RILL_DISCARD), but it would still be started for every
// element; a mask lets the backend skip them before the kernel body runs:
//   glsl    the mask is rendered into a stencil buffer and the kernel is drawn with the
//           stencil test, so rasterization culls masked fragments before shading (the
//           thesis's early-z culling; the stencil test is the same early per-fragment test);
//   cpu     the unchanged kernel runs over each run of consecutive selected elements,
//           found on the host (ranges without one cost only the scan);
//   opencl  each work-item tests the state first and returns.
// Semantics are the same on every backend: a masked-out element is not run, its outputs
// keep their previous values and it is not counted as written; Kernel::last_launch()
// reports how many elements were processed (selected by the mask) and written. The state
// is read as it was before the launch, even when the kernel also writes that stream.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

#include "rill/Stream.h"

namespace rill {

class StateMask {
 public:
  // At most this many values in one set (a GLSL uniform array of fixed size holds them).
  static constexpr size_t kMaxValues = 8;

  StateMask(StreamRef state, std::vector<int32_t> values)
      : state_(std::move(state)), values_(std::move(values)) {}
  const StreamRef& state() const { return state_; }
  const std::vector<int32_t>& values() const { return values_; }

 private:
  StreamRef state_;
  std::vector<int32_t> values_;
};

// The elements where state equals value.
inline StateMask where(const Stream<Int>& state, int32_t value) {
  return StateMask(state, {value});
}
// The elements where state is one of values (1 to StateMask::kMaxValues of them).
inline StateMask where(const Stream<Int>& state, std::initializer_list<int32_t> values) {
  return StateMask(state, std::vector<int32_t>(values));
}
// Type-erased form; the stream must hold Int elements (checked at launch).
inline StateMask where(StreamRef state, std::vector<int32_t> values) {
  return StateMask(std::move(state), std::move(values));
}

}  // namespace rill
