// The operation enum and what each operation accepts and returns (the table is Ops.def).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "rill/ir/Type.h"

namespace rill::ir {

enum class Op : uint8_t {
#define RILL_OP(name, spelling, arity, cls) name,
#include "rill/ir/Ops.def"
#undef RILL_OP
};

enum class OpClass : uint8_t {
  Any,        // any type in, same type out
  Arith,      // float or int, same kind out
  FloatMath,  // float only
  IntBits,    // int only
  Logic,      // bool only
  Order,      // float or int in, bool out
  Equality,   // any kind in, bool out
  Select,     // (bool, T, T) -> T
  Convert,    // kind changes, width kept
  Special,    // typed by hand (see result_type)
};

struct OpInfo {
  const char* spelling;
  int arity;
  OpClass cls;
};

const OpInfo& op_info(Op op);
inline const char* op_name(Op op) { return op_info(op).spelling; }
bool is_componentwise(Op op);
// Pure ops can be folded, deduplicated and deleted when unused (all ops are pure today; the
// hook exists so a future op with an effect is handled in one place).
bool is_pure(Op op);
bool is_commutative(Op op);

// The result type of `op` on operands of the given types, or nullopt with `why` filled in.
// Gather and Construct need context and are typed by their caller.
std::optional<Type> result_type(Op op, std::span<const Type> args, std::string* why);

}  // namespace rill::ir
