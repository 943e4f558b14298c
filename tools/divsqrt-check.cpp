// Proves the lean correctly rounded division and square root of the GLSL backends
// (backends/glsl/lean/div.glsl, sqrt.glsl) on the host: the GLSL text itself is compiled here
// as C++ (a few definitions make it so), with the host's fused fmaf for GLSL's fma and the
// driver's approximate operations MODELLED as worst cases: the driver's 1/b and inversesqrt(m)
// are every float within `--ulps K` steps (default 3) of the correctly rounded value, more
// than GLSL's bounds (2.5 ulp for /, 2 ulp for inversesqrt). Each result is compared bit for
// bit with IEEE's (the host's a / b and sqrtf, correctly rounded) under the semantics strict
// GLSL kernels define (DivSqrt.h): subnormal operands count as zero, results below the normal
// range flush to zero judging by the exact result, NaN results are the quiet NaN 0x7fc00000
// (sqrt of a positive NaN returns it).
//
//   divsqrt-check sqrt-all                every one of the 2^32 inputs, each ulp offset
//   divsqrt-check sqrt-significands       every significand of [1, 4), each offset
//   divsqrt-check div-random N [SEED]     N random pairs of significands, each offset
//   divsqrt-check div-bits N [SEED]       N random pairs of bit patterns (specials, ranges)
//   divsqrt-check div-hard N [SEED]       quotients next to a halfway point (the closest
//                                         there are), every divisor for chosen dividends
//   divsqrt-check div-edges N [SEED]      every pair of exponents for N significand pairs
// Exit status 1 and the first failures printed when a result differs, 2 for a bad command.
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

// The driver model: the correctly rounded value moved by g_step floats (up or down).
int g_step = 0;

// k floats up (down for k < 0) from a positive finite f: consecutive positive floats have
// consecutive bit patterns, across binades too.
float step_float(float f, int k) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  u += static_cast<uint32_t>(k);
  std::memcpy(&f, &u, sizeof f);
  return f;
}

}  // namespace

// GLSL as C++: what the helpers assume (GLSLEmitter.cpp's prelude, codegen/Helpers.h).
namespace glsl_model {
typedef uint32_t uint;
inline uint floatBitsToUint(float f) {
  uint u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}
inline float uintBitsToFloat(uint u) {
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}
// GLSL's fma where the driver's is fused. Declared here, it hides <cmath>'s double overloads,
// so a literal such as 0.5 becomes a float, as in GLSL.
inline float fma(float a, float b, float c) {
  return fmaf(a, b, c);
}
// The driver's a / b (only 1 / m is asked for, m in [1, 2)) and inversesqrt (m in [1, 4)).
inline float rill_native_div(float a, float b) {
  return step_float(static_cast<float>(static_cast<double>(a) / b), g_step);
}
inline float rill_native_rsqrt(float m) {
  return step_float(static_cast<float>(1.0 / std::sqrt(static_cast<double>(m))), g_step);
}
#define RILL_PRECISE
#define RILL_ONE 1.0f
#include "../backends/glsl/lean/div.glsl"
#include "../backends/glsl/lean/sqrt.glsl"
#undef RILL_PRECISE
#undef RILL_ONE
}  // namespace glsl_model

