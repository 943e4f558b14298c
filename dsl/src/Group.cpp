// The lane-group operations of the DSL (rill/Group.h): each records one IR op of class Group
// (ir/Ops.def), which every backend's dialect spells (codegen::Dialect::group).
#include "rill/Group.h"

#include "rill/Capture.h"

namespace rill {

namespace {
template <class R, int W, class... Args>
Value<R, W> group_op(ir::Op op, const Args&... args) {
  return Value<R, W>(detail::emit(op, detail::type_of<R, W>(), {args.operand()...}),
                     detail::AdoptTag{});
}
}  // namespace

Int group_size() {
  return group_op<int32_t, 1>(ir::Op::GroupSize);
}
Int lane_index() {
  return group_op<int32_t, 1>(ir::Op::LaneIndex);
}
Bool group_any(const Bool& b) {
  return group_op<bool, 1>(ir::Op::GroupAny, b);
}
Bool group_all(const Bool& b) {
  return group_op<bool, 1>(ir::Op::GroupAll, b);
}
Int4 group_ballot(const Bool& b) {
  return group_op<int32_t, 4>(ir::Op::GroupBallot, b);
}
Int group_count(const Bool& b) {
  return group_op<int32_t, 1>(ir::Op::GroupCount, b);
}
Int group_min(const Int& x) {
  return group_op<int32_t, 1>(ir::Op::GroupMin, x);
}
Int group_max(const Int& x) {
  return group_op<int32_t, 1>(ir::Op::GroupMax, x);
}
Int group_sum(const Int& x) {
  return group_op<int32_t, 1>(ir::Op::GroupSum, x);
}
Int group_broadcast(const Int& x, const Int& lane) {
  return group_op<int32_t, 1>(ir::Op::GroupBroadcast, x, lane);
}
Float group_broadcast(const Float& x, const Int& lane) {
  return group_op<float, 1>(ir::Op::GroupBroadcast, x, lane);
}
Bool group_broadcast(const Bool& x, const Int& lane) {
  return group_op<bool, 1>(ir::Op::GroupBroadcast, x, lane);
}

}  // namespace rill
