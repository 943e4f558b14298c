// Exact evaluation of IR operations on constants (used by constant_fold).
//
// Float operations are evaluated in binary32 one operation at a time: this file is compiled
// without FMA contraction (see CMakeLists.txt), and x86-64 float arithmetic is SSE, so each
// result is the correctly rounded binary32 value every strict backend produces. Operations
// whose result is not exactly specified (exp, sin, ...) are never folded.
#include <bit>
#include <cmath>
#include <limits>

#include "rill/passes/Passes.h"

namespace rill::passes {

namespace {
using ir::Constant;
using ir::Op;

float f_min(float a, float b) { return b < a ? b : a; }
float f_max(float a, float b) { return a < b ? b : a; }
float f_sign(float x) { return x > 0.0f ? 1.0f : (x < 0.0f ? -1.0f : 0.0f); }

int32_t i_wrap(int64_t v) { return static_cast<int32_t>(static_cast<uint32_t>(static_cast<uint64_t>(v))); }

std::optional<float> float_op(Op op, float a, float b) {
  switch (op) {
    case Op::Copy: return a;
    case Op::Neg: return -a;
    case Op::Add: return a + b;
    case Op::Sub: return a - b;
    case Op::Mul: return a * b;
    case Op::Div: return a / b;
    case Op::Mod: {
      float q = a / b;
      float fl = std::floor(q);
      float m = b * fl;
      return a - m;
    }
    case Op::Min: return f_min(a, b);
    case Op::Max: return f_max(a, b);
    case Op::Abs: return std::bit_cast<float>(std::bit_cast<uint32_t>(a) & 0x7fffffffu);
    case Op::Sign: return f_sign(a);
    case Op::Floor: return std::floor(a);
    case Op::Ceil: return std::ceil(a);
    case Op::Fract: {
      float fl = std::floor(a);
      return a - fl;
    }
    case Op::Sqrt: return std::sqrt(a);
    case Op::Rsqrt: {
      float s = std::sqrt(a);
      return 1.0f / s;
    }
    default: return std::nullopt;  // transcendental: backend-defined until Rill's own routines
  }
}

std::optional<int32_t> int_op(Op op, int32_t a, int32_t b) {
  switch (op) {
    case Op::Copy: return a;
    case Op::Neg: return i_wrap(-static_cast<int64_t>(a));
    case Op::Add: return i_wrap(static_cast<int64_t>(a) + b);
    case Op::Sub: return i_wrap(static_cast<int64_t>(a) - b);
    case Op::Mul: return i_wrap(static_cast<int64_t>(a) * b);
    case Op::Div: return b == 0 ? 0 : i_wrap(static_cast<int64_t>(a) / b);
    case Op::Mod: return b == 0 ? 0 : static_cast<int32_t>(static_cast<int64_t>(a) % b);
    case Op::Min: return b < a ? b : a;
    case Op::Max: return a < b ? b : a;
    case Op::Abs: return i_wrap(a < 0 ? -static_cast<int64_t>(a) : a);
    case Op::Sign: return a > 0 ? 1 : (a < 0 ? -1 : 0);
    case Op::BitAnd: return a & b;
    case Op::BitOr: return a | b;
    case Op::BitXor: return a ^ b;
    case Op::BitNot: return ~a;
    case Op::Shl: return static_cast<int32_t>(static_cast<uint32_t>(a) << (b & 31));
    case Op::Shr: return a >> (b & 31);
    default: return std::nullopt;
  }
}

template <class T>
std::optional<bool> compare(Op op, T a, T b) {
  switch (op) {
    case Op::Lt: return a < b;
    case Op::Le: return a <= b;
    case Op::Gt: return a > b;
    case Op::Ge: return a >= b;
    case Op::Eq: return a == b;
    case Op::Ne: return a != b;
    default: return std::nullopt;
  }
}

std::optional<bool> bool_op(Op op, bool a, bool b) {
  switch (op) {
    case Op::Copy: return a;
    case Op::And: return a && b;
    case Op::Or: return a || b;
    case Op::Not: return !a;
    case Op::Eq: return a == b;
    case Op::Ne: return a != b;
    default: return std::nullopt;
  }
}

int32_t float_to_int(float x) {
  if (x != x) return 0;
  if (x >= 2147483648.0f) return std::numeric_limits<int32_t>::max();
  if (x < -2147483648.0f) return std::numeric_limits<int32_t>::min();
  return static_cast<int32_t>(x);
}

}  // namespace

std::optional<Constant> fold(Op op, ir::Type result, const std::vector<Constant>& args) {
  Constant out;
  out.type = result;
  auto comp = [&](size_t a, int c) {  // component c of argument a, broadcasting scalars
    const Constant& k = args[a];
    return k.bits[static_cast<size_t>(k.type.width == 1 ? 0 : c)];
  };
  auto fbits = [&](size_t a, int c) { return std::bit_cast<float>(comp(a, c)); };
  auto ibits = [&](size_t a, int c) { return static_cast<int32_t>(comp(a, c)); };

  switch (op) {
    case Op::Dot: {
      float s = 0.0f;
      for (int c = 0; c < args[0].type.width; ++c) {
        float p = fbits(0, c) * fbits(1, c);
        s = c == 0 ? p : s + p;
      }
      out.bits[0] = std::bit_cast<uint32_t>(s);
      return out;
    }
    case Op::Cross: {
      auto a = [&](int c) { return fbits(0, c); };
      auto b = [&](int c) { return fbits(1, c); };
      float r[3];
      for (int c = 0; c < 3; ++c) {
        int i = (c + 1) % 3, j = (c + 2) % 3;
        float p = a(i) * b(j);
        float q = a(j) * b(i);
        r[c] = p - q;
      }
      for (int c = 0; c < 3; ++c) out.bits[static_cast<size_t>(c)] = std::bit_cast<uint32_t>(r[c]);
      return out;
    }
    case Op::Construct: {
      int i = 0;
      for (const Constant& k : args)
        for (int c = 0; c < k.type.width; ++c) out.bits[static_cast<size_t>(i++)] = k.bits[static_cast<size_t>(c)];
      return out;
    }
    case Op::Gather:
    case Op::ElementIndex:
    case Op::ElementCoord:
      return std::nullopt;
    default:
      break;
  }

  for (int c = 0; c < result.width; ++c) {
    uint32_t bits = 0;
    ir::ScalarKind in = args[0].type.kind;
    if (op == Op::Select) {
      bits = comp(0, c) ? comp(1, c) : comp(2, c);
    } else if (op == Op::IntToFloat) {
      bits = std::bit_cast<uint32_t>(static_cast<float>(ibits(0, c)));
    } else if (op == Op::FloatToInt) {
      bits = static_cast<uint32_t>(float_to_int(fbits(0, c)));
    } else if (op == Op::FloatBitsToInt || op == Op::IntBitsToFloat) {
      bits = comp(0, c);
    } else if (result.is_bool() && in != ir::ScalarKind::Bool) {
      std::optional<bool> r = in == ir::ScalarKind::Float
                                  ? compare(op, fbits(0, c), fbits(1, c))
                                  : compare(op, ibits(0, c), ibits(1, c));
      if (!r) return std::nullopt;
      bits = *r;
    } else if (in == ir::ScalarKind::Float) {
      auto r = float_op(op, fbits(0, c), args.size() > 1 ? fbits(1, c) : 0.0f);
      if (!r) return std::nullopt;
      bits = std::bit_cast<uint32_t>(*r);
    } else if (in == ir::ScalarKind::Int) {
      auto r = int_op(op, ibits(0, c), args.size() > 1 ? ibits(1, c) : 0);
      if (!r) return std::nullopt;
      bits = static_cast<uint32_t>(*r);
    } else {
      auto r = bool_op(op, comp(0, c) != 0, args.size() > 1 && comp(1, c) != 0);
      if (!r) return std::nullopt;
      bits = *r;
    }
    out.bits[static_cast<size_t>(c)] = bits;
  }
  return out;
}

}  // namespace rill::passes
