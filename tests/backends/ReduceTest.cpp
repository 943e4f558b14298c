// Reductions on every backend: each result is compared, bit for bit, with a host fold in the
// documented order (Reduce.h), so every backend gives the same bits, for sizes around the
// block size, 1D and 2D streams, Float and Int vectors, and hard values.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class ReduceTest : public BackendTest {};

// The documented order: blocks of kReduceBlock (rows never mixed), each folded left to right,
// then the block results the same way, until one is left.
template <class T, class Op>
T host_tree(std::vector<T> v, int64_t width, Op op) {
  const int64_t B = kReduceBlock;
  auto fold_rows = [&](const std::vector<T>& in, int64_t w) {
    std::vector<T> out;
    for (int64_t row = 0; row < static_cast<int64_t>(in.size()); row += w)
      for (int64_t first = row; first < row + w; first += B) {
        T acc = in[static_cast<size_t>(first)];
        for (int64_t i = first + 1; i < std::min(first + B, row + w); ++i)
          acc = op(acc, in[static_cast<size_t>(i)]);
        out.push_back(acc);
      }
    return out;
  };
  v = fold_rows(v, width);
  while (v.size() > 1) v = fold_rows(v, static_cast<int64_t>(v.size()));
  return v[0];
}

// The DSL's min and max (Eval.h): the first operand unless the second is strictly smaller
// (larger).
float min_op(float a, float b) {
  return b < a ? b : a;
}
float max_op(float a, float b) {
  return a < b ? b : a;
}

std::vector<float> values(uint32_t seed, size_t n) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> v(-1000.0f, 1000.0f);
  std::vector<float> out(n);
  for (float& x : out) x = v(rng);
  return out;
}

TEST_P(ReduceTest, FloatSumMinMaxInTheDocumentedOrder) {
  for (size_t n : {size_t{1}, size_t{63}, size_t{64}, size_t{65}, size_t{4097}, size_t{300001}}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    std::vector<float> v = values(static_cast<uint32_t>(n), n);
    Stream<Float> s(v);
    const std::string be = backend_name();
    EXPECT_EQ(bits_of(sum(s, be)),
              bits_of(host_tree(v, static_cast<int64_t>(n), std::plus<float>())));
    EXPECT_EQ(bits_of(minimum(s, be)), bits_of(host_tree(v, static_cast<int64_t>(n), min_op)));
    EXPECT_EQ(bits_of(maximum(s, be)), bits_of(host_tree(v, static_cast<int64_t>(n), max_op)));
  }
}

TEST_P(ReduceTest, TwoDimensionalStreamsFoldRowByRow) {
  // One row high too: a 2D stream all the same (a one-row tile of an image).
  for (const int h : {7, 1}) {
    const int w = 130;
    std::vector<float> v = values(3, w * h);
    Stream<Float> s(w, h, "image");
    s.upload(v);
    EXPECT_EQ(bits_of(sum(s, backend_name())), bits_of(host_tree(v, w, std::plus<float>())))
        << w << "x" << h;
  }
}

// The example of docs/programming-model.md ("Reductions"), written out from the text rather
// than through host_tree: a 130 x 3 stream gives blocks of 64, 64 and 2 elements per row,
// nine partial results p0 .. p8 in row order, then one block of nine. The values make the
// layout matter: folding the 390 elements as a 1D stream of blocks that cross rows gives
// other bits, which the test checks too.
TEST_P(ReduceTest, TheDocumentedTwoDimensionalBlockLayout) {
  const int w = 130, h = 3;
  std::vector<float> v = values(11, w * h);
  Stream<Float> s(w, h, "image");
  s.upload(v);
  std::vector<float> partial;  // row 0's blocks left to right, then row 1's, then row 2's
  for (int y = 0; y < h; ++y)
    for (int first = 0; first < w; first += 64) {
      float acc = v[static_cast<size_t>(y * w + first)];
      for (int x = first + 1; x < std::min(first + 64, w); ++x)
        acc = acc + v[static_cast<size_t>(y * w + x)];
      partial.push_back(acc);
    }
  ASSERT_EQ(partial.size(), 9u);
  float want = partial[0];
  for (size_t k = 1; k < partial.size(); ++k) want = want + partial[k];
  EXPECT_EQ(bits_of(sum(s, backend_name())), bits_of(want));
  // Blocks of 64 over the flattened stream (what a 1D stream of 390 elements does).
  EXPECT_NE(bits_of(host_tree(v, w * h, std::plus<float>())), bits_of(want));
}

TEST_P(ReduceTest, VectorsReduceComponentwise) {
  const size_t n = 5000;
  std::vector<float> a = values(5, n), b = values(6, n), c = values(7, n);
  std::vector<glm::vec3> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = glm::vec3(a[i], b[i], c[i]);
  Stream<Float3> s(v);
  glm::vec3 got = sum(s, backend_name());
  EXPECT_EQ(bits_of(got.x), bits_of(host_tree(a, n, std::plus<float>())));
  EXPECT_EQ(bits_of(got.y), bits_of(host_tree(b, n, std::plus<float>())));
  EXPECT_EQ(bits_of(got.z), bits_of(host_tree(c, n, std::plus<float>())));
}

