// Reductions over a stream, computed by kernels on the device: sum, minimum, maximum, count,
// any and all.
//
//   Stream<Float> energy(n);  ...  float total = rill::sum(energy);
//   int64_t hits = rill::count(hit_flags);            // elements that are not 0
//   glm::vec3 lo = rill::minimum(points);             // componentwise
//
// They run on the backend that holds the stream's newest copy (the one whose kernel wrote it
// last), or on the backend named; only the result (one element) comes back to the host.
//
// Deterministic by construction: the combination order is fixed and does not depend on the
// backend, the thread count or the work-group size, so under strict the result has the same
// bits everywhere. The order, stated once here and in docs/programming-model.md:
//   - the elements are taken in blocks of kReduceBlock (64) consecutive elements (for a 2D
//     stream, consecutive elements of one row: rows are never mixed in a block);
//   - each block is folded left to right: ((x0 op x1) op x2) op ...;
//   - the block results, in order, form a stream that is reduced the same way, until one
//     element is left.
// Each level is one launch of a Rill kernel that gathers its block from the previous level.
//
// The kernels and partial streams that reduce a stream are kept and reused by its later
// reductions (no capture or allocation per call). They hold the stream: its data is released
// at the first reduction after the last user handle is dropped.
//
// Meanings: sum adds in the order above (an Int sum wraps around modulo 2^32); minimum and
// maximum use the DSL's min and max (a NaN is kept only where it comes first in its fold);
// count, any and all read a Stream<Int> as truth values (not 0 is true); count is an Int sum
// (so it is exact below 2^31 elements).
// An empty stream gives the identity: 0 for sum and count, +inf (or INT32_MAX) for minimum,
// -inf (or INT32_MIN) for maximum, false for any and true for all.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "rill/Stream.h"

namespace rill {

enum class ReduceOp { Sum, Min, Max, Count, Any, All };

// Elements folded per block (and per launch level) by every reduction.
constexpr int kReduceBlock = 64;

namespace detail {
// Reduces s with op on the named backend ("" picks the backend that holds the newest copy, or
// cpu) and returns the result's words (s's element type; one Int for count, any and all).
std::array<uint32_t, 4> reduce(const StreamRef& s, ReduceOp op, const std::string& backend);

template <class V>
HostOf<V> host_value(const std::array<uint32_t, 4>& w) {
  HostOf<V> out;
  std::memcpy(&out, w.data(), sizeof out);
  return out;
}
}  // namespace detail

template <class V>
detail::HostOf<V> sum(const Stream<V>& s, const std::string& backend = {}) {
  return detail::host_value<V>(detail::reduce(s, ReduceOp::Sum, backend));
}
template <class V>
detail::HostOf<V> minimum(const Stream<V>& s, const std::string& backend = {}) {
  return detail::host_value<V>(detail::reduce(s, ReduceOp::Min, backend));
}
template <class V>
detail::HostOf<V> maximum(const Stream<V>& s, const std::string& backend = {}) {
  return detail::host_value<V>(detail::reduce(s, ReduceOp::Max, backend));
}
// Elements that are not 0.
inline int64_t count(const Stream<Int>& s, const std::string& backend = {}) {
  return static_cast<int32_t>(detail::reduce(s, ReduceOp::Count, backend)[0]);
}
inline bool any(const Stream<Int>& s, const std::string& backend = {}) {
  return detail::reduce(s, ReduceOp::Any, backend)[0] != 0;
}
inline bool all(const Stream<Int>& s, const std::string& backend = {}) {
  return detail::reduce(s, ReduceOp::All, backend)[0] != 0;
}

}  // namespace rill
