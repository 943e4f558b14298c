// The suite's internals: cases, checks, inputs and error measures (see Conformance.h).
#pragma once

#include <rill/rill.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "Conformance.h"
#include "rill/ir/FlushModel.h"

namespace rill::conformance {

// ---- bits, flushing and ulps ------------------------------------------------------------------

inline uint32_t bits_of(float f) {
  return std::bit_cast<uint32_t>(f);
}
inline float float_of(uint32_t b) {
  return std::bit_cast<float>(b);
}
inline bool is_denormal(uint32_t b) {
  return (b & 0x7f800000u) == 0 && (b & 0x007fffffu) != 0;
}
// The denormal rule: a denormal becomes a zero of the same sign.
inline uint32_t flush_bits(uint32_t b) {
  return is_denormal(b) ? (b & 0x80000000u) : b;
}
inline bool is_nan_bits(uint32_t b) {
  return (b & 0x7fffffffu) > 0x7f800000u;
}

// The ulp of the binary32 binade holding |r| (2^-149 below FLT_MIN).
double ulp_of(double r);
// |got - ref| in ulps of max(|ref|, scale) (scale: the magnitude of the terms of a formula
// that cancels; 0 for a plain relative measure).
double ulp_error(double got, double ref, double scale = 0);
// Distance between two floats in ulps (adjacent floats are 1 apart, +0 and -0 are 0 apart);
// NaN vs NaN 0, NaN vs number: infinite.
double ulp_distance(float a, float b);

// ---- inputs -----------------------------------------------------------------------------------

using Words = std::vector<uint32_t>;

// One element's inputs, as the references see them. With daz set, denormal float inputs
// read as zeros of the same sign (the reference of a backend that flushes them).
struct Elem {
  const std::vector<Words>* words = nullptr;
  const std::vector<ir::Type>* types = nullptr;
  int64_t index = 0;
  bool daz = false;

  uint32_t w(int input, int c) const {
    const ir::Type& t = (*types)[static_cast<size_t>(input)];
    uint32_t b = (*words)[static_cast<size_t>(input)][static_cast<size_t>(index * t.width + c)];
    return daz && t.is_float() ? flush_bits(b) : b;
  }
  float f(int input, int c) const { return float_of(w(input, c)); }
  double d(int input, int c) const {
    const ir::Type& t = (*types)[static_cast<size_t>(input)];
    return t.is_float() ? static_cast<double>(f(input, c)) : static_cast<double>(i(input, c));
  }
  int32_t i(int input, int c) const { return static_cast<int32_t>(w(input, c)); }
};

// The random part of an input: a typical range for uniform values; the generator mixes in
// hard values, random magnitudes over every exponent and random bit patterns.
struct Domain {
  double lo = -100, hi = 100;
  bool integers = false;  // int inputs: uniform integers in [lo, hi] instead of floats
};

using Rng = std::mt19937_64;

// The hard values every float / int input starts with.
const std::vector<float>& hard_floats();
const std::vector<int32_t>& hard_ints();

// Fills each input stream (types[j], n elements) with hard values first (every pair of hard
// values for the first two inputs of the same kind: the cross product, component by
// component), then random values from domains[j] mixed with hard values.
void generate_inputs(Rng& rng, int64_t n, const std::vector<ir::Type>& types,
                     const std::vector<Domain>& domains, std::vector<Words>& out);

// ---- cases -------------------------------------------------------------------------------------

// One checked output of a case: component c of output `output` for element e should be
// ref(e, c). Several checks with the same op name form one table row.
struct Check {
  std::string op;
  std::string category;
  std::string form;  // "float4", "float", "float4,float", ...
  int output = 0;
  std::function<double(const Elem&, int c)> ref;
  // Fast mode: the operation's documented domain (beyond finite inputs and a finite result).
  std::function<bool(const Elem&, int c)> fast_domain;
  // Error unit for formulas that cancel: ulps of max(|ref|, scale(e, c)).
  std::function<double(const Elem&, int c)> scale;
};

struct Case {
  std::string name;
  std::string category;
  std::function<Program()> build;
  std::vector<Domain> domains;  // per input (default Domain{} when missing)
  // Custom inputs (replaces generate_inputs when set).
  std::function<void(Rng&, int64_t n, const std::vector<ir::Type>&, std::vector<Words>&)> generate;
  int64_t elements = 0;  // 0: Options::elements
  int64_t width = 0;     // >0: 2D streams of this width (element_coord)
  std::vector<Check> checks;

  // Control programs: every output compared bit for bit with the interpreter in every mode,
  // together with the number of elements written; one row named after the case.
  bool exact_program = false;
  // Initial contents of the outputs (what discarded elements keep); zero when unset.
  std::function<void(int64_t n, const std::vector<ir::Type>&, std::vector<Words>&)> prefill;
  // Launches: before each, set_launch(k) may change uniforms (no recompile).
  int launches = 1;
  std::function<void(int)> set_launch;
};

std::vector<Case> operation_cases();
// Whether an operation's double reference, rounded once to float, is its exact binary32
// result (exact and correctly rounded operations; for +, -, *, / and sqrt double rounding
// through binary64 is innocuous). Strict mode then also checks the result against it.
bool exact_reference(const std::string& op);
std::vector<Case> control_cases();

// The special-value table (docs/conformance.md): each entry is evaluated in one kernel.
struct Special {
  std::string label;     // "sqrt(-1)"
  std::string category;  // "float", "int", "vector", "conversion"
  // Evaluates the entry: float results go to rf (up to 4 components), int results to ri.
  std::function<void(const Float& x, const Float& y, const Float& z, const Int& i, const Int& j,
                     Float4& rf, Int& ri)>
      eval;
  float x = 0, y = 0, z = 0;
  int32_t i = 0, j = 0;
  bool int_result = false;
  int width = 1;                   // float result components
  std::vector<uint32_t> expected;  // bits (floats) or values (ints)
  std::string expected_text;       // as documented
  bool strict_only = false;        // the double mode gives another (documented) result
};
const std::vector<Special>& specials();
Case specials_case();

// The flush-to-zero model of a backend that flushes denormals (rill/ir/FlushModel.h): every
// arithmetic operation reads denormal operands as zeros and flushes denormal results.
using ir::flush_model;

// Shared by runner and tests.
std::string describe_words(ir::Type t, const uint32_t* w);

}  // namespace rill::conformance
