// Counter-based random numbers (rill/Random.h) on every backend: Philox4x32-10 gives the
// known-answer vectors of Random123 (Salmon et al., the generator's authors), the same bits
// as a plain C++ reference over many counters, and unit floats that are uniform.
#include <array>
#include <cstdint>

#include "BackendTest.h"

namespace rill::testing {
namespace {

using I2 = glm::ivec2;
using I4 = glm::ivec4;

// Philox4x32-10 in plain C++, from the paper's definition; the known-answer test checks it too.
std::array<uint32_t, 4> philox_reference(std::array<uint32_t, 4> c, uint32_t k0, uint32_t k1) {
  auto mul = [](uint32_t a, uint32_t b) { return uint64_t{a} * b; };
  for (int round = 0; round < 10; ++round) {
    if (round > 0) {
      k0 += 0x9E3779B9u;
      k1 += 0xBB67AE85u;
    }
    const uint64_t p0 = mul(0xD2511F53u, c[0]), p1 = mul(0xCD9E8D57u, c[2]);
    c = {static_cast<uint32_t>(p1 >> 32) ^ c[1] ^ k0, static_cast<uint32_t>(p1),
         static_cast<uint32_t>(p0 >> 32) ^ c[3] ^ k1, static_cast<uint32_t>(p0)};
  }
  return c;
}

I4 to_i4(const std::array<uint32_t, 4>& u) {
  return I4(static_cast<int32_t>(u[0]), static_cast<int32_t>(u[1]), static_cast<int32_t>(u[2]),
            static_cast<int32_t>(u[3]));
}

Program philox_program() {
  return program("philox", [] {
    Input<Int4> counter("counter");
    Input<Int2> key("key");
    Output<Int4> bits("bits");
    bits = philox4x32(counter, key);
  });
}

class RandomTest : public BackendTest {};

// Random123's kat_vectors for philox4x32 with 10 rounds: counter, key, then the output.
TEST_P(RandomTest, PhiloxGivesTheKnownAnswers) {
  struct Kat {
    std::array<uint32_t, 4> counter;
    std::array<uint32_t, 2> key;
    std::array<uint32_t, 4> out;
  };
  const std::vector<Kat> kats = {
      {{0, 0, 0, 0}, {0, 0}, {0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}},
      {{0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff},
       {0xffffffff, 0xffffffff},
       {0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}},
      {{0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344},
       {0xa4093822, 0x299f31d0},
       {0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}},
  };
  std::vector<I4> counters;
  std::vector<I2> keys;
  for (const Kat& k : kats) {
    EXPECT_EQ(to_i4(philox_reference(k.counter, k.key[0], k.key[1])), to_i4(k.out))
        << "the C++ reference";
    counters.push_back(to_i4(k.counter));
    keys.push_back(I2(static_cast<int32_t>(k.key[0]), static_cast<int32_t>(k.key[1])));
  }
  std::vector<I4> got = run<Int4>(philox_program(), counters, keys);
  for (size_t i = 0; i < kats.size(); ++i) EXPECT_EQ(got[i], to_i4(kats[i].out)) << "vector " << i;
}

// Counters as a path tracer keys them (pixel, sample, bounce, purpose) and arbitrary keys:
// every bit as the reference computes it.
TEST_P(RandomTest, PhiloxEqualsTheReferenceForManyCounters) {
  std::mt19937 rng(48);
  std::vector<I4> counters;
  std::vector<I2> keys;
  for (int i = 0; i < 4096; ++i) {
    const bool structured = i < 2048;
    counters.push_back(structured ? I4(i, i % 7, i % 5, i % 3)
                                  : I4(static_cast<int32_t>(rng()), static_cast<int32_t>(rng()),
                                       static_cast<int32_t>(rng()), static_cast<int32_t>(rng())));
    keys.push_back(I2(static_cast<int32_t>(rng()), structured ? 0 : static_cast<int32_t>(rng())));
  }
  std::vector<I4> got = run<Int4>(philox_program(), counters, keys);
  int bad = 0;
  for (size_t i = 0; i < counters.size(); ++i) {
    const I4 c = counters[i];
    const I4 want =
        to_i4(philox_reference({static_cast<uint32_t>(c.x), static_cast<uint32_t>(c.y),
                                static_cast<uint32_t>(c.z), static_cast<uint32_t>(c.w)},
                               static_cast<uint32_t>(keys[i].x), static_cast<uint32_t>(keys[i].y)));
    if (got[i] != want && ++bad <= 5) ADD_FAILURE() << "counter " << i << " differs";
  }
  EXPECT_EQ(bad, 0);
}

// 4 x 65536 unit floats (counters 0..65535, one key) in 256 equal bins. For uniform,
// independent values Pearson's statistic follows chi-square with 255 degrees of freedom; its
// 1 - 1e-6 quantile, by Wilson and Hilferty's approximation
// v (1 - 2/(9v) + z sqrt(2/(9v)))^3 with z = 4.753, is 377.3. The bits are fixed, so this
// passes or fails the same way every run: a correct generator fails it with probability 1e-6
// over the choice of key, and a mapping that is not onto [0, 1) (a sign-extending shift,
// values of [-0.5, 0.5)) fails it by far.
TEST_P(RandomTest, UnitFloatsFillTheUnitIntervalUniformly) {
  Program p = program("philox_unit", [] {
    Input<Int4> counter("counter");
    Output<Float4> u("u");
    u = unit_float(philox4x32(counter, Int2(20261207, 0)));
  });
  std::vector<I4> counters;
  for (int i = 0; i < 65536; ++i) counters.push_back(I4(i, 0, 0, 0));
  std::vector<glm::vec4> got = run<Float4>(p, counters);
  std::vector<double> bins(256, 0.0);
  int outside = 0;
  for (const glm::vec4& v : got)
    for (int c = 0; c < 4; ++c) {
      if (!(v[c] >= 0.0f && v[c] < 1.0f)) {
        ++outside;
        continue;
      }
      bins[static_cast<size_t>(v[c] * 256.0f)] += 1.0;
    }
  EXPECT_EQ(outside, 0) << "values outside [0, 1)";
  const double expected = 4.0 * 65536.0 / 256.0;
  double chi2 = 0.0;
  for (double b : bins) chi2 += (b - expected) * (b - expected) / expected;
  EXPECT_LT(chi2, 377.3) << "Pearson's chi-square over 256 bins";
}

// The example of docs/programming-model.md ("Random numbers"), as written there.
TEST_P(RandomTest, TheDocumentedJitterExampleRuns) {
  Uniform<Int> seed(7, "seed"), sample(0, "sample");
  Program p = program("jitter", [&] {
    Output<Float2> offset("offset");
    Int4 bits = philox4x32(Int4(element_index(), sample, 0, 0), Int2(seed, 0));
    Float4 u = unit_float(bits);
    offset = u.xy() - 0.5f;
  });
  sample.set(3);
  std::vector<glm::vec2> got = run_n<Float2>(p, 64);
  for (int i = 0; i < 64; ++i) {
    const auto r = philox_reference({static_cast<uint32_t>(i), 3, 0, 0}, 7, 0);
    const glm::vec2 want(static_cast<float>(r[0] >> 8) / 16777216.0f - 0.5f,
                         static_cast<float>(r[1] >> 8) / 16777216.0f - 0.5f);
    EXPECT_EQ(got[static_cast<size_t>(i)], want) << "element " << i;
  }
}

RILL_BACKEND_TEST_SUITE(RandomTest);

}  // namespace
}  // namespace rill::testing
