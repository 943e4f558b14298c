// The fixture every backend test uses: tests are written once and instantiated for each
// backend registered in this build (rill::backends()). A backend that cannot run on this
// machine skips its tests, with the reason it gives.
//
//   TEST_P(MyTest, Doubles) {
//     auto p = rill::program("twice", [] {
//       rill::Input<rill::Float> x("x");
//       rill::Output<rill::Float> y("y");
//       y = x * 2.0f;
//     });
//     std::vector<float> xs = sweep_floats(1, 4096);
//     std::vector<float> got = run<rill::Float>(p, xs);
//     EXPECT_TRUE(bits_equal(got, map(xs, [](float x) { return x * 2.0f; })));
//   }
//   RILL_BACKEND_TEST_SUITE(MyTest);
//
// Helpers here: compile()/run() (launch a program over host vectors, get host vectors back),
// bitwise and ulp comparisons that name the failing elements, and seeded input generators
// that mix hard values (signed zeros, denormals, infinities, NaN, extremes) into random data.
#pragma once

#include <gtest/gtest.h>
#include <xmmintrin.h>
#include <rill/rill.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>
#include "ParamName.h"

namespace rill::testing {

// ---- backends -------------------------------------------------------------------------------

inline std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (Backend* b : rill::backends()) names.push_back(b->name());
  return names;
}

// The DSL type for a host element type (float -> Float, glm::ivec3 -> Int3, ...).
template <class H>
struct DslOf;
template <>
struct DslOf<float> {
  using type = Float;
};
template <>
struct DslOf<int32_t> {
  using type = Int;
};
template <int N, class T>
struct DslOf<glm::vec<N, T, glm::defaultp>> {
  using type = Value<T, N>;
};
template <class V>
using HostOf = typename V::host_type;

// Scalar components of host elements, flattened (glm vectors are tightly packed).
template <class H>
struct ScalarOf {
  using type = H;
  static constexpr int width = 1;
};
template <int N, class T>
struct ScalarOf<glm::vec<N, T, glm::defaultp>> {
  using type = T;
  static constexpr int width = N;
};
template <class H>
std::vector<typename ScalarOf<H>::type> flatten(const std::vector<H>& v) {
  std::vector<typename ScalarOf<H>::type> out(v.size() * ScalarOf<H>::width);
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size() * 4);
  return out;
}
template <class H, class S>
std::vector<H> unflatten(const std::vector<S>& v) {
  std::vector<H> out(v.size() / ScalarOf<H>::width);
  if (!out.empty()) std::memcpy(out.data(), v.data(), out.size() * sizeof(H));
  return out;
}

// ---- the denormal rule ----------------------------------------------------------------------
// docs/accuracy.md: a backend may flush denormals to zero (llvmpipe's GLSL does); results are then
// compared after flushing both sides, and inputs carry no denormals (a flushing backend reads
// them as zero, the C++ reference would not). Set per test by BackendTest::SetUp.
inline bool& flushes_denormals() {
  static bool flag = false;
  return flag;
}
inline bool is_denormal(float f) { return f != 0.0f && std::fabs(f) < std::numeric_limits<float>::min(); }
inline float flush(float f) { return is_denormal(f) ? std::copysign(0.0f, f) : f; }

