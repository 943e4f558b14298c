// Masked launches (rill::where, StateMask.h) on every backend: only the selected elements run,
// the others keep their outputs and are not counted; sets of values; a mask stream that
// the kernel also writes (the state is read as it was before the launch); loop() with a
// mask; an empty selection; LaunchStats; the counts of many launches of one kernel; and the
// errors for a wrong mask stream.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class MaskTest : public BackendTest {};

// 5000 elements: not a multiple of the CPU grain (1024) nor of a GLSL texture row (4096).
constexpr int64_t kN = 5000;

std::vector<int32_t> random_states(uint32_t seed, int64_t n, int32_t states) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> d(0, states - 1);
  std::vector<int32_t> v(static_cast<size_t>(n));
  for (int32_t& s : v) s = d(rng);
  return v;
}

// kN floats with hard values (signed zeros, infinities, NaN...) mixed in.
std::vector<float> floats(uint32_t seed) {
  std::vector<float> xs = sweep_floats(seed, static_cast<size_t>(kN));
  xs.resize(static_cast<size_t>(kN));
  return xs;
}

bool in_set(int32_t s, std::initializer_list<int32_t> set) {
  return std::find(set.begin(), set.end(), s) != set.end();
}

template <class F>
void expect_error(F f, const char* part) {
  try {
    f();
    ADD_FAILURE() << "expected rill::Error mentioning '" << part << "'";
  } catch (const rill::Error& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
        << "message '" << e.what() << "' does not mention '" << part << "'";
  }
}

Program scale_program() {
  return program("mask_scale", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> ran("ran");
    y = x * 2.0f + 1.0f;
    ran = 1;
  });
}

TEST_P(MaskTest, RunsOnlyTheSelectedElements) {
  std::vector<float> xs = floats(7);
  std::vector<int32_t> states = random_states(1, kN, 5);
  Kernel k = compile(scale_program());
  Stream<Float> x(xs), y(kN);
  Stream<Int> ran(kN), state(states);
  y.fill(-7.0f);
  ran.fill(0);
  k.inputs(x).outputs(y, ran);
  int64_t written = k.execute(where(state, 3));

  int64_t want = 0;
  for (int32_t s : states) want += s == 3;
  ASSERT_GT(want, 0);
  ASSERT_LT(want, kN);
  EXPECT_EQ(written, want);
  EXPECT_EQ(k.last_launch().written, want);
  EXPECT_EQ(k.last_launch().processed, want);
  std::vector<float> want_y(xs.size());
  std::vector<int32_t> want_ran(xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    want_y[i] = states[i] == 3 ? xs[i] * 2.0f + 1.0f : -7.0f;
    want_ran[i] = states[i] == 3;
  }
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(y.download(), want_y, d));
  EXPECT_TRUE(bits_equal(ran.download(), want_ran, d));

  // Without a mask the same Kernel runs everywhere again.
  EXPECT_EQ(k.execute(), kN);
  EXPECT_EQ(k.last_launch().processed, kN);
}

TEST_P(MaskTest, SetOfValuesWithDiscardInside) {
  std::vector<float> xs = floats(8);
  std::vector<int32_t> states = random_states(2, kN, 6);
  Program p = program("mask_discard", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF(x < 0.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    y = x + 1.0f;
  });
  Kernel k = compile(p);
  Stream<Float> x(xs), y(kN);
  Stream<Int> state(states);
  y.fill(-7.0f);
  k.inputs(x).outputs(y);
  int64_t written = k.execute(where(state, {1, 4, 5}));
  int64_t want_processed = 0, want_written = 0;
  std::vector<float> want_y(xs.size());
  for (size_t i = 0; i < xs.size(); ++i) {
    bool sel = in_set(states[i], {1, 4, 5});
    bool writes = sel && !(xs[i] < 0.0f);
    want_processed += sel;
    want_written += writes;
    want_y[i] = writes ? xs[i] + 1.0f : -7.0f;
  }
  EXPECT_EQ(written, want_written);
  EXPECT_EQ(k.last_launch().processed, want_processed);
  EXPECT_LT(want_written, want_processed);  // the discard mattered
  EXPECT_TRUE(bits_equal(y.download(), want_y, describe_inputs(xs)));
}