namespace {

uint32_t bits(float f) {
  return glsl_model::floatBitsToUint(f);
}
float from_bits(uint32_t u) {
  return glsl_model::uintBitsToFloat(u);
}
const uint32_t kQuietNaN = 0x7fc00000u;

// IEEE's result under strict GLSL's semantics (see the top of this file).
uint32_t ref_div(float a, float b) {
  uint32_t ua = bits(a), ub = bits(b);
  if (((ua >> 23) & 0xffu) == 0u) a = from_bits(ua & 0x80000000u);
  if (((ub >> 23) & 0xffu) == 0u) b = from_bits(ub & 0x80000000u);
  float q = a / b;
  if (std::isnan(q)) return kQuietNaN;
  // Tininess before rounding: the exact quotient, which double holds closely enough to
  // compare with 2^-126 (a quotient of floats is never within 2^-60 relative of it unless
  // equal).
  double exact = static_cast<double>(a) / static_cast<double>(b);
  if (std::fabs(exact) < 0x1p-126) return (ua ^ ub) & 0x80000000u;
  return bits(q);
}

uint32_t ref_sqrt(float x) {
  uint32_t u = bits(x);
  if (((u >> 23) & 0xffu) == 0u) return u & 0x80000000u;
  if (u & 0x80000000u) return kQuietNaN;
  if (std::isnan(x)) return u;
  return bits(std::sqrt(x));
}

int g_ulps = 3;
uint64_t g_checked = 0, g_failed = 0;

void fail(const char* op, float a, float b, uint32_t got, uint32_t want) {
  if (++g_failed <= 20)
    std::printf("FAIL %s(%a [%08" PRIx32 "], %a [%08" PRIx32
                "]) with the driver %+d steps: %08" PRIx32 ", IEEE %08" PRIx32 "\n",
                op, static_cast<double>(a), bits(a), static_cast<double>(b), bits(b), g_step, got,
                want);
}

void check_div(float a, float b) {
  const uint32_t want = ref_div(a, b);
  for (g_step = -g_ulps; g_step <= g_ulps; ++g_step) {
    ++g_checked;
    const uint32_t got = bits(glsl_model::rill_div_f(a, b));
    if (got != want) fail("div", a, b, got, want);
  }
}

void check_sqrt(float x) {
  const uint32_t want = ref_sqrt(x);
  for (g_step = -g_ulps; g_step <= g_ulps; ++g_step) {
    ++g_checked;
    const uint32_t got = bits(glsl_model::rill_sqrt(x));
    if (got != want) fail("sqrt", x, 0.0f, got, want);
  }
}

// splitmix64: a reproducible stream for the random cases.
uint64_t g_rng = 1;
uint64_t next_u64() {
  uint64_t z = (g_rng += 0x9e3779b97f4a7c15ull);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
uint32_t next_u32() {
  return static_cast<uint32_t>(next_u64() >> 32);
}
// A significand in [1, 2) with random fraction bits.
float significand(uint32_t r) {
  return from_bits(0x3f800000u | (r & 0x7fffffu));
}

int usage() {
  std::fprintf(stderr,
               "usage: divsqrt-check [--ulps K] sqrt-all | sqrt-significands | div-random N [SEED] "
               "| div-bits N [SEED] | div-hard N [SEED] | div-edges N [SEED]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int i = 1;
  if (i + 1 < argc && std::strcmp(argv[i], "--ulps") == 0) {
    g_ulps = std::atoi(argv[i + 1]);
    i += 2;
  }
  if (i >= argc) return usage();
  const std::string mode = argv[i];
  const bool counted = mode.rfind("div-", 0) == 0;
  if (counted && i + 1 >= argc) return usage();
  const uint64_t n = counted ? std::strtoull(argv[i + 1], nullptr, 10) : 0;
  g_rng = counted && i + 2 < argc ? std::strtoull(argv[i + 2], nullptr, 10) : 1;

  if (mode == "sqrt-all") {
    for (uint64_t u = 0; u <= 0xffffffffull; ++u) check_sqrt(from_bits(static_cast<uint32_t>(u)));
  } else if (mode == "sqrt-significands") {
    for (uint32_t u = 0x3f800000u; u < 0x40800000u; ++u) check_sqrt(from_bits(u));
  } else if (mode == "div-random") {
    for (uint64_t k = 0; k < n; ++k) check_div(significand(next_u32()), significand(next_u32()));
  } else if (mode == "div-bits") {
    // Random bit patterns, half of them with exponents near the ends of the range, where the
    // quotient overflows, underflows or is subnormal.
    for (uint64_t k = 0; k < n; ++k) {
      uint32_t a = next_u32(), b = next_u32();
      const uint32_t r = next_u32();
      if (r & 1u) a = (a & 0x807fffffu) | ((r >> 8) % 24u << 23) | ((r & 2u) ? 0x70000000u : 0u);
      if (r & 4u) b = (b & 0x807fffffu) | ((r >> 16) % 24u << 23) | ((r & 8u) ? 0x70000000u : 0u);
      check_div(from_bits(a), from_bits(b));
    }
  } else if (mode == "div-hard") {
    // Quotients next to a halfway point: for a random divisor b and a random 25-bit odd
    // midpoint m (between two floats of [1, 2)), a = m * b rounded is a dividend whose exact
    // quotient is within about an ulp of a's of the midpoint; its neighbours too.
    for (uint64_t k = 0; k < n; ++k) {
      const float b = significand(next_u32());
      const double mid = 1.0 + static_cast<double>((next_u32() & 0x7fffffu) * 2u + 1u) * 0x1p-24;
      const double a = mid * b;
      if (a >= 2.0) continue;  // the dividend must be a significand too
      const float fa = static_cast<float>(a);
      for (int s = -2; s <= 2; ++s) {
        const float x = step_float(fa, s);
        if (x >= 1.0f && x < 2.0f) check_div(x, b);
      }
    }
    // The hardest quotients: a / b - m = j / (b 2^S) for a 25-bit odd midpoint m and
    // j = +-1, +-2, +-3, the closest a quotient of floats comes to a midpoint (about 2^-24
    // ulp). With integer significands A, B (2^23 <= A, B < 2^24) and quotients in [1, 2)
    // (S = 24) or [1/2, 1) (S = 25): A 2^S - M B = j, so M = -j / B modulo 2^S, B odd.
    for (uint64_t k = 0; k < n; ++k) {
      const uint64_t B = (0x800000u | (next_u32() & 0x7fffffu)) | 1u;
      uint64_t inv = 1;  // B^-1 modulo 2^32 by Newton's iteration, each step doubling the bits
      for (int it = 0; it < 5; ++it) inv = (inv * (2 - B * inv)) & 0xffffffffull;
      for (int S = 24; S <= 25; ++S)
        for (int64_t j = -3; j <= 3; ++j) {
          if (j == 0) continue;
          const uint64_t mod = 1ull << S;
          const uint64_t M0 = (static_cast<uint64_t>(-j) * inv) & (mod - 1);
          const uint64_t M = S == 24 ? M0 + mod : M0;
          if (M < (1ull << 24) || M >= (1ull << 25) || (M & 1u) == 0) continue;
          const uint64_t num = M * B + static_cast<uint64_t>(j);
          const uint64_t A = num >> S;
          if ((num & (mod - 1)) != 0 || A < (1u << 23) || A >= (1u << 24)) continue;
          check_div(from_bits(0x3f800000u | static_cast<uint32_t>(A & 0x7fffffu)),
                    from_bits(0x3f800000u | static_cast<uint32_t>(B & 0x7fffffu)));
        }
    }
    // Every divisor significand for dividends at the ends of [1, 2) and a few inside.
    const float dividends[] = {1.0f, step_float(2.0f, -1), step_float(1.0f, 1),
                               1.5f, step_float(1.5f, 1),  step_float(1.5f, -1)};
    for (float a : dividends)
      for (uint32_t f = 0; f < (n < (1u << 23) ? n : (1u << 23)); ++f)
        check_div(a, from_bits(0x3f800000u | f));
  } else if (mode == "div-edges") {
    // Every pair of exponent fields (0 and 255 too: zeros, subnormals, infinities, NaNs) for
    // N pairs of significands, a third of them equal and a third adjacent: the exponent
    // arithmetic, overflow and the flush at the bottom of the range, at every boundary.
    for (uint64_t k = 0; k < n; ++k) {
      const uint32_t fa = next_u32() & 0x7fffffu;
      uint32_t fb = next_u32() & 0x7fffffu;
      if (k % 3 == 0) fb = fa;
      if (k % 3 == 1) fb = (fa + ((k & 4) ? 1u : 0x7fffffu)) & 0x7fffffu;
      const uint32_t signs = next_u32();
      for (uint32_t xa = 0; xa < 256; ++xa)
        for (uint32_t xb = 0; xb < 256; ++xb)
          check_div(from_bits((signs & 0x80000000u) | xa << 23 | fa),
                    from_bits((signs << 1 & 0x80000000u) | xb << 23 | fb));
    }
  } else {
    return usage();
  }
  std::printf("%s: %" PRIu64 " results checked (driver within %d steps), %" PRIu64
              " differ from IEEE\n",
              mode.c_str(), g_checked, g_ulps, g_failed);
  return g_failed == 0 ? 0 : 1;
}