// Does this backend flush? The smallest denormal doubled tells (x * 1 would not: shader
// compilers drop the multiplication).
inline bool probe_flushes_denormals(const std::string& backend) {
  static std::map<std::string, bool> known;
  auto it = known.find(backend);
  if (it != known.end()) return it->second;
  Program p = program("denormal_probe", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  Kernel k = rill::compile(p, backend);
  Stream<Float> in(std::vector<float>{std::numeric_limits<float>::denorm_min()}), out(1);
  k.inputs(in).outputs(out);
  k.execute();
  bool flushes = out.download()[0] == 0.0f;
  known[backend] = flushes;
  return flushes;
}

class BackendTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::string why = rill::backend(GetParam()).unavailable_reason();
    if (!why.empty()) GTEST_SKIP() << "backend '" << GetParam() << "' is not available: " << why;
    flushes_denormals() = probe_flushes_denormals(GetParam());
    if (flushes_denormals())
      RecordProperty("denormals", "flushed to zero: compared after flushing both sides");
  }

  const std::string& backend_name() const { return GetParam(); }
  bool supports(Accuracy a) const { return rill::backend(GetParam()).supports(a); }

  Kernel compile(const Program& p, Accuracy a = Accuracy::Strict, PassOptions passes = {}) {
    CompileOptions o;
    o.accuracy = a;
    o.passes = passes;
    return rill::compile(p, GetParam(), o);
  }

  // Binds fresh streams holding `ins` (and zero-filled outputs of n elements), executes
  // once, and returns the outputs: a vector for one output type, a tuple for several.
  template <class... Outs, class... Hs>
  auto run_kernel(Kernel& k, int64_t n, const std::vector<Hs>&... ins) {
    static_assert(sizeof...(Outs) >= 1, "name the output types: run<Float, Int>(...)");
    std::tuple<Stream<typename DslOf<Hs>::type>...> in_streams{
        Stream<typename DslOf<Hs>::type>(ins)...};
    std::tuple<Stream<Outs>...> out_streams{Stream<Outs>(n)...};
    std::apply([&](const auto&... s) { k.inputs(s...); }, in_streams);
    std::apply([&](const auto&... s) { k.outputs(s...); }, out_streams);
    last_written_ = k.execute();
    if constexpr (sizeof...(Outs) == 1) {
      return std::get<0>(out_streams).download();
    } else {
      return std::apply([](const auto&... s) { return std::make_tuple(s.download()...); },
                        out_streams);
    }
  }
  // Compiles p (strict) and runs it over inputs of equal size.
  template <class... Outs, class H0, class... Hs>
  auto run(const Program& p, const std::vector<H0>& in0, const std::vector<Hs>&... ins) {
    Kernel k = compile(p);
    return run_kernel<Outs...>(k, static_cast<int64_t>(in0.size()), in0, ins...);
  }
  // The same, for programs without inputs: n elements.
  template <class... Outs>
  auto run_n(const Program& p, int64_t n) {
    Kernel k = compile(p);
    return run_kernel<Outs...>(k, n);
  }

  int64_t last_written_ = 0;  // what the last run's execute() returned
};

// Sets an environment variable for the life of the object, then restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// Instantiates a TEST_P suite derived from BackendTest for every backend of this build. Test
// names end in "/<backend>", which the CMake registration filters on.
#define RILL_BACKEND_TEST_SUITE(Suite)                                        \
  INSTANTIATE_TEST_SUITE_P(                                                   \
      Backends, Suite, ::testing::ValuesIn(::rill::testing::backend_names()), \
      [](const ::testing::TestParamInfo<std::string>& info) { return ::rill::testing::param_name(info.param); })

// ---- comparisons ----------------------------------------------------------------------------

inline uint32_t bits_of(float f) {
  return std::bit_cast<uint32_t>(f);
}
inline float float_of(uint32_t b) {
  return std::bit_cast<float>(b);
}

// "1.5 (0x3fc00000)": the value and its bits, so signed zeros and NaN payloads show.
inline std::string show(float f) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g (0x%08x)", static_cast<double>(f), bits_of(f));
  return buf;
}
inline std::string show(int32_t i) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%d (0x%08x)", i, static_cast<uint32_t>(i));
  return buf;
}

// Same value bit for bit; any NaN matches any NaN (payloads are not specified). On a backend
// that flushes denormals, both sides are flushed first.
inline bool same_bits(float a, float b) {
  if (flushes_denormals()) {
    a = flush(a);
    b = flush(b);
    // Flush-to-zero hardware decides tininess before rounding: a result just below FLT_MIN
    // that IEEE rounds up to +-FLT_MIN comes out as a zero of the same sign.
    auto zero_for_min = [](float z, float m) {
      return z == 0.0f && std::fabs(m) == std::numeric_limits<float>::min() && std::signbit(z) == std::signbit(m);
    };
    if (zero_for_min(a, b) || zero_for_min(b, a)) return true;
  }
  return (std::isnan(a) && std::isnan(b)) || bits_of(a) == bits_of(b);
}
inline bool same_bits(int32_t a, int32_t b) {
  return a == b;
}

