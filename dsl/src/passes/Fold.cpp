// Exact evaluation of IR operations on constants (used by constant_fold and the reference
// interpreter): each op's eval function, named by the eval column of ir/Ops.def and defined
// in ir/Eval.h, applied component by component.
#include <bit>
#include <type_traits>

#include "../ir/Eval.h"
#include "rill/passes/Passes.h"

namespace rill::passes {

namespace {
using ir::Constant;
using ir::Op;
using ir::ScalarKind;

// A component's bits as the C++ value of its kind, and back.
template <class T>
T unpack(uint32_t bits) {
  if constexpr (std::is_same_v<T, float>)
    return std::bit_cast<float>(bits);
  else if constexpr (std::is_same_v<T, int32_t>)
    return static_cast<int32_t>(bits);
  else
    return bits != 0;
}
template <class T>
uint32_t pack(T v) {
  if constexpr (std::is_same_v<T, float>)
    return std::bit_cast<uint32_t>(v);
  else if constexpr (std::is_same_v<T, int32_t>)
    return static_cast<uint32_t>(v);
  else
    return v ? 1u : 0u;
}

// Applies a componentwise eval function to the operands, each component read as T (select's
// condition as bool); nullopt when the function has no overload for T (eval::none has none).
template <class T, class Eval>
std::optional<Constant> componentwise(Op op, Eval eval, ir::Type result,
                                      const std::vector<Constant>& args) {
  auto comp = [&](size_t a, int c) {  // component c of argument a, broadcasting scalars
    const Constant& k = args[a];
    return k.bits[static_cast<size_t>(k.type.width == 1 ? 0 : c)];
  };
  Constant out;
  out.type = result;
  for (int c = 0; c < result.width; ++c) {
    std::optional<uint32_t> bits;
    auto apply = [&](auto... x) {
      if constexpr (std::is_invocable_v<Eval, decltype(x)...>) bits = pack(eval(x...));
    };
    switch (args.size()) {
      case 1:
        apply(unpack<T>(comp(0, c)));
        break;
      case 2:
        apply(unpack<T>(comp(0, c)), unpack<T>(comp(1, c)));
        break;
      case 3:
        if (op == Op::Select) apply(comp(0, c) != 0, unpack<T>(comp(1, c)), unpack<T>(comp(2, c)));
        break;
      default:
        break;
    }
    if (!bits) return std::nullopt;
    out.bits[static_cast<size_t>(c)] = *bits;
  }
  return out;
}

template <class Eval>
std::optional<Constant> evaluate(Op op, Eval eval, ir::Type result,
                                 const std::vector<Constant>& args) {
  if constexpr (std::is_invocable_v<Eval, ir::Type, const std::vector<Constant>&>) {
    return eval(result, args);  // a whole-value op (dot, cross, construct)
  } else {
    if (args.empty()) return std::nullopt;
    // The kind the op computes on: its operands' (select: its branches').
    switch (args[op == Op::Select ? 1 : 0].type.kind) {
      case ScalarKind::Float:
        return componentwise<float>(op, eval, result, args);
      case ScalarKind::Int:
        return componentwise<int32_t>(op, eval, result, args);
      case ScalarKind::Bool:
        return componentwise<bool>(op, eval, result, args);
    }
    return std::nullopt;
  }
}

}  // namespace

std::optional<Constant> fold(Op op, ir::Type result, const std::vector<Constant>& args) {
  namespace eval = ir::eval;
  switch (op) {
    // Each eval name is an overload set; the lambda makes it one callable object.
#define RILL_OP(name, spelling, arity, cls, traits, ff, fi, fb, fn) \
  case Op::name:                                                    \
    return evaluate(                                                \
        op, [](auto&&... x) -> decltype(fn(x...)) { return fn(x...); }, result, args);
#include "rill/ir/Ops.def"
#undef RILL_OP
  }
  return std::nullopt;
}

}  // namespace rill::passes