// A state machine step: the kernel advances the state it is masked on. The mask is the
// state before the launch, so an element moved into a selected state is not run again.
Program step_program() {
  return program("mask_step", [] {
    Input<Int> s("s");
    Output<Int> s_out("s_out");
    s_out = s + 1;
  });
}

TEST_P(MaskTest, MaskStreamWrittenByTheKernel) {
  std::vector<int32_t> states = random_states(3, kN, 4);
  Kernel k = compile(step_program());
  Stream<Int> s(states);
  k.inputs(s).outputs(s);
  int64_t written = k.execute(where(s, {1, 2}));
  int64_t want = 0;
  std::vector<int32_t> after = states;
  for (int32_t& v : after)
    if (v == 1 || v == 2) {
      ++v;
      ++want;
    }
  EXPECT_EQ(written, want);
  EXPECT_TRUE(bits_equal(s.download(), after));
}

TEST_P(MaskTest, LoopReevaluatesTheMask) {
  std::vector<int32_t> states = random_states(4, kN, 6);  // 0..5
  Kernel k = compile(step_program());
  Stream<Int> s(states);
  k.inputs(s).outputs(s);
  // Every element below 3 steps up to 3: three passes that write, one that writes nothing.
  int64_t passes = k.loop(where(s, {0, 1, 2}));
  EXPECT_EQ(passes, 4);
  std::vector<int32_t> want = states;
  for (int32_t& v : want) v = std::max(v, 3);
  EXPECT_TRUE(bits_equal(s.download(), want));
  EXPECT_EQ(k.last_launch().processed, 0);
}

TEST_P(MaskTest, CountsOfSuccessiveLaunchesOfOneKernel) {
  // Backends keep a kernel's launch state between launches (opencl: running totals in its
  // counter, tables rewritten when they change): every launch must still report its own
  // counts, masked or not, whatever the uniform and the mask values.
  Uniform<Int> limit(0, "limit");
  Program p = program("count_up", [&] {
    Input<Int> v("v");
    Output<Int> next("v");
    RILL_IF(v >= limit) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    next = v + 1;
  });
  std::vector<int32_t> values = random_states(11, kN, 6), states = random_states(12, kN, 3);
  Kernel k = compile(p);
  Stream<Int> v(values), state(states);
  k.bind("v", v);
  for (int launch = 0; launch < 12; ++launch) {
    const int32_t lim = launch % 7, pick = launch % 3;
    const bool masked = pick != 0;
    limit.set(lim);
    int64_t want_written = 0, want_processed = 0;
    for (size_t i = 0; i < values.size(); ++i) {
      if (masked && states[i] != pick) continue;
      ++want_processed;
      if (values[i] >= lim) continue;
      ++values[i];
      ++want_written;
    }
    const int64_t written = masked ? k.execute(where(state, pick)) : k.execute();
    EXPECT_EQ(written, want_written) << "launch " << launch;
    EXPECT_EQ(k.last_launch().processed, want_processed) << "launch " << launch;
  }
  EXPECT_TRUE(bits_equal(v.download(), values));
}

// Runs of selected elements start and end anywhere in a row: each element still sees its
// own column and row (the CPU backends run each run of selected elements as a range).
TEST_P(MaskTest, SelectedElementsOfAnImageSeeTheirOwnCoordinates) {
  Program p = program("mask_coord", [] {
    Output<Int> xy("xy");
    Int2 c = element_coord();
    xy = c.x() * 4096 + c.y();
  });
  Kernel k = compile(p);
  for (auto [w, h] : {std::pair<int, int>{37, 61}, {1, 50}, {1000, 3}}) {
    const int64_t count = int64_t{w} * h;
    const std::vector<int32_t> states = random_states(static_cast<uint32_t>(w), count, 3);
    Stream<Int> xy(w, h), state(w, h);
    state.upload(states);
    xy.fill(-1);
    k.outputs(xy);
    int64_t want_written = 0;
    EXPECT_EQ(k.execute(where(state, 1)), std::count(states.begin(), states.end(), 1));
    const std::vector<int32_t> got = xy.download();
    for (int64_t e = 0; e < count; ++e) {
      const bool selected = states[static_cast<size_t>(e)] == 1;
      want_written += selected;
      const int32_t want = selected ? static_cast<int32_t>((e % w) * 4096 + e / w) : -1;
      ASSERT_EQ(got[static_cast<size_t>(e)], want) << w << "x" << h << " element " << e;
    }
    ASSERT_GT(want_written, 0);
  }
}