// Distance in units in the last place (adjacent floats are 1 apart; +0 and -0 are 0 apart;
// infinity is one past FLT_MAX).
inline int64_t ulp_key(float f) {
  int32_t i = std::bit_cast<int32_t>(f);
  return i >= 0 ? int64_t{i} : -int64_t{i & 0x7fffffff};
}
inline int64_t ulp_distance(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return (std::isnan(a) && std::isnan(b)) ? 0 : INT64_MAX;
  int64_t d = ulp_key(a) - ulp_key(b);
  return d < 0 ? -d : d;
}

// Describes element i of the inputs, for failure messages ("x=1.5 (0x3fc00000)").
using Describe = std::function<std::string(size_t)>;

namespace detail {
template <class S, class Match>
::testing::AssertionResult compare_all(const std::vector<S>& got, const std::vector<S>& want,
                                       const Describe& describe, int width, Match match,
                                       const char* how) {
  if (got.size() != want.size())
    return ::testing::AssertionFailure() << "size " << got.size() << ", expected " << want.size();
  size_t bad = 0;
  std::string msg;
  for (size_t i = 0; i < got.size(); ++i) {
    if (match(got[i], want[i])) continue;
    if (++bad <= 8) {
      msg += "\n  [" + std::to_string(i / static_cast<size_t>(width));
      if (width > 1) msg += "." + std::string(1, "xyzw"[i % static_cast<size_t>(width)]);
      msg += "] got " + show(got[i]) + ", expected " + show(want[i]);
      if (describe) msg += "  <- " + describe(i / static_cast<size_t>(width));
    }
  }
  if (bad == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << bad << " of " << got.size() << " components differ ("
                                       << how << ")" << msg << (bad > 8 ? "\n  ..." : "");
}
}  // namespace detail

// Bitwise equality of host elements (float, int, glm vectors), NaN matching NaN.
template <class H>
::testing::AssertionResult bits_equal(const std::vector<H>& got, const std::vector<H>& want,
                                      const Describe& describe = {},
                                      int width = ScalarOf<H>::width) {
  return detail::compare_all(
      flatten(got), flatten(want), describe, width, [](auto a, auto b) { return same_bits(a, b); },
      "bitwise");
}

// Floats within `ulps` of a double-precision reference (rounded to float first).
inline ::testing::AssertionResult within_ulps(const std::vector<float>& got,
                                              const std::vector<double>& ref, int64_t ulps,
                                              const Describe& describe = {}, int width = 1) {
  std::vector<float> want(ref.size());
  for (size_t i = 0; i < ref.size(); ++i) want[i] = static_cast<float>(ref[i]);
  return detail::compare_all(
      got, want, describe, width,
      [&](float a, float b) {
        if (flushes_denormals() && same_bits(a, b)) return true;
        return ulp_distance(a, b) <= ulps;
      },
      "ulp tolerance");
}

// Floats close to a reference: |got - want| <= abs_tol + rel_tol * |want|, NaN matching NaN.
inline ::testing::AssertionResult close_to(const std::vector<float>& got,
                                           const std::vector<float>& want, double rel_tol,
                                           double abs_tol, const Describe& describe = {}) {
  return detail::compare_all(
      got, want, describe, 1,
      [&](float a, float b) {
        if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
        if (std::isinf(a) || std::isinf(b)) return a == b;
        return std::fabs(double{a} - double{b}) <= abs_tol + rel_tol * std::fabs(double{b});
      },
      "relative tolerance");
}

// While alive, host float arithmetic flushes denormal operands and results to zero
// (x86 MXCSR DAZ and FTZ), as a flushing backend does: references computed under it model
// that backend exactly, intermediates included (llvmpipe uses the same hardware modes).
class HostFlushScope {
 public:
  explicit HostFlushScope(bool on) : on_(on) {
    if (on_) {
      saved_ = _mm_getcsr();
      _mm_setcsr(saved_ | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
    }
  }
  ~HostFlushScope() {
    if (on_) _mm_setcsr(saved_);
  }
  HostFlushScope(const HostFlushScope&) = delete;
  HostFlushScope& operator=(const HostFlushScope&) = delete;

 private:
  bool on_;
  unsigned saved_ = 0;
};

// The reference of each element (under the flushing backend's rules, see HostFlushScope).
template <class T, class F>
auto map(const std::vector<T>& v, F f) {
  HostFlushScope flush_like_backend(flushes_denormals());
  std::vector<std::decay_t<decltype(f(v[0]))>> out;
  out.reserve(v.size());
  for (const T& x : v) out.push_back(f(x));
  return out;
}
template <class T, class U, class F>
auto map(const std::vector<T>& a, const std::vector<U>& b, F f) {
  HostFlushScope flush_like_backend(flushes_denormals());
  std::vector<std::decay_t<decltype(f(a[0], b[0]))>> out;
  out.reserve(a.size());
  for (size_t i = 0; i < a.size(); ++i) out.push_back(f(a[i], b[i]));
  return out;
}

// ---- inputs ---------------------------------------------------------------------------------

// Values that break careless implementations.
inline const std::vector<float>& hard_floats_with_denormals() {
  static const std::vector<float> v = [] {
    using L = std::numeric_limits<float>;
    std::vector<float> h = {0.0f,
                            -0.0f,
                            L::denorm_min(),
                            -L::denorm_min(),
                            float_of(0x007fffffu),  // largest denormal
                            -float_of(0x007fffffu),
                            1e-40f,
                            L::min(),
                            -L::min(),
                            L::max(),
                            -L::max(),
                            L::infinity(),
                            -L::infinity(),
                            L::quiet_NaN(),
                            -L::quiet_NaN(),
                            1.0f,
                            -1.0f,
                            0.5f,
                            -0.5f,
                            1.5f,
                            -1.5f,
                            2.5f,
                            -2.5f,
                            3.0f,
                            -3.0f,
                            0.1f,
                            3.14159265f,
                            1e10f,
                            -1e10f,
                            2147483648.0f,   // 2^31: does not fit an int
                            2147483520.0f,   // largest float below 2^31
                            -2147483648.0f,  // INT_MIN: fits
                            -2147483904.0f,  // next float below INT_MIN
                            16777216.0f,
                            8388607.5f,
                            0.49999997f,
                            -0.99999994f,
                            1.0000001f};
    return h;
  }();
  return v;
}

inline const std::vector<int32_t>& hard_ints() {
  static const std::vector<int32_t> v = {0,
                                         1,
                                         -1,
                                         2,
                                         -2,
                                         3,
                                         -7,
                                         31,
                                         32,
                                         33,
                                         -31,
                                         -32,
                                         255,
                                         16777217,
                                         0x55555555,
                                         std::numeric_limits<int32_t>::max(),
                                         std::numeric_limits<int32_t>::max() - 1,
                                         std::numeric_limits<int32_t>::min(),
                                         std::numeric_limits<int32_t>::min() + 1};
  return v;
}

// The hard values, with denormals flushed when the backend flushes them.
inline const std::vector<float>& hard_floats() {
  static const std::vector<float> flushed = [] {
    std::vector<float> v = hard_floats_with_denormals();
    for (float& x : v) x = flush(x);
    return v;
  }();
  return flushes_denormals() ? flushed : hard_floats_with_denormals();
}

// A seeded mix: random bit patterns (every exponent, NaNs, denormals), moderate values,
// integers and halves, wide magnitudes, and the hard values.
inline std::vector<float> random_floats(uint32_t seed, size_t n) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, 99);
  std::uniform_real_distribution<float> moderate(-10.0f, 10.0f);
  std::uniform_int_distribution<int> integer(-200, 200);
  std::uniform_int_distribution<int> exponent(-149, 127);
  std::uniform_real_distribution<float> mantissa(1.0f, 2.0f);
  const auto& hard = hard_floats();
  std::uniform_int_distribution<size_t> hard_pick(0, hard.size() - 1);
  std::vector<float> out(n);
  for (float& x : out) {
    int p = pick(rng);
    if (p < 25)
      x = float_of(static_cast<uint32_t>(rng()));
    else if (p < 50)
      x = moderate(rng);
    else if (p < 65)
      x = static_cast<float>(integer(rng)) * 0.5f;
    else if (p < 85)
      x = (rng() & 1 ? -1.0f : 1.0f) * std::ldexp(mantissa(rng), exponent(rng));
    else
      x = hard[hard_pick(rng)];
    if (flushes_denormals()) x = flush(x);
  }
  return out;
}

