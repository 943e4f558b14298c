// The operation enum and the properties of each operation, read from the one table of
// them, Ops.def: what it accepts and returns, its traits, and how C-family printers spell it.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "rill/ir/Type.h"

namespace rill::ir {

enum class Op : uint8_t {
#define RILL_OP(name, spelling, arity, cls, ...) name,
#include "rill/ir/Ops.def"
#undef RILL_OP
};
// How many ops there are: Op values are 0 .. kOpCount - 1.
constexpr int kOpCount = 0
#define RILL_OP(...) +1
#include "rill/ir/Ops.def"
#undef RILL_OP
    ;

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
  Group,      // lane-group ops: scalar operands, typed by hand (see result_type)
};

// How a C-family printer spells an op on operands of one scalar kind (the *_form columns of
// Ops.def). `text` is the operator or the helper's name; `lanes` the lane-mask spelling of
// a LOGIC op.
enum class FormKind : uint8_t {
  None,      // not defined on this kind
  Copy,      // the operand itself
  Negate,    // float negation: (-a)
  Infix,     // (a text b)
  Prefix,    // (text a)
  Logic,     // on bools: (a text b) / (text a); lane masks use `lanes`
  Helper,    // rill_text(a, ...) in scalar code, rill_v_text(a, ...) in lockstep code
  Compare,   // a text b, through Dialect::compare (GLSL compares floats by bit pattern)
  FloatDiv,  // a / b, through Dialect::float_div (GLSL may need a correctly rounded helper)
  Select,    // c ? a : b, through Dialect::select
  Fixed,     // combines components in one fixed order (fixed_form_expr in codegen)
  Gather,    // a statement of its own, through Dialect::gather
  Element,   // the element's index or coordinate, through the dialect
  Group,     // a lane-group op, through Dialect::group
};
struct OpForm {
  FormKind kind = FormKind::None;
  const char* text = "";
  const char* lanes = "";
};

// Traits (the traits column of Ops.def).
enum OpTrait : uint8_t {
  kCommutes = 1,        // operands may be swapped
  kFlushes = 2,         // a flushing backend may flush its float operands and result
  kTranscendental = 4,  // not exactly specified: lowered in strict mode, never folded
  kGroup = 8,           // reads the active lanes of the group: never folded or deduplicated
};

struct OpInfo {
  const char* spelling;
  int arity;
  OpClass cls;
  uint8_t traits;
  OpForm forms[3];  // by operand ScalarKind: Float, Int, Bool

  bool has(OpTrait t) const { return (traits & t) != 0; }
  const OpForm& form(ScalarKind k) const { return forms[static_cast<int>(k)]; }
};

const OpInfo& op_info(Op op);
inline const char* op_name(Op op) { return op_info(op).spelling; }
bool is_componentwise(Op op);
// Pure ops can be folded, deduplicated and deleted when unused (all ops are pure today; the
// hook exists so a future op with an effect is handled in one place).
bool is_pure(Op op);
inline bool is_commutative(Op op) { return op_info(op).has(kCommutes); }
inline bool is_transcendental(Op op) { return op_info(op).has(kTranscendental); }
inline bool flushes_denormals(Op op) { return op_info(op).has(kFlushes); }
// A lane-group op whose result depends on which lanes of the group are active (the mask
// lockstep lowering appends as its last operand).
inline bool reads_group(Op op) { return op_info(op).has(kGroup); }

// The result type of `op` on operands of the given types, or nullopt with `why` filled in.
// Gather and Construct need context and are typed by their caller.
std::optional<Type> result_type(Op op, std::span<const Type> args, std::string* why);

}  // namespace rill::ir
