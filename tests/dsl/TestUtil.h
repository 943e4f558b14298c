// Helpers shared by the front-end tests: IR text matching, error expectations, running
// kernels on the CPU backend, seeded random inputs and bitwise comparison.
#pragma once

#include <gtest/gtest.h>
#include <rill/ir/Hash.h>
#include <rill/ir/Printer.h>
#include <rill/ir/Verifier.h>
#include <rill/ir/Visitor.h>
#include <rill/passes/Passes.h>
#include <rill/rill.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace rill::test {

// ---- IR text --------------------------------------------------------------------------------

// The lines of `text`, with leading and trailing blanks removed.
inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string l;
  while (std::getline(in, l)) {
    size_t b = l.find_first_not_of(' ');
    size_t e = l.find_last_not_of(' ');
    out.push_back(b == std::string::npos ? std::string() : l.substr(b, e - b + 1));
  }
  return out;
}

// Temporaries are numbered by creation order; tests that should not depend on how many
// temporaries capture happens to create compare text with every "t<n>" written "t#".
inline std::string normalized(const std::string& text) {
  static const std::regex temp(R"(\bt[0-9]+\b)");
  return std::regex_replace(text, temp, "t#");
}

inline int count_occurrences(const std::string& text, const std::string& sub) {
  int n = 0;
  for (size_t at = text.find(sub); at != std::string::npos; at = text.find(sub, at + 1)) ++n;
  return n;
}

// How many (trimmed) lines of `text` equal `line`.
inline int count_lines(const std::string& text, const std::string& line) {
  int n = 0;
  for (const auto& l : lines(text)) n += l == line;
  return n;
}

// How many (trimmed) lines of `text` match the regular expression `pattern` entirely.
inline int count_matching(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  int n = 0;
  for (const auto& l : lines(text)) n += std::regex_match(l, re);
  return n;
}

inline ::testing::AssertionResult Contains(const char* text_expr, const char* sub_expr,
                                           const std::string& text, const std::string& sub) {
  if (text.find(sub) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << text_expr << " does not contain " << sub_expr << " (\"" << sub << "\"); it is:\n"
         << text;
}
inline ::testing::AssertionResult Lacks(const char* text_expr, const char* sub_expr,
                                        const std::string& text, const std::string& sub) {
  if (text.find(sub) == std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << text_expr << " contains " << sub_expr << " (\"" << sub << "\"); it is:\n"
         << text;
}
inline ::testing::AssertionResult HasLine(const char* text_expr, const char* line_expr,
                                          const std::string& text, const std::string& line) {
  if (count_lines(text, line) > 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << text_expr << " has no line " << line_expr << " (\"" << line << "\"); it is:\n"
         << text;
}

#define EXPECT_HAS(text, sub) EXPECT_PRED_FORMAT2(::rill::test::Contains, text, sub)
#define EXPECT_LACKS(text, sub) EXPECT_PRED_FORMAT2(::rill::test::Lacks, text, sub)
#define EXPECT_LINE(text, line) EXPECT_PRED_FORMAT2(::rill::test::HasLine, text, line)

// ---- errors ---------------------------------------------------------------------------------

// The message of the rill::Error that f throws, or a note that it threw none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const rill::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("<not a rill::Error: ") + e.what() + ">";
  }
  return "<no rill::Error thrown>";
}

// "tests/dsl/ThisTest.cpp:<line>", as rill::SourceLoc::str() prints a location of __FILE__
// (relative_path), for matching error locations.
inline std::string here(const char* path, int line) {
  return rill::relative_path(path) + ":" + std::to_string(line);
}
#define RILL_TEST_HERE ::rill::test::here(__FILE__, __LINE__)

// ---- statements -----------------------------------------------------------------------------

inline int statements(const ir::Function& f) {
  return ir::count_statements(f.body);
}

// Statements of a kind (and, for assignments, of an op) anywhere in f.
inline int count_ops(const ir::Function& f, ir::Op op) {
  int n = 0;
  ir::for_each_stmt(f.body, [&](const ir::Stmt& s) {
    if (s.kind == ir::StmtKind::Assign && s.op == op) ++n;
  });
  return n;
}
inline int count_kind(const ir::Function& f, ir::StmtKind k) {
  int n = 0;
  ir::for_each_stmt(f.body, [&](const ir::Stmt& s) { n += s.kind == k; });
  return n;
}

// Problems the verifier finds, joined (empty when the function is well formed).
inline std::string problems(const ir::Function& f) {
  std::string out;
  for (const auto& p : ir::verify(f)) out += p + "\n";
  return out;
}

// ---- running on the CPU backend ---------------------------------------------------------------

template <class V>
using Host = typename V::host_type;

// The bits of a host stream's words. For float data every NaN becomes the canonical quiet NaN
// 0x7fc00000: the sign and payload of a NaN result are not specified (docs/accuracy.md), and
// they do differ between C compilers (clang may swap the operands of a commutative add of two
// NaNs; x86's invalid-operation NaN is negative where GCC folds a positive one).
template <class T>
std::vector<uint32_t> bits_of(const std::vector<T>& v) {
  std::vector<uint32_t> out(v.size() * sizeof(T) / 4);
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size() * 4);
  constexpr bool floats = std::is_same_v<T, float> || requires {
    requires std::is_same_v<typename T::value_type, float>;
  };
  if constexpr (floats)
    for (uint32_t& w : out)
      if ((w & 0x7fffffffu) > 0x7f800000u) w = 0x7fc00000u;
  return out;
}

