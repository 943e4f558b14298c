// The C dialect and the C translation unit the CPU backend compiles.
//
// Vectors are scalarized (one C variable per component), which gives the C compiler plain
// scalar code to optimize. Each kernel becomes one function, rill_run(launch, begin, end),
// that computes elements [begin, end) and returns how many it wrote; the runtime calls it
// from many threads on disjoint ranges.
#include "CEmitter.h"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "../codegen/CFamilyPrinter.h"

namespace rill::cpu {

using namespace ir;

namespace {

// Definitions of the rill_* helpers the printer calls (see CFamilyPrinter.h), in C99.
// rill_real is float, or double in the `double` accuracy mode.
const char* kPrelude = R"(#include <math.h>
#include <stdint.h>
#include <string.h>

typedef struct rill_launch {
  void* const* inputs;
  void* const* outputs;
  const uint32_t* uniforms;     /* 4 words per uniform */
  const void* const* arrays;
  const int64_t* array_shapes;  /* 3 per array */
  int64_t count, width, height;
} rill_launch;

static inline rill_real rill_ibits(int32_t i) { float f; memcpy(&f, &i, 4); return (rill_real)f; }
static inline int32_t rill_fbits(rill_real x) { float f = (float)x; int32_t i; memcpy(&i, &f, 4); return i; }
static inline rill_real rill_word_f(uint32_t w) { float f; memcpy(&f, &w, 4); return (rill_real)f; }
static inline float rill_store_f(rill_real x) { return (float)x; }

/* Integer arithmetic wraps (two's complement); division and remainder by zero give 0. */
static inline int32_t rill_add_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); }
static inline int32_t rill_sub_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a - (uint32_t)b); }
static inline int32_t rill_mul_i(int32_t a, int32_t b) { return (int32_t)((uint32_t)a * (uint32_t)b); }
static inline int32_t rill_neg_i(int32_t a) { return (int32_t)(0u - (uint32_t)a); }
static inline int32_t rill_div_i(int32_t a, int32_t b) {
  if (b == 0) return 0;
  if (b == -1) return rill_neg_i(a);
  return a / b;
}
static inline int32_t rill_mod_i(int32_t a, int32_t b) {
  if (b == 0 || b == -1) return 0;
  return a % b;
}
static inline int32_t rill_min_i(int32_t a, int32_t b) { return b < a ? b : a; }
static inline int32_t rill_max_i(int32_t a, int32_t b) { return a < b ? b : a; }
static inline int32_t rill_abs_i(int32_t a) { return a < 0 ? rill_neg_i(a) : a; }
static inline int32_t rill_sign_i(int32_t a) { return a > 0 ? 1 : (a < 0 ? -1 : 0); }
static inline int32_t rill_shl(int32_t a, int32_t b) { return (int32_t)((uint32_t)a << (b & 31)); }
static inline int32_t rill_shr(int32_t a, int32_t b) { return a >> (b & 31); }

