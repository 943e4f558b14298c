// Hard values, seeded random inputs, and the error measures.
#include <algorithm>
#include <cfloat>
#include <climits>
#include <cstdio>

#include "Suite.h"

namespace rill::conformance {

double ulp_of(double r) {
  double a = std::fabs(r);
  if (!(a >= static_cast<double>(FLT_MIN))) return std::ldexp(1.0, -149);
  if (a > static_cast<double>(FLT_MAX)) a = static_cast<double>(FLT_MAX);
  int e = 0;
  std::frexp(a, &e);  // a = m * 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 24);
}

double ulp_error(double got, double ref, double scale) {
  if (std::isnan(got) || std::isnan(ref))
    return std::isnan(got) && std::isnan(ref) ? 0 : std::numeric_limits<double>::infinity();
  if (got == ref) return 0;  // also equal infinities
  if (std::isinf(got) || std::isinf(ref)) return std::numeric_limits<double>::infinity();
  double unit = ulp_of(std::max(std::fabs(ref), std::fabs(scale)));
  return std::fabs(got - ref) / unit;
}

double ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b))
    return std::isnan(a) && std::isnan(b) ? 0 : std::numeric_limits<double>::infinity();
  auto key = [](float f) {
    int32_t i = std::bit_cast<int32_t>(f);
    return i >= 0 ? int64_t{i} : -int64_t{i & 0x7fffffff};
  };
  int64_t d = key(a) - key(b);
  return static_cast<double>(d < 0 ? -d : d);
}

const std::vector<float>& hard_floats() {
  static const std::vector<float> v = [] {
    std::vector<uint32_t> bits = {
        0x00000000u, 0x80000000u,  // +0, -0
        0x00000001u, 0x80000001u,  // smallest denormals
        0x007fffffu, 0x807fffffu,  // largest denormals
        0x00400000u,               // a middle denormal
        0x00800000u, 0x80800000u,  // FLT_MIN
        0x7f7fffffu, 0xff7fffffu,  // FLT_MAX
        0x7f800000u, 0xff800000u,  // infinities
        0x7fc00000u, 0xffc00000u,  // quiet NaN, negative quiet NaN
        0x7f800001u,               // a signaling NaN
        0x7fc12345u,               // a NaN with a payload
    };
    std::vector<float> out;
    for (uint32_t b : bits) out.push_back(float_of(b));
    for (float f :
         {1.0f,         -1.0f,       0.5f,          -0.5f,         2.0f,           -2.0f,
          3.0f,         1.5f,        -1.5f,         2.5f,          -2.5f,          0.1f,
          -0.75f,       3.14159274f, -3.14159274f,  1.57079637f,   0.785398185f,   2.71828183f,
          10.0f,        100.0f,      -100.0f,       1e-10f,        1e10f,          -1e10f,
          1e30f,        16777216.0f, 2147483520.0f, 2147483648.0f, -2147483648.0f, 88.7228394f,
          -103.972076f, 6434.0f,     0.99999994f,   1.00000012f})
      out.push_back(f);
    return out;
  }();
  return v;
}

const std::vector<int32_t>& hard_ints() {
  static const std::vector<int32_t> v = {
      0,       1,           -1,          2,          -2,
      3,       -7,          7,           31,         32,
      33,      -1 - 31,     -32,         63,         64,
      100,     -100,        65536,       16777217,   INT_MAX,
      INT_MIN, INT_MAX - 1, INT_MIN + 1, 0x55555555, static_cast<int32_t>(0xaaaaaaaau)};
  return v;
}

