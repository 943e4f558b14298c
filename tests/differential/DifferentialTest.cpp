// Randomized differential tests (docs/testing.md).
//
// Seeded random programs (Generator.h) run on every backend in `strict` mode and are compared
// bit for bit with the reference: the program optimized for strict mode and run by the IR
// interpreter on the same inputs. Many programs share one kernel (a uniform selects one per
// launch), so each compile serves a whole batch. Every few kernels are compiled with the
// optimizer passes off, which must not change any result.
//
//   Backends/Differential.RandomPrograms/<backend>   one backend against the reference
//   DifferentialCross.AllBackends                     the same programs on every available
//                                                     backend, and the reference optimized
//                                                     with passes off against passes on
//
// Environment: RILL_DIFF_PROGRAMS (programs per test), RILL_DIFF_BATCH (programs per kernel),
// RILL_DIFF_BASE_SEED (another set of programs), RILL_DIFF_SEED (run just these programs:
// reproduce a failure; with RILL_DIFF_DROP / RILL_DIFF_LEAF for a shrunk one),
// RILL_DIFF_VERBOSE=1 (print every program), RILL_DIFF_SHRINK=0 (report without shrinking),
// RILL_DIFF_SHRINK_SECONDS, RILL_DIFF_MAX_FAILURES, RILL_DIFF_BACKENDS (the cross-check's
// backends, e.g. cpu,opencl).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <sstream>

#include "Harness.h"
#include "ParamName.h"

namespace rill::difftest {
namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

// Programs per test in CI, sized so that each test costs about 25 s of CPU time on the 2-core
// machine with cold driver caches (docs/testing.md has the measurements), a whole number of
// kernels each; half under the sanitizers. RILL_DIFF_PROGRAMS runs more.
int64_t default_programs(const std::string& test) {
  const int64_t n = test == "cpu"            ? 576
                    : test == "opencl"       ? 384
                    : test == "glsl"         ? 216
                    : test == "glsl-compute" ? 96
                    : test == "vulkan"       ? 96
                    : test == "cross"        ? 96
                                             : 288;
  return kSanitized ? n / 2 : n;
}
// Programs per kernel: compile times grow faster than linearly with kernel size on llvmpipe,
// while PoCL has a large fixed cost per compile. The cross-check's kernels run on glsl too, so
// they take glsl's size: at 32, its third kernel (programs 64-95, compiled with the passes
// off) took llvmpipe 163 s to compile and 157 s more at its first draw, while 32 programs of
// other seeds take 17-22 s (docs/testing.md, "Batching").
int64_t default_batch(const std::string& test) {
  return test == "cpu" ? 48 : test == "opencl" ? 96 : test == "glsl" || test == "cross" ? 24 : 32;
}

std::optional<std::string> env(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return std::nullopt;
  return std::string(v);
}
uint64_t parse_u64(const std::string& s) {
  return std::strtoull(s.c_str(), nullptr, 0);
}
int64_t env_int(const char* name, int64_t def) {
  auto v = env(name);
  return v ? static_cast<int64_t>(parse_u64(*v)) : def;
}
std::vector<uint64_t> parse_list(const std::string& s) {
  std::vector<uint64_t> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(parse_u64(item));
  return out;
}
std::set<uint64_t> env_ids(const char* name) {
  auto v = env(name);
  if (!v) return {};
  auto l = parse_list(*v);
  return std::set<uint64_t>(l.begin(), l.end());
}

uint64_t name_hash(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (char c : s) h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
  return h;
}

std::string current_filter() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + "." + info->name();
}

struct Campaign {
  std::string name;  // salts the program seeds
  std::vector<std::string> backends;
  int passes_off_every = 4;  // every n-th kernel is compiled with the optimizer passes off
  bool check_unoptimized = false;
  bool check_lockstep = false;
};