inline std::vector<int32_t> random_ints(uint32_t seed, size_t n) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, 99);
  std::uniform_int_distribution<int32_t> small(-40, 40);
  const auto& hard = hard_ints();
  std::uniform_int_distribution<size_t> hard_pick(0, hard.size() - 1);
  std::vector<int32_t> out(n);
  for (int32_t& x : out) {
    int p = pick(rng);
    if (p < 45)
      x = static_cast<int32_t>(rng());
    else if (p < 80)
      x = small(rng);
    else
      x = hard[hard_pick(rng)];
  }
  return out;
}

// Every hard value first, then n random values.
// n integers drawn uniformly from [lo, hi], seeded (trip counts, branch selectors).
inline std::vector<int32_t> small_ints(uint32_t seed, size_t n, int32_t lo, int32_t hi) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> d(lo, hi);
  std::vector<int32_t> v(n);
  for (int32_t& x : v) x = d(rng);
  return v;
}

inline std::vector<float> sweep_floats(uint32_t seed, size_t n) {
  std::vector<float> v = hard_floats();
  std::vector<float> r = random_floats(seed, n);
  v.insert(v.end(), r.begin(), r.end());
  return v;
}
inline std::vector<int32_t> sweep_ints(uint32_t seed, size_t n) {
  std::vector<int32_t> v = hard_ints();
  std::vector<int32_t> r = random_ints(seed, n);
  v.insert(v.end(), r.begin(), r.end());
  return v;
}
// Two sweeps of equal length whose first elements pair every hard value with every other.
template <class T>
std::pair<std::vector<T>, std::vector<T>> sweep_pairs(const std::vector<T>& hard, std::vector<T> ra,
                                                      std::vector<T> rb) {
  std::vector<T> a, b;
  for (T x : hard)
    for (T y : hard) {
      a.push_back(x);
      b.push_back(y);
    }
  a.insert(a.end(), ra.begin(), ra.end());
  b.insert(b.end(), rb.begin(), rb.end());
  return {a, b};
}
inline std::pair<std::vector<float>, std::vector<float>> sweep_float_pairs(uint32_t seed,
                                                                           size_t n) {
  return sweep_pairs(hard_floats(), random_floats(seed, n), random_floats(seed + 1, n));
}
inline std::pair<std::vector<int32_t>, std::vector<int32_t>> sweep_int_pairs(uint32_t seed,
                                                                             size_t n) {
  return sweep_pairs(hard_ints(), random_ints(seed, n), random_ints(seed + 1, n));
}

// Groups a flat list of scalars into 4-vectors (the list is padded by repeating it).
template <class T>
std::vector<glm::vec<4, T, glm::defaultp>> as_vec4(std::vector<T> v) {
  size_t n0 = v.size();
  while (v.size() % 4) v.push_back(v[v.size() - n0]);
  return unflatten<glm::vec<4, T, glm::defaultp>>(v);
}

// Describers for failure messages. describe_inputs keeps references to the vectors: they
// must outlive the comparisons that use it.
template <class H>
std::string show_elem(const H& h) {
  if constexpr (ScalarOf<H>::width == 1) {
    return show(h);
  } else {
    std::string s = "(";
    for (int c = 0; c < ScalarOf<H>::width; ++c) s += (c ? ", " : "") + show(h[c]);
    return s + ")";
  }
}
template <class... Hs>
Describe describe_inputs(const std::vector<Hs>&... ins) {
  return [&ins...](size_t i) {
    std::string s;
    int k = 0;
    auto add = [&](const std::string& e) {
      s += (k ? ", in" : "in") + std::to_string(k) + "=" + e;
      ++k;
    };
    (add(show_elem(ins[i])), ...);
    return s;
  };
}

}  // namespace rill::testing