// A sparse, scattered selection (about one element in seven, the live paths of a wavefront
// after a few bounces), which the simd backend runs compacted: its lanes take the selected
// elements from a dense list (HostKernel.cpp), so each lane must still read its own element's
// inputs, see its own index, run its own number of loop iterations and store to its own
// element. Every output is recomputed here in integers, so any mix-up shows.
TEST_P(MaskTest, SparseScatteredSelectionRunsEachElementAsItself) {
  Program p = program("mask_sparse", [] {
    Input<Int2> in("in");
    Output<Int> out("out");
    Int n = in.x() & 15, acc = in.y(), i = 0;
    RILL_WHILE(i < n) {
      acc = acc * 3 + element_index() + i;
      i += 1;
    }
    RILL_ENDWHILE;
    out = acc;
  });
  Kernel k = compile(p);
  const std::vector<int32_t> states = random_states(11, kN, 7);
  const std::vector<int32_t> raw = random_states(12, 2 * kN, 1 << 20);
  std::vector<Stream<Int2>::host_type> ins(static_cast<size_t>(kN));
  for (size_t u = 0; u < ins.size(); ++u) {
    ins[u].x = raw[2 * u];
    ins[u].y = raw[2 * u + 1];
  }
  Stream<Int2> in(ins);
  Stream<Int> out(kN);
  Stream<Int> state(states);
  out.fill(-1);
  k.inputs(in).outputs(out);
  const int64_t selected = std::count(states.begin(), states.end(), 3);
  EXPECT_EQ(k.execute(where(state, 3)), selected);
  EXPECT_EQ(k.last_launch().processed, selected);
  const std::vector<int32_t> got = out.download();
  for (int64_t e = 0; e < kN; ++e) {
    const auto u = static_cast<size_t>(e);
    int32_t want = -1;
    if (states[u] == 3) {
      uint32_t acc = static_cast<uint32_t>(raw[2 * u + 1]);  // wraps as the kernel's Int does
      for (int32_t i = 0; i < (raw[2 * u] & 15); ++i)
        acc = acc * 3u + static_cast<uint32_t>(e) + static_cast<uint32_t>(i);
      want = static_cast<int32_t>(acc);
    }
    ASSERT_EQ(got[u], want) << "element " << e;
  }
  ASSERT_GT(selected, kN / 10);  // random_states: about kN / 7
}

TEST_P(MaskTest, EmptySelectionRunsNothing) {
  std::vector<float> xs = floats(9);
  Kernel k = compile(scale_program());
  Stream<Float> x(xs), y(kN);
  Stream<Int> ran(kN), state(kN);
  y.fill(-7.0f);
  ran.fill(0);
  state.fill(1);
  k.inputs(x).outputs(y, ran);
  EXPECT_EQ(k.execute(where(state, 2)), 0);
  EXPECT_EQ(k.last_launch().processed, 0);
  EXPECT_TRUE(bits_equal(y.download(), std::vector<float>(xs.size(), -7.0f)));
}

TEST_P(MaskTest, BadMasksAreErrors) {
  Kernel k = compile(scale_program());
  Stream<Float> x(kN), y(kN), wrong_type(kN);
  Stream<Int> ran(kN), short_state(kN - 1), state(kN);
  k.inputs(x).outputs(y, ran);
  expect_error([&] { k.execute(where(StreamRef(wrong_type), {1})); }, "must be a Stream<Int>");
  expect_error([&] { k.execute(where(short_state, 1)); }, "mask stream has 4999 elements");
  expect_error([&] { k.execute(where(StreamRef(state), {})); }, "1 to 8 state values");
  expect_error([&] { k.execute(where(state, {0, 1, 2, 3, 4, 5, 6, 7, 8})); }, "(got 9)");
}

RILL_BACKEND_TEST_SUITE(MaskTest);

}  // namespace
}  // namespace rill::testing