void run_campaign(const Campaign& c) {
  auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpu_seconds();
  std::vector<Target> targets;
  bool any_ftz = false;
  for (const std::string& b : c.backends) {
    Target t{b, false, flushes_denormals(b)};
    any_ftz = any_ftz || t.ftz;
    targets.push_back(t);
  }
  Options opt;
  // A backend that flushes denormals gets inputs without them (see docs/testing.md).
  opt.denormals = !any_ftz;
  opt.verbose = env_int("RILL_DIFF_VERBOSE", 0) != 0;
  const bool shrink = env_int("RILL_DIFF_SHRINK", 1) != 0;
  // Shrinking time for the whole test, shared by its failures.
  double shrink_left = static_cast<double>(env_int("RILL_DIFF_SHRINK_SECONDS", 90));
  const int64_t max_failures = env_int("RILL_DIFF_MAX_FAILURES", 3);  // full reports
  Stats st;
  auto with_passes = [&](bool off) {
    std::vector<Target> t = targets;
    for (Target& x : t) x.passes_off = off;
    return t;
  };
  // The first failures get a full report, shrunk while the time lasts; later ones a line.
  int64_t reported = 0, listed = 0;
  std::string more;
  auto one_line = [](const std::vector<ProgramSpec>& subs, const Failure& f) {
    std::string what = f.message.substr(0, f.message.find('\n'));
    size_t mark = f.message.find("<--");
    if (mark != std::string::npos) {
      size_t start = f.message.rfind('\n', mark) + 1;
      what = f.message.substr(start, f.message.find('\n', mark) - start);
    }
    return "  RILL_DIFF_SEED=" + hex(subs[f.sub].seed) + ": " + f.title() + ": " +
           what.substr(what.find_first_not_of(' ')) + "\n";
  };
  auto check = [&](const std::vector<ProgramSpec>& subs) {
    auto fs = run_batch(subs, opt, st);
    rill::clear_kernel_cache();
    if (fs.empty()) return;
    if (reported >= max_failures) {
      for (const Failure& f : fs)
        if (listed++ < 100) more += one_line(subs, f);
      return;
    }
    ++reported;
    std::string others;
    for (size_t i = 1; i < fs.size(); ++i) others += one_line(subs, fs[i]);
    double before = st.shrink_s;
    ADD_FAILURE() << report_failure(subs, fs[0], opt, shrink && shrink_left > 0, shrink_left, st,
                                    current_filter())
                  << (others.empty() ? "" : "\nthe kernel's other failing programs:\n" + others);
    shrink_left -= st.shrink_s - before;
  };

  if (auto seeds = env("RILL_DIFF_SEED")) {  // reproduce: just these programs, as one kernel
    std::vector<ProgramSpec> subs;
    for (uint64_t s : parse_list(*seeds))
      subs.push_back(ProgramSpec{s, Edits{env_ids("RILL_DIFF_DROP"), env_ids("RILL_DIFF_LEAF")}});
    try {
      std::printf("%s", build_program(subs).print().c_str());
    } catch (const std::exception& e) {
      std::printf("capturing the program threw: %s\n", e.what());
    }
    opt.check_unoptimized = true;
    opt.check_lockstep = true;
    for (bool off : {false, true}) {
      opt.targets = with_passes(off);
      check(subs);
    }
  } else {
    const int64_t programs = env_int("RILL_DIFF_PROGRAMS", default_programs(c.name));
    const int64_t batch = std::max<int64_t>(1, env_int("RILL_DIFF_BATCH", default_batch(c.name)));
    const uint64_t salt =
        derive(static_cast<uint64_t>(env_int("RILL_DIFF_BASE_SEED", 0x5eed)), name_hash(c.name));
    int64_t done = 0;
    for (int64_t b = 0; done < programs; ++b) {
      int64_t n = std::min(batch, programs - done);
      std::vector<ProgramSpec> subs;
      for (int64_t k = 0; k < n; ++k)
        subs.push_back(ProgramSpec{derive(salt, static_cast<uint64_t>(done + k)), {}});
      opt.targets =
          with_passes(c.passes_off_every > 0 && b % c.passes_off_every == c.passes_off_every - 1);
      opt.check_unoptimized = c.check_unoptimized;
      opt.check_lockstep = c.check_lockstep;
      check(subs);
      done += n;
    }
  }
  Interface::get().release_device_copies();
  if (!more.empty())
    ADD_FAILURE() << "more failing programs (" << listed << ", not shrunk; up to 100 listed):\n"
                  << more;
  double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double cpu = cpu_seconds() - cpu_start;
  std::printf("[differential %s] %s; total %.1f s wall, %.1f s CPU%s\n", c.name.c_str(),
              st.summary().c_str(), total, cpu,
              any_ftz ? " (a backend flushes denormals: inputs had none)" : "");
  ::testing::Test::RecordProperty("programs", std::to_string(st.programs));
  ::testing::Test::RecordProperty("seconds", std::to_string(total));
  ::testing::Test::RecordProperty("cpu_seconds", std::to_string(cpu));
}

std::vector<std::string> backend_names() {
  std::vector<std::string> names;
  for (Backend* b : rill::backends()) names.push_back(b->name());
  return names;
}

class Differential : public ::testing::TestWithParam<std::string> {};

TEST_P(Differential, RandomPrograms) {
  const std::string& b = GetParam();
  std::string why = rill::backend(b).unavailable_reason();
  if (!why.empty()) GTEST_SKIP() << "backend '" << b << "' is not available: " << why;
  // simd's campaign also checks its lowering on the reference interpreter.
  run_campaign(Campaign{b, {b}, 4, false, b == "simd"});
}

INSTANTIATE_TEST_SUITE_P(Backends, Differential, ::testing::ValuesIn(backend_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return rill::testing::param_name(info.param);
                         });

TEST(DifferentialCross, AllBackends) {
  std::vector<std::string> available;
  std::string unavailable;
  auto only = env("RILL_DIFF_BACKENDS");  // e.g. "cpu,opencl"
  for (Backend* b : rill::backends()) {
    std::string why = b->unavailable_reason();
    if (why.empty() && only && ("," + *only + ",").find("," + b->name() + ",") == std::string::npos)
      why = "left out by RILL_DIFF_BACKENDS";
    if (why.empty())
      available.push_back(b->name());
    else
      unavailable += "\n  " + b->name() + ": " + why;
  }
  if (available.size() < 2)
    GTEST_SKIP() << "the cross-check needs two available backends; unavailable:" << unavailable;
  if (!unavailable.empty())
    std::printf("[differential cross] not available:%s\n", unavailable.c_str());
  run_campaign(Campaign{"cross", available, 3, true, true});
}

}  // namespace
}  // namespace rill::difftest
