#include "rill/ir/Ops.h"

#include <algorithm>
#include <array>

namespace rill::ir {

namespace {
// The spellings of Ops.def's columns, as OpInfo fields.
#define COMMUTES kCommutes
#define FLUSHES kFlushes
#define TRANSCENDENTAL kTranscendental
#define GROUPED kGroup
#define NONE OpForm{}
#define COPY OpForm{FormKind::Copy}
#define NEGATE OpForm{FormKind::Negate}
#define INFIX(t) OpForm{FormKind::Infix, t}
#define PREFIX(t) OpForm{FormKind::Prefix, t}
#define LOGIC(t, lanes) OpForm{FormKind::Logic, t, lanes}
#define HELPER(t) OpForm{FormKind::Helper, t}
#define COMPARE(t) OpForm{FormKind::Compare, t}
#define FLOAT_DIV OpForm{FormKind::FloatDiv}
#define SELECT OpForm{FormKind::Select}
#define FIXED OpForm{FormKind::Fixed}
#define GATHER OpForm{FormKind::Gather}
#define ELEMENT OpForm{FormKind::Element}
#define GROUP OpForm{FormKind::Group}
constexpr OpInfo kOps[] = {
#define RILL_OP(name, spelling, arity, cls, traits, ff, fi, fb, eval) \
  {spelling, arity, OpClass::cls, static_cast<uint8_t>(traits), {ff, fi, fb}},
#include "rill/ir/Ops.def"
#undef RILL_OP
};
#undef COMMUTES
#undef FLUSHES
#undef TRANSCENDENTAL
#undef NONE
#undef COPY
#undef NEGATE
#undef INFIX
#undef PREFIX
#undef LOGIC
#undef HELPER
#undef COMPARE
#undef FLOAT_DIV
#undef SELECT
#undef FIXED
#undef GATHER
#undef ELEMENT
#undef GROUP
#undef GROUPED

// Operands of a componentwise op must have the result's width or width 1 (broadcast).
std::optional<int> common_width(std::span<const Type> args, std::string* why) {
  int w = 1;
  for (const Type& t : args) w = std::max<int>(w, t.width);
  for (const Type& t : args) {
    if (t.width != 1 && t.width != w) {
      if (why) *why = "operand widths differ (" + std::to_string(t.width) + " vs " +
                      std::to_string(w) + "); use a swizzle or a scalar";
      return std::nullopt;
    }
  }
  return w;
}

bool same_kind(std::span<const Type> args, std::string* why) {
  for (const Type& t : args) {
    if (t.kind != args[0].kind) {
      if (why) *why = std::string("operand kinds differ (") + kind_name(args[0].kind) + " vs " +
                      kind_name(t.kind) + "); convert explicitly";
      return false;
    }
  }
  return true;
}
}  // namespace

const OpInfo& op_info(Op op) { return kOps[static_cast<size_t>(op)]; }

bool is_componentwise(Op op) {
  return op_info(op).cls != OpClass::Special && op_info(op).cls != OpClass::Group;
}
bool is_pure(Op) { return true; }

std::optional<Type> result_type(Op op, std::span<const Type> args, std::string* why) {
  const OpInfo& info = op_info(op);
  auto fail = [&](std::string m) -> std::optional<Type> {
    if (why) *why = std::string(info.spelling) + ": " + m;
    return std::nullopt;
  };
  // Lockstep lowering appends the active-lane mask (a scalar bool) to a GROUPED op.
  if (info.has(kGroup) && static_cast<int>(args.size()) == info.arity + 1) {
    if (args.back() != bool_type(1)) return fail("the active-lane mask must be a scalar bool");
    args = args.first(args.size() - 1);
  }
  if (info.arity >= 0 && static_cast<int>(args.size()) != info.arity)
    return fail("expects " + std::to_string(info.arity) + " operands, got " +
                std::to_string(args.size()));
  auto width = [&](std::span<const Type> a) { return common_width(a, why); };
  switch (info.cls) {
    case OpClass::Any:
      return args[0];
    case OpClass::Arith:
    case OpClass::FloatMath:
    case OpClass::IntBits:
    case OpClass::Logic:
    case OpClass::Order:
    case OpClass::Equality: {
      if (!same_kind(args, why)) return std::nullopt;
      auto w = width(args);
      if (!w) return std::nullopt;
      ScalarKind k = args[0].kind;
      bool ok = (info.cls == OpClass::Arith && k != ScalarKind::Bool) ||
                (info.cls == OpClass::FloatMath && k == ScalarKind::Float) ||
                (info.cls == OpClass::IntBits && k == ScalarKind::Int) ||
                (info.cls == OpClass::Logic && k == ScalarKind::Bool) ||
                (info.cls == OpClass::Order && k != ScalarKind::Bool) ||
                info.cls == OpClass::Equality;
      if (!ok) return fail(std::string("not defined on ") + kind_name(k));
      bool to_bool = info.cls == OpClass::Order || info.cls == OpClass::Equality;
      return Type{to_bool ? ScalarKind::Bool : k, static_cast<uint8_t>(*w)};
    }
    case OpClass::Select: {
      if (!args[0].is_bool()) return fail("condition must be bool");
      if (args[1].kind != args[2].kind) return fail("branches have different kinds");
      auto w = width(args);
      if (!w) return std::nullopt;
      return args[1].with_width(*w);
    }
    case OpClass::Convert: {
      ScalarKind from =
          (op == Op::IntToFloat || op == Op::IntBitsToFloat || op == Op::UnitFloat)
              ? ScalarKind::Int
              : ScalarKind::Float;
      if (args[0].kind != from) return fail(std::string("expects ") + kind_name(from));
      ScalarKind to = from == ScalarKind::Int ? ScalarKind::Float : ScalarKind::Int;
      return args[0].with_kind(to);
    }
    case OpClass::Special:
      switch (op) {
        case Op::Dot:
          if (!args[0].is_float() || args[0] != args[1]) return fail("expects two equal float vectors");
          return float_type(1);
        case Op::Cross:
          if (args[0] != float_type(3) || args[1] != float_type(3)) return fail("expects float3 operands");
          return float_type(3);
        case Op::ElementIndex:
          return int_type(1);
        case Op::ElementCoord:
          return int_type(2);
        default:
          return fail("typed by its caller");
      }
    case OpClass::Group: {
      for (const Type& t : args)
        if (t.width != 1) return fail("expects scalar operands, got " + t.str());
      switch (op) {
        case Op::GroupSize:
        case Op::LaneIndex:
          return int_type(1);
        case Op::GroupAny:
        case Op::GroupAll:
          if (!args[0].is_bool()) return fail("expects a Bool");
          return bool_type(1);
        case Op::GroupBallot:
        case Op::GroupCount:
          if (!args[0].is_bool()) return fail("expects a Bool");
          return int_type(op == Op::GroupBallot ? 4 : 1);
        case Op::GroupMin:
        case Op::GroupMax:
        case Op::GroupSum:
          if (!args[0].is_int()) return fail("expects an Int (float reductions are not offered)");
          return int_type(1);
        case Op::GroupBroadcast:
          if (!args[1].is_int()) return fail("the lane must be an Int");
          return args[0];
        default:
          break;
      }
      return fail("unknown group op");
    }
  }
  return fail("unknown op");
}

}  // namespace rill::ir
