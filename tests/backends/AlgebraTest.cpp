// Program algebra on every backend: a connected pair computes, in one launch, the same bits as
// the two programs launched one after the other with an intermediate stream, and a combined
// pair the same bits as the two launched separately. The programs read shared and private
// uniforms, gather from shared and private arrays, branch and loop per element, and one
// overwrites an input the other also reads.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class AlgebraTest : public BackendTest {
 protected:
  Uniform<Float> gain{1.5f, "gain"};
  Uniform<Int> bias{3, "bias"};
  Uniform<Float> shift{-0.75f, "shift"};
  Array<Float> table{random_floats(11, 37), "table"};
  Array<Float2> pairs{as_vec2(random_floats(12, 18)), "pairs"};
  Array<Float> ramp{random_floats(13, 9), "ramp"};

  static std::vector<glm::vec2> as_vec2(const std::vector<float>& v) {
    return unflatten<glm::vec2>(v);
  }

  // x and k element by element, with the hard values of both.
  std::vector<float> xs() const { return sweep_floats(21, 3000); }
  std::vector<int32_t> ks() const {
    std::vector<int32_t> k = sweep_ints(22, 3000);
    k.resize(xs().size(), 5);
    return k;
  }

  // Outputs uv (read by the second program) and steps (not read by it). Overwrites its copy
  // of x, which the second program also reads as it is in the stream.
  Program first() {
    return program("first", [&] {
      Input<Float> x("x");
      Input<Int> k("k");
      Output<Float2> uv("uv");
      Output<Int> steps("steps");
      x = x * gain;
      RILL_IF(x < 0.0f) {
        uv = Float2(-x, table[k]);
      }
      RILL_ELSE {
        uv.y() = x - table[k + bias];
        uv.x() = x;
      }
      RILL_ENDIF;
      Int i = 0;
      RILL_WHILE(i < (k & 7)) {
        uv = uv * 0.5f + pairs[i];
        i += 1;
      }
      RILL_ENDWHILE;
      steps = i + bias;
    });
  }

  // Reads uv from the first program, and x and k as the streams hold them.
  Program second() {
    return program("second", [&] {
      Input<Float2> uv("uv");
      Input<Int> k("k");
      Input<Float> x("x");
      Output<Float> r("r");
      Output<Int> code("code");
      // ramp is this program's array 0 but the fused program's array 2.
      // (separate statements: C++ leaves the order of operands unspecified).
      Float t = ramp[k];
      t = t + uv.x() * gain + uv.y() * shift + x;
      RILL_FOR(Int j = 0, j < (k & 3), j += 1) {
        t = t - table[j * 5 + k];
        RILL_IF(t < -4.0f) {
          RILL_BREAK;
        }
        RILL_ENDIF;
      }
      RILL_ENDFOR;
      r = t;
      code = to_int(t) + bias;
    });
  }
};

TEST_P(AlgebraTest, ConnectGivesTheBitsOfTwoLaunches) {
  auto x = xs();
  auto k = ks();
  Program a = first(), b = second();
  // Two launches, uv through an intermediate stream.
  auto [uv, steps] = run<Float2, Int>(a, x, k);
  auto [r, code] = run<Float, Int>(b, uv, k, x);
  // One launch: no uv stream; x and k are read once.
  Program ab = connect(a, b);
  ASSERT_EQ(ab.ir().inputs.size(), 2u);   // x, k (the two programs have 5)
  ASSERT_EQ(ab.ir().outputs.size(), 3u);  // r, code, steps (the two programs have 4)
  auto [fr, fcode, fsteps] = run<Float, Int, Int>(ab, x, k);
  EXPECT_EQ(last_written_, static_cast<int64_t>(x.size()));
  Describe d = describe_inputs(x, k);
  EXPECT_TRUE(bits_equal(fr, r, d));
  EXPECT_TRUE(bits_equal(fcode, code, d));
  EXPECT_TRUE(bits_equal(fsteps, steps, d));

  // A uniform changed after connecting is read by both halves at the next launch.
  gain.set(-2.0f);
  auto [uv2, steps2] = run<Float2, Int>(a, x, k);
  auto [r2, code2] = run<Float, Int>(b, uv2, k, x);
  auto [fr2, fcode2, fsteps2] = run<Float, Int, Int>(ab, x, k);
  EXPECT_TRUE(bits_equal(fr2, r2, d));
  EXPECT_TRUE(bits_equal(fcode2, code2, d));
  EXPECT_FALSE(bits_equal(fr2, fr));  // the uniform did change the result
}

TEST_P(AlgebraTest, ConnectIntoADiscardingProgram) {
  // The second program discards; the first has no output it does not read, so the fused
  // kernel writes (and counts) exactly what the second launch writes.
  auto x = xs();
  auto k = ks();
  Program a = program("scale", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * gain - table[to_int(x)];
  });
  Program b = program("cull", [&] {
    Input<Float> y("y");
    Input<Int> k("k");
    Output<Float> r("r");
    RILL_IF(y < shift || (k & 1) == 1) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    r = y + 1.0f;
  });
  auto y = run<Float>(a, x);
  auto r = run<Float>(b, y, k);
  int64_t written = last_written_;
  Program ab = a >> b;
  ASSERT_EQ(ab.ir().outputs.size(), 1u);
  auto fr = run<Float>(ab, x, k);
  EXPECT_EQ(last_written_, written);
  EXPECT_LT(written, static_cast<int64_t>(x.size()));  // some elements did discard
  EXPECT_TRUE(bits_equal(fr, r, describe_inputs(x, k)));
}

TEST_P(AlgebraTest, CombineGivesTheBitsOfSeparateLaunches) {
  auto x = xs();
  auto k = ks();
  auto w = random_floats(23, x.size());
  Program a = first();
  Program c = program("other", [&] {
    Input<Float> w("w");
    Input<Int> k("k");  // shared with first
    Output<Float> s("s");
    Float acc = w;
    RILL_DO {
      acc = acc * gain + table[k];
      k = k >> 1;
    }
    RILL_UNTIL(k == 0 || k == -1);
    s = acc;
  });
  auto [uv, steps] = run<Float2, Int>(a, x, k);
  auto s = run<Float>(c, w, k);
  Program ac = combine(a, c);
  ASSERT_EQ(ac.ir().inputs.size(), 3u);  // x, k, w (the two programs have 4)
  auto [fuv, fsteps, fs] = run<Float2, Int, Float>(ac, x, k, w);
  Describe d = describe_inputs(x, k, w);
  EXPECT_TRUE(bits_equal(fuv, uv, d));
  EXPECT_TRUE(bits_equal(fsteps, steps, d));
  EXPECT_TRUE(bits_equal(fs, s, d));
}

RILL_BACKEND_TEST_SUITE(AlgebraTest);

}  // namespace
}  // namespace rill::testing