namespace {

uint32_t random_float_bits(Rng& rng, const Domain& d) {
  std::uniform_int_distribution<int> pick(0, 99);
  int k = pick(rng);
  if (k < 8) {  // a hard value
    const auto& h = hard_floats();
    return bits_of(h[std::uniform_int_distribution<size_t>(0, h.size() - 1)(rng)]);
  }
  if (k < 18) return static_cast<uint32_t>(rng());  // any bit pattern
  if (k < 38) {  // any finite magnitude: uniform exponent and mantissa, random sign
    uint32_t e = std::uniform_int_distribution<uint32_t>(0, 254)(rng);
    uint32_t m = static_cast<uint32_t>(rng()) & 0x007fffffu;
    uint32_t s = static_cast<uint32_t>(rng() & 1u) << 31;
    return s | (e << 23) | m;
  }
  if (k < 46) {  // integers and halves in the typical range (rounding edges)
    double v = std::round(std::uniform_real_distribution<double>(d.lo, d.hi)(rng) * 2) / 2;
    return bits_of(static_cast<float>(v));
  }
  return bits_of(static_cast<float>(std::uniform_real_distribution<double>(d.lo, d.hi)(rng)));
}

uint32_t random_int_bits(Rng& rng, const Domain& d) {
  std::uniform_int_distribution<int> pick(0, 99);
  int k = pick(rng);
  if (k < 10) {
    const auto& h = hard_ints();
    return static_cast<uint32_t>(h[std::uniform_int_distribution<size_t>(0, h.size() - 1)(rng)]);
  }
  if (k < 40) return static_cast<uint32_t>(rng());
  auto lo = static_cast<int64_t>(d.lo), hi = static_cast<int64_t>(d.hi);
  return static_cast<uint32_t>(
      static_cast<int32_t>(std::uniform_int_distribution<int64_t>(lo, hi)(rng)));
}

}  // namespace

void generate_inputs(Rng& rng, int64_t n, const std::vector<ir::Type>& types,
                     const std::vector<Domain>& domains, std::vector<Words>& out) {
  const size_t k = types.size();
  out.assign(k, Words{});
  for (size_t j = 0; j < k; ++j) out[j].assign(static_cast<size_t>(n * types[j].width), 0u);
  auto domain = [&](size_t j) { return j < domains.size() ? domains[j] : Domain{}; };
  auto hard = [&](size_t j, size_t h) -> uint32_t {
    if (types[j].is_float()) return bits_of(hard_floats()[h % hard_floats().size()]);
    return static_cast<uint32_t>(hard_ints()[h % hard_ints().size()]);
  };
  auto hard_count = [&](size_t j) {
    return types[j].is_float() ? hard_floats().size() : hard_ints().size();
  };
  // Values are laid out in "slots": slot s is component s % 4 of element s / 4, and input j
  // of width w takes the slots whose component is below w.
  const int64_t slots = n * 4;
  // The hard part: the cross product of the first two inputs' hard values (each input's
  // hard values in turn when there is one input; the others cycle through theirs).
  int64_t hard_slots = 0;
  if (k >= 1) {
    size_t a = hard_count(0);
    size_t b = k >= 2 ? hard_count(1) : 1;
    hard_slots = std::min<int64_t>(slots / 2, static_cast<int64_t>(a * b));
  }
  for (int64_t s = 0; s < slots; ++s) {
    int64_t e = s / 4;
    int c = static_cast<int>(s % 4);
    for (size_t j = 0; j < k; ++j) {
      if (c >= types[j].width) continue;
      uint32_t v;
      if (s < hard_slots) {
        size_t hs = static_cast<size_t>(s);
        if (j == 0)
          v = hard(0, k >= 2 ? hs / hard_count(1) : hs);
        else if (j == 1)
          v = hard(1, hs % hard_count(1));
        else
          v = hard(j, hs * 7 + j);
      } else {
        v = types[j].is_float() ? random_float_bits(rng, domain(j))
                                : random_int_bits(rng, domain(j));
      }
      out[j][static_cast<size_t>(e * types[j].width + c)] = v;
    }
  }
}

std::string describe_words(ir::Type t, const uint32_t* w) {
  std::string s = t.width > 1 ? "(" : "";
  char buf[64];
  for (int c = 0; c < t.width; ++c) {
    if (c) s += ", ";
    if (t.is_float())
      std::snprintf(buf, sizeof buf, "%.9g [%08x]", static_cast<double>(float_of(w[c])), w[c]);
    else
      std::snprintf(buf, sizeof buf, "%d", static_cast<int32_t>(w[c]));
    s += buf;
  }
  return s + (t.width > 1 ? ")" : "");
}

}  // namespace rill::conformance
