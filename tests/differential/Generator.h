// Random program generation for the differential tests.
//
// A program is generated from a 64-bit seed by C++ code that drives the DSL at capture time:
// host code chooses operations at random, exactly as Rill's metaprogramming model intends.
// Every statement and expression node has a 64-bit id derived from its parent's id and its
// position, and draws its random choices from an RNG seeded with that id. So removing a
// statement (or replacing an expression by a leaf) leaves every other node's choices as they
// were: the shrinker edits programs by id and regenerates them from the same seed.
//
// All generated programs share one interface (Io below): five input streams, five output
// streams, four uniforms and five arrays. That lets many programs be batched into one kernel
// (a uniform `which` selects one per launch) and lets every launch data set (LaunchData) fit
// every program.
#pragma once

#include <rill/rill.h>

#include <array>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace rill::difftest {

// ---- randomness ----------------------------------------------------------------------------

// splitmix64's finalizer: a bijective 64-bit mix.
inline uint64_t mix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
// The id of child `i` of node `id`.
inline uint64_t derive(uint64_t id, uint64_t i) {
  return mix64(id ^ mix64(i + 0x51ed2701ull));
}

class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  uint64_t next() { return mix64(s_ += 0x9e3779b97f4a7c15ull); }
  uint32_t bits() { return static_cast<uint32_t>(next() >> 32); }
  // Uniform in [0, n).
  int below(int n) { return static_cast<int>(next() % static_cast<uint64_t>(n)); }
  // Uniform in [lo, hi].
  int range(int lo, int hi) { return lo + below(hi - lo + 1); }
  bool percent(int p) { return below(100) < p; }
  // An index chosen with the given weights.
  int pick(std::initializer_list<int> weights);

 private:
  uint64_t s_;
};

// ---- the shared interface ------------------------------------------------------------------

constexpr int kStreams = 5;  // inputs, and likewise outputs
// Inputs f4 (Float4), f3 (Float3), f1 (Float), i4 (Int4), i2 (Int2).
constexpr std::array<int, kStreams> kInWidth = {4, 3, 1, 4, 2};
constexpr std::array<bool, kStreams> kInFloat = {true, true, true, false, false};
constexpr std::array<const char*, kStreams> kInName = {"f4", "f3", "f1", "i4", "i2"};
// Outputs of4 (Float4), of3 (Float3), of2 (Float2), oi4 (Int4), oi1 (Int).
constexpr std::array<int, kStreams> kOutWidth = {4, 3, 2, 4, 1};
constexpr std::array<bool, kStreams> kOutFloat = {true, true, true, false, false};
constexpr std::array<const char*, kStreams> kOutName = {"of4", "of3", "of2", "oi4", "oi1"};
// Arrays af1 (Float, 1D), af4 (Float4, 1D), af2d (Float2, 2D), ai1 (Int, 1D), ai2d (Int3, 2D).
constexpr int kArrays = 5;
constexpr std::array<int, kArrays> kArrWidth = {1, 4, 2, 1, 3};
constexpr std::array<bool, kArrays> kArrFloat = {true, true, true, false, false};
constexpr std::array<int, kArrays> kArrDims = {1, 1, 2, 1, 2};

// Uniforms and arrays live on the host, outside programs. One set serves every program of
// the process, so kernels served from the in-process cache read the same states.
struct Interface {
  Uniform<Int> which{0, "which"};
  Uniform<Float> uf{0.0f, "uf"};
  Uniform<Float4> uf4{glm::vec4(0.0f), "uf4"};
  Uniform<Int> ui{0, "ui"};
  Uniform<Int3> ui3{glm::ivec3(0), "ui3"};
  Array<Float> af1{1, "af1"};
  Array<Float4> af4{1, "af4"};
  Array<Float2> af2d{1, 1, "af2d"};
  Array<Int> ai1{1, "ai1"};
  Array<Int3> ai2d{1, 1, "ai2d"};

  static Interface& get();
  // Drops the arrays' device copies (each backend's buffer or texture), while the backends
  // are certainly alive: not at exit, when static destructors run in an order of their own.
  void release_device_copies();
};

// ---- programs --------------------------------------------------------------------------------

// Edits the shrinker makes to a generated program, by node id.
struct Edits {
  std::set<uint64_t> dropped;  // statements left out (with everything nested in them)
  std::set<uint64_t> leaves;   // expression nodes generated as leaves instead
  bool empty() const { return dropped.empty() && leaves.empty(); }
};

struct ProgramSpec {
  uint64_t seed = 0;
  Edits edits;
};

// The node ids one generation visited, in order (what the shrinker may edit).
struct GenTrace {
  std::vector<uint64_t> stmts, exprs;
};

// Captures the programs of `subs` as one kernel. With one program its code is the body;
// with several, `which == k` selects program k (a RILL_IF / RILL_ELSE_IF chain).
// `traces`, if given, receives one GenTrace per program.
Program build_program(const std::vector<ProgramSpec>& subs,
                      std::vector<GenTrace>* traces = nullptr);

// ---- launch data -----------------------------------------------------------------------------

// Everything one launch of one program reads, as raw 32-bit words, derived from the
// program's seed: stream contents, the outputs' previous contents, uniforms and arrays.
struct LaunchData {
  int64_t count = 0, width = 0, height = 1;             // elements, and the streams' 2D shape
  std::array<std::vector<uint32_t>, kStreams> in, out;  // out: previous output contents
  // The in-place case: output of4 is input f4's stream and oi4 is i4's (in[0] == out[0] and
  // in[3] == out[3] then).
  bool alias = false;
  float uf = 0.0f;
  glm::vec4 uf4{0.0f};
  int32_t ui = 0;
  glm::ivec3 ui3{0};
  std::array<std::array<int64_t, 2>, kArrays> shape{};
  std::array<std::vector<uint32_t>, kArrays> arr;
};

// `denormals`: whether float data may contain denormals (not for backends that flush them).
LaunchData make_launch_data(uint64_t seed, bool denormals);
// Sets the interface's uniforms (which = `which`) and arrays from `d`.
void apply_launch_data(const LaunchData& d, int which);

// "1.5 (0x3fc00000)", "-7 (0xfffffff9)".
std::string show_word(uint32_t w, bool is_float);

}  // namespace rill::difftest