/* Float helpers with one meaning on every backend. */
static inline rill_real rill_min_f(rill_real a, rill_real b) { return b < a ? b : a; }
static inline rill_real rill_max_f(rill_real a, rill_real b) { return a < b ? b : a; }
static inline rill_real rill_sign_f(rill_real x) { return x > 0 ? (rill_real)1 : (x < 0 ? (rill_real)-1 : (rill_real)0); }
static inline rill_real rill_abs_f(rill_real x) { return RILL_M(fabs)(x); }
static inline rill_real rill_floor(rill_real x) { return RILL_M(floor)(x); }
static inline rill_real rill_ceil(rill_real x) { return RILL_M(ceil)(x); }
static inline rill_real rill_fract(rill_real x) { rill_real f = RILL_M(floor)(x); return x - f; }
static inline rill_real rill_mod_f(rill_real a, rill_real b) {
  rill_real q = a / b;
  rill_real f = RILL_M(floor)(q);
  rill_real m = b * f;
  return a - m;
}
static inline rill_real rill_sqrt(rill_real x) { return RILL_M(sqrt)(x); }
static inline rill_real rill_rsqrt(rill_real x) { rill_real s = RILL_M(sqrt)(x); return (rill_real)1 / s; }
static inline rill_real rill_exp(rill_real x) { return RILL_M(exp)(x); }
static inline rill_real rill_log(rill_real x) { return RILL_M(log)(x); }
static inline rill_real rill_exp2(rill_real x) { return RILL_M(exp2)(x); }
static inline rill_real rill_log2(rill_real x) { return RILL_M(log2)(x); }
static inline rill_real rill_sin(rill_real x) { return RILL_M(sin)(x); }
static inline rill_real rill_cos(rill_real x) { return RILL_M(cos)(x); }
static inline rill_real rill_tan(rill_real x) { return RILL_M(tan)(x); }
static inline rill_real rill_atan(rill_real x) { return RILL_M(atan)(x); }
static inline rill_real rill_pow(rill_real x, rill_real y) { return RILL_M(pow)(x, y); }
static inline rill_real rill_atan2(rill_real y, rill_real x) { return RILL_M(atan2)(y, x); }
static inline rill_real rill_i2f(int32_t i) { return (rill_real)i; }
/* Truncation toward zero; NaN gives 0, out-of-range values saturate. */
static inline int32_t rill_f2i(rill_real x) {
  if (x != x) return 0;
  if (x >= (rill_real)2147483648.0) return 2147483647;
  if (x < (rill_real)-2147483648.0) return (int32_t)(-2147483647 - 1);
  return (int32_t)x;
}
/* Array index, clamped into [0, n). */
static inline int64_t rill_clamp_index(int32_t i, int64_t n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); }
)";

class CDialect : public codegen::Dialect {
 public:
  explicit CDialect(Accuracy a) : accuracy_(a) {}

  bool scalarize() const override { return true; }
  std::string scalar_type(ScalarKind k) const override {
    switch (k) {
      case ScalarKind::Float: return "rill_real";
      case ScalarKind::Int: return "int32_t";
      case ScalarKind::Bool: return "int";
    }
    return "?";
  }
  std::string vector_type(Type t) const override { return scalar_type(t.kind); }
  std::string literal(ScalarKind k, uint32_t bits) const override {
    switch (k) {
      case ScalarKind::Int:
        if (bits == 0x80000000u) return "(-2147483647 - 1)";
        return std::to_string(static_cast<int32_t>(bits));
      case ScalarKind::Bool: return bits ? "1" : "0";
      case ScalarKind::Float: {
        float v = std::bit_cast<float>(bits);
        if (v != v || v == INFINITY || v == -INFINITY) {
          char buf[48];
          std::snprintf(buf, sizeof buf, "rill_word_f(0x%08xu)", bits);
          return buf;
        }
        // The shortest decimal that reads back as this float, with the f suffix: C compilers
        // round float literals correctly, so the value is exact (and widens exactly to
        // double in double mode).
        char buf[48];
        auto r = std::to_chars(buf, buf + sizeof buf, v);
        std::string s(buf, r.ptr);
        if (s.find_first_of(".e") == std::string::npos) s += ".0";
        return s + "f";
      }
    }
    return "?";
  }
  std::string discard() const override { return "goto rill_discarded;"; }

  std::string initial_value(const Function& f, VarId v, int c) const override {
    const Variable& var = f.var(v);
    int w = var.type.width;
    std::string at = "[rill_i * " + std::to_string(w) + " + " + std::to_string(c) + "]";
    switch (var.role) {
      case VarRole::Input: return "in" + std::to_string(var.slot) + at;
      case VarRole::Output: return "out" + std::to_string(var.slot) + at;
      case VarRole::Uniform: return "u" + std::to_string(var.slot) + "_" + std::to_string(c);
      default:
        return literal(var.type.kind, 0);
    }
  }