TEST_P(ReduceTest, IntegersWrapAndTruthValuesCount) {
  const size_t n = 70000;
  std::vector<int32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = static_cast<int32_t>(i * 2654435761u);
  Stream<Int> s(v);
  const std::string be = backend_name();
  auto wrap_add = [](int32_t x, int32_t y) {
    return static_cast<int32_t>(static_cast<uint32_t>(x) + static_cast<uint32_t>(y));
  };
  EXPECT_EQ(sum(s, be), host_tree(v, n, wrap_add));
  EXPECT_EQ(minimum(s, be), *std::min_element(v.begin(), v.end()));
  EXPECT_EQ(maximum(s, be), *std::max_element(v.begin(), v.end()));

  std::vector<int32_t> flags(n, 0);
  for (size_t i = 0; i < n; i += 7) flags[i] = static_cast<int32_t>(i % 5) - 2;  // some 0s too
  Stream<Int> f(flags);
  EXPECT_EQ(count(f, be),
            std::count_if(flags.begin(), flags.end(), [](int32_t x) { return x != 0; }));
  EXPECT_TRUE(any(f, be));
  EXPECT_FALSE(all(f, be));
  f.fill(0);
  EXPECT_FALSE(any(f, be));
  EXPECT_EQ(count(f, be), 0);
  f.fill(-3);
  EXPECT_TRUE(all(f, be));
  EXPECT_EQ(count(f, be), static_cast<int64_t>(n));
}

TEST_P(ReduceTest, HardValuesKeepTheirBits) {
  // Infinities, NaN, signed zeros: the result follows the fold order exactly.
  std::vector<float> v = values(9, 1000);
  v[10] = -0.0f;
  v[500] = std::numeric_limits<float>::infinity();
  Stream<Float> s(v);
  EXPECT_EQ(bits_of(maximum(s, backend_name())), bits_of(std::numeric_limits<float>::infinity()));
  EXPECT_EQ(bits_of(sum(s, backend_name())), bits_of(host_tree(v, 1000, std::plus<float>())));
  std::vector<float> zeros(100, -0.0f);
  EXPECT_EQ(bits_of(sum(Stream<Float>(zeros), backend_name())), bits_of(-0.0f));
}

TEST_P(ReduceTest, RunsWhereAnEarlierLaunchLeftTheData) {
  // The stream is written by a kernel on this backend; the reduction runs there (no backend
  // named) and only the result is read back.
  Program ramp = program("reduce_ramp", [] {
    Output<Int> o("o");
    o = element_index();
  });
  Stream<Int> s(100000);
  compile(ramp).bind("o", s).execute();
  EXPECT_EQ(sum(s), static_cast<int32_t>(int64_t{99999} * 100000 / 2));
}

TEST_P(ReduceTest, RepeatedReductionsSeeNewDataAndReleaseDroppedStreams) {
  // The second and later reductions of a stream reuse its kernels and partial streams.
  Stream<Float> s(std::vector<float>(1000, 0.5f));
  const std::string be = backend_name();
  EXPECT_EQ(sum(s, be), 500.0f);
  s.fill(2.0f);
  EXPECT_EQ(sum(s, be), 2000.0f);
  EXPECT_EQ(maximum(s, be), 2.0f);
  std::weak_ptr<rill::detail::StreamState> dropped;
  {
    Stream<Float> temporary(std::vector<float>(5000, 1.0f));
    dropped = StreamRef(temporary).shared();
    EXPECT_EQ(sum(temporary, be), 5000.0f);
  }
  // Held by the cached kernels until the next reduction notices it was dropped.
  EXPECT_EQ(sum(s, be), 2000.0f);
  EXPECT_TRUE(dropped.expired());
}

TEST_P(ReduceTest, EmptyStreamsGiveTheIdentity) {
  Stream<Float> e(0);
  Stream<Int> ei(0);
  const std::string be = backend_name();
  EXPECT_EQ(bits_of(sum(e, be)), bits_of(0.0f));
  EXPECT_EQ(minimum(e, be), std::numeric_limits<float>::infinity());
  EXPECT_EQ(maximum(e, be), -std::numeric_limits<float>::infinity());
  EXPECT_EQ(minimum(ei, be), std::numeric_limits<int32_t>::max());
  EXPECT_EQ(maximum(ei, be), std::numeric_limits<int32_t>::min());
  EXPECT_EQ(count(ei, be), 0);
  EXPECT_FALSE(any(ei, be));
  EXPECT_TRUE(all(ei, be));
}

TEST_P(ReduceTest, TruthReductionsNeedAnIntStream) {
  Stream<Float> f(10, "energies");
  try {
    (void)rill::detail::reduce(f, ReduceOp::Count, backend_name());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'energies'"), std::string::npos) << e.what();
  }
}

}  // namespace

RILL_BACKEND_TEST_SUITE(ReduceTest);

}  // namespace rill::testing
