// The types of Rill values: a scalar kind (float, int, bool) and a width of 1 to 4.
//
// Rill's IR is deliberately small-typed. `Float` is IEEE binary32 in the `strict` and `fast`
// accuracy modes and binary64 in `double` mode; the IR does not change between modes, only
// the code a backend emits for it. `Int` is a 32-bit two's-complement integer whose
// arithmetic wraps on overflow on every backend.
#pragma once

#include <cstdint>
#include <string>

namespace rill::ir {

enum class ScalarKind : uint8_t { Float, Int, Bool };

struct Type {
  ScalarKind kind = ScalarKind::Float;
  uint8_t width = 1;  // 1..4

  constexpr bool operator==(const Type&) const = default;
  constexpr bool is_float() const { return kind == ScalarKind::Float; }
  constexpr bool is_int() const { return kind == ScalarKind::Int; }
  constexpr bool is_bool() const { return kind == ScalarKind::Bool; }
  constexpr bool is_scalar() const { return width == 1; }
  constexpr Type with_width(int w) const { return Type{kind, static_cast<uint8_t>(w)}; }
  constexpr Type with_kind(ScalarKind k) const { return Type{k, width}; }

  // "float", "int3", "bool2": the same spelling the DSL uses (Float, Int3, Bool2).
  std::string str() const;
};

constexpr Type float_type(int w = 1) { return Type{ScalarKind::Float, static_cast<uint8_t>(w)}; }
constexpr Type int_type(int w = 1) { return Type{ScalarKind::Int, static_cast<uint8_t>(w)}; }
constexpr Type bool_type(int w = 1) { return Type{ScalarKind::Bool, static_cast<uint8_t>(w)}; }

const char* kind_name(ScalarKind k);

}  // namespace rill::ir