  std::string gather(const Function& f, const Stmt& s, const std::vector<std::string>& index,
                     const std::vector<std::string>& dst) const override {
    const ArrayDecl& a = f.arrays.at(static_cast<size_t>(s.array));
    std::string id = std::to_string(s.array);
    std::string shape = "arr" + id + "_shape";
    // Clamp each index into its dimension, then linearize (x fastest).
    std::string lin = "rill_clamp_index(" + index[0] + ", " + shape + "[0])";
    if (index.size() > 1) lin += " + " + shape + "[0] * rill_clamp_index(" + index[1] + ", " + shape + "[1])";
    if (index.size() > 2)
      lin += " + " + shape + "[0] * " + shape + "[1] * rill_clamp_index(" + index[2] + ", " + shape + "[2])";
    std::string out = "{\n  const int64_t g = (" + lin + ") * " + std::to_string(a.elem.width) + ";\n";
    for (size_t c = 0; c < dst.size(); ++c) {
      std::string load = "arr" + id + "[g + " + std::to_string(c) + "]";
      out += "  " + dst[c] + " = " + (a.elem.is_float() ? "(rill_real)" : "") + load + ";\n";
    }
    return out + "}\n";
  }

  std::string element_index() const override { return "((int32_t)rill_i)"; }
  std::string element_coord(int c) const override {
    return c == 0 ? "((int32_t)(rill_i % L->width))" : "((int32_t)(rill_i / L->width))";
  }

 private:
  Accuracy accuracy_;
};

std::string c_elem_type(ScalarKind k) { return k == ScalarKind::Float ? "float" : "int32_t"; }

}  // namespace

std::string emit_c(const Function& f, Accuracy accuracy) {
  CDialect d(accuracy);
  codegen::CFamilyPrinter p(f, d);
  std::string src = "/* Generated by Rill from kernel '" + f.name + "' (" + accuracy_name(accuracy) +
                    "). */\n";
  if (accuracy == Accuracy::Double) src += "typedef double rill_real;\n#define RILL_M(fn) fn\n";
  else src += "typedef float rill_real;\n#define RILL_M(fn) fn##f\n";
  src += kPrelude;
  src += "\nint64_t rill_run(const rill_launch* L, int64_t rill_begin, int64_t rill_end) {\n";
  for (size_t i = 0; i < f.inputs.size(); ++i) {
    const Variable& v = f.var(f.inputs[i]);
    src += "  const " + c_elem_type(v.type.kind) + "* in" + std::to_string(i) + " = (const " +
           c_elem_type(v.type.kind) + "*)L->inputs[" + std::to_string(i) + "];\n";
  }
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    const Variable& v = f.var(f.outputs[i]);
    src += "  " + c_elem_type(v.type.kind) + "* out" + std::to_string(i) + " = (" +
           c_elem_type(v.type.kind) + "*)L->outputs[" + std::to_string(i) + "];\n";
  }
  for (size_t i = 0; i < f.uniforms.size(); ++i) {
    const Variable& v = f.var(f.uniforms[i]);
    for (int c = 0; c < v.type.width; ++c) {
      std::string word = "L->uniforms[" + std::to_string(i * 4 + static_cast<size_t>(c)) + "]";
      std::string value = v.type.is_float() ? "rill_word_f(" + word + ")" : "(" + d.scalar_type(v.type.kind) + ")" + word;
      src += "  const " + d.scalar_type(v.type.kind) + " u" + std::to_string(i) + "_" + std::to_string(c) + " = " + value + ";\n";
    }
  }
  for (size_t i = 0; i < f.arrays.size(); ++i) {
    std::string id = std::to_string(i);
    std::string t = c_elem_type(f.arrays[i].elem.kind);
    src += "  const " + t + "* arr" + id + " = (const " + t + "*)L->arrays[" + id + "];\n";
    src += "  const int64_t* arr" + id + "_shape = L->array_shapes + " + std::to_string(i * 3) + ";\n";
  }
  src += "  int64_t rill_written = 0;\n";
  src += "  for (int64_t rill_i = rill_begin; rill_i < rill_end; ++rill_i) {\n";
  src += p.declarations(2);
  src += p.body(2);
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    VarId v = f.outputs[i];
    const Variable& var = f.var(v);
    for (int c = 0; c < var.type.width; ++c) {
      std::string value = p.component(v, c);
      if (var.type.is_float()) value = "rill_store_f(" + value + ")";
      src += "    out" + std::to_string(i) + "[rill_i * " + std::to_string(var.type.width) + " + " +
             std::to_string(c) + "] = " + value + ";\n";
    }
  }
  src += "    ++rill_written;\n";
  src += "    continue;\n";
  src += "  rill_discarded:;\n";
  src += "  }\n  return rill_written;\n}\n";
  return src;
}

}  // namespace rill::cpu