// Compiles p for the CPU backend and runs it once over the given input streams (bound in
// declaration order); its one output starts as all zero bits. Returns the output.
template <class Out, class... In>
std::vector<Host<Out>> run_cpu(const Program& p, const CompileOptions& options,
                               const std::vector<Host<In>>&... inputs) {
  Kernel k = compile(p, "cpu", options);
  size_t n = std::get<0>(std::forward_as_tuple(inputs...)).size();
  std::tuple<Stream<In>...> in{Stream<In>(inputs)...};
  Stream<Out> out(static_cast<int64_t>(n));
  out.fill(Host<Out>{});
  std::apply([&](auto&... s) { k.inputs(s...); }, in);
  k.outputs(out);
  k.execute();
  return out.download();
}

struct NamedOptions {
  std::string name;
  CompileOptions options;
};

// All passes on, each one off in turn, and all off.
inline std::vector<NamedOptions> pass_configs(Accuracy a = Accuracy::Strict) {
  std::vector<NamedOptions> out;
  CompileOptions all;
  all.accuracy = a;
  out.push_back({"all passes", all});
  auto off = [&](const char* name, bool PassOptions::*field) {
    CompileOptions o = all;
    o.passes.*field = false;
    out.push_back({std::string("without ") + name, o});
  };
  off("constant_folding", &PassOptions::constant_folding);
  off("copy_propagation", &PassOptions::copy_propagation);
  off("common_subexpressions", &PassOptions::common_subexpressions);
  off("dead_code", &PassOptions::dead_code);
  CompileOptions none = all;
  none.passes = PassOptions{false, false, false, false};
  out.push_back({"no passes", none});
  return out;
}

// Seeded inputs: special values first (zeros, infinities, NaN, denormals, extremes), then
// uniform random values in [lo, hi].
inline std::vector<float> random_floats(size_t n, uint32_t seed, float lo = -100.0f,
                                        float hi = 100.0f) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> v{0.0f,
                       -0.0f,
                       1.0f,
                       -1.0f,
                       0.5f,
                       inf,
                       -inf,
                       std::numeric_limits<float>::quiet_NaN(),
                       std::bit_cast<float>(0x7fc12345u),
                       std::numeric_limits<float>::denorm_min(),
                       -1e-40f,
                       std::numeric_limits<float>::max(),
                       std::numeric_limits<float>::lowest(),
                       std::numeric_limits<float>::min(),
                       3e9f,
                       -3e9f};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(lo, hi);
  while (v.size() < n) v.push_back(d(rng));
  v.resize(n);
  return v;
}

inline std::vector<int32_t> random_ints(size_t n, uint32_t seed, int32_t lo = -1000,
                                        int32_t hi = 1000) {
  std::vector<int32_t> v{0,
                         1,
                         -1,
                         2,
                         -2,
                         31,
                         32,
                         33,
                         std::numeric_limits<int32_t>::max(),
                         std::numeric_limits<int32_t>::min()};
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> d(lo, hi);
  while (v.size() < n) v.push_back(d(rng));
  v.resize(n);
  return v;
}

inline ::testing::AssertionResult SameBits(const char* a_expr, const char* b_expr,
                                           const std::vector<uint32_t>& a,
                                           const std::vector<uint32_t>& b) {
  if (a.size() != b.size())
    return ::testing::AssertionFailure()
           << a_expr << " has " << a.size() << " words but " << b_expr << " has " << b.size();
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "word %zu differs: 0x%08x (%g) vs 0x%08x (%g)", i, a[i],
                    static_cast<double>(std::bit_cast<float>(a[i])), b[i],
                    static_cast<double>(std::bit_cast<float>(b[i])));
      return ::testing::AssertionFailure() << a_expr << " vs " << b_expr << ": " << buf;
    }
  return ::testing::AssertionSuccess();
}
#define EXPECT_SAME_BITS(a, b) EXPECT_PRED_FORMAT2(::rill::test::SameBits, a, b)

// Runs p under each of `configs` and expects the outputs of all of them to be bitwise
// identical to the output under the first.
template <class Out, class... In>
void expect_configs_agree(const std::vector<NamedOptions>& configs, const Program& p,
                          const std::vector<Host<In>>&... inputs) {
  auto reference = bits_of(run_cpu<Out, In...>(p, configs[0].options, inputs...));
  for (size_t i = 1; i < configs.size(); ++i) {
    SCOPED_TRACE(configs[i].name);
    auto got = bits_of(run_cpu<Out, In...>(p, configs[i].options, inputs...));
    EXPECT_SAME_BITS(reference, got);
  }
}

// Runs p under every pass configuration (strict accuracy) and expects the outputs of all of
// them to be bitwise identical to the output with all passes on.
template <class Out, class... In>
void expect_passes_preserve_results(const Program& p, const std::vector<Host<In>>&... inputs) {
  expect_configs_agree<Out, In...>(pass_configs(), p, inputs...);
}

// Applies a pass to a copy of p's IR and expects the verifier to accept the result.
template <class Pass>
ir::Function after(const Program& p, Pass&& pass) {
  ir::Function f = p.ir();
  pass(f);
  EXPECT_EQ(problems(f), "") << "after the pass:\n" << ir::print(f);
  return f;
}

}  // namespace rill::test
