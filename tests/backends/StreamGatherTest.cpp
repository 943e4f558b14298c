// Gathers from streams: a kernel reads, at any index, a stream an earlier launch wrote, with
// no host round trip in between; and misuse (gathering from a stream being written, the wrong
// number of indices) is a clear error.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class StreamGatherTest : public BackendTest {};

// Host reference for the horizontal then vertical 3-tap box blur below, one binary32
// operation at a time, with clamped borders.
std::vector<float> blur_reference(const std::vector<float>& img, int w, int h) {
  auto at = [&](const std::vector<float>& v, int x, int y) {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return v[static_cast<size_t>(y * w + x)];
  };
  std::vector<float> mid(img.size()), out(img.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = at(img, x - 1, y) + at(img, x, y);
      s = s + at(img, x + 1, y);
      mid[static_cast<size_t>(y * w + x)] = s * (1.0f / 3.0f);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float s = at(mid, x, y - 1) + at(mid, x, y);
      s = s + at(mid, x, y + 1);
      out[static_cast<size_t>(y * w + x)] = s * (1.0f / 3.0f);
    }
  return out;
}

TEST_P(StreamGatherTest, SeparableBlurChainsOnTheDevice) {
  const int w = 37, h = 23;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> value(-4.0f, 4.0f);
  std::vector<float> img(w * h);
  for (float& v : img) v = value(rng);
  Stream<Float> src(w, h, "src"), mid(w, h, "mid"), dst(w, h, "dst");
  src.upload(img);
  // Each pass gathers its neighbours from the stream the previous launch wrote.
  Program horizontal = program("blur_h", [&] {
    Output<Float> out("out");
    Int2 p = element_coord();
    Float s = src(p.x() - 1, p.y()) + src(p);
    out = (s + src(p.x() + 1, p.y())) * (1.0f / 3.0f);
  });
  Program vertical = program("blur_v", [&] {
    Output<Float> out("out");
    Int2 p = element_coord();
    Float s = mid(p.x(), p.y() - 1) + mid(p);
    out = (s + mid(p.x(), p.y() + 1)) * (1.0f / 3.0f);
  });
  Kernel kh = compile(horizontal), kv = compile(vertical);
  kh.bind("out", mid).execute();
  kv.bind("out", dst).execute();
  EXPECT_TRUE(bits_equal(dst.download(), blur_reference(img, w, h)));

  // New input data flows through both passes again (the host wrote src, the device mid).
  for (float& v : img) v = -v * 0.5f;
  src.upload(img);
  kh.execute();
  kv.execute();
  EXPECT_TRUE(bits_equal(dst.download(), blur_reference(img, w, h)));
}

TEST_P(StreamGatherTest, OneDimensionalGatherClampsAndReadsEarlierLaunches) {
  const int n = 300;
  Stream<Int> squares(n, "squares");
  Program square = program("square", [] {
    Output<Int> out("out");
    Int i = element_index();
    out = i * i;
  });
  // Reverses the squares, reading far outside at both ends (clamped to the edges).
  Program reverse = program("reverse", [&] {
    Output<Int> out("out");
    Int i = element_index();
    Int j = (n - 1) - i;
    out = squares[j] + squares[i * 4096 - 2000000] * 0 + squares(j + n * 2) - squares[n - 1];
  });
  Stream<Int> out(n);
  compile(square).bind("out", squares).execute();
  compile(reverse).bind("out", out).execute();
  std::vector<int32_t> got = out.download();
  ASSERT_EQ(got.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const int j = n - 1 - i;
    ASSERT_EQ(got[static_cast<size_t>(i)], j * j) << "at " << i;
  }
}

TEST_P(StreamGatherTest, VectorStreamsGatherWholeElements) {
  const int n = 64;
  Stream<Float3> points(n, "points");
  Program make = program("make_points", [] {
    Output<Float3> p("p");
    Float i = to_float(element_index());
    p = Float3(i, i * 0.5f, -i);
  });
  Program diff = program("diff_points", [&] {
    Output<Float3> d("d");
    Int i = element_index();
    d = points[i + 1] - points[i];
  });
  Stream<Float3> d(n);
  compile(make).bind("p", points).execute();
  compile(diff).bind("d", d).execute();
  std::vector<glm::vec3> got = d.download();
  for (int i = 0; i < n; ++i) {
    const float step = i + 1 < n ? 1.0f : 0.0f;
    EXPECT_EQ(got[static_cast<size_t>(i)], glm::vec3(step, step * 0.5f, -step)) << "at " << i;
  }
}

TEST_P(StreamGatherTest, BoundaryModesApplyToStreams) {
  const int n = 10;
  Stream<Int> ramp(n, "ramp");
  compile(program("ramp_i",
                  [] {
                    Output<Int> o("o");
                    o = element_index() * 10;
                  }))
      .bind("o", ramp)
      .execute();
  Stream<Int> wrap_view = ramp, constant_view = ramp;  // handles on the same data
  wrap_view.boundary(Boundary::Wrap);
  constant_view.boundary(Boundary::Constant, -7);
  Program p = program("read_outside", [&] {
    Output<Int2> o("o");
    Int i = element_index() - 3;  // -3 .. n - 4, and beyond with + n below
    o = Int2(wrap_view[i + n * (i & 1)], constant_view[i + n * (i & 1)]);
  });
  Stream<Int2> out(n);
  compile(p).bind("o", out).execute();
  std::vector<glm::ivec2> got = out.download();
  for (int e = 0; e < n; ++e) {
    const int i = e - 3, j = i + n * (i & 1);
    const int wrapped = ((j % n) + n) % n;
    EXPECT_EQ(got[static_cast<size_t>(e)].x, wrapped * 10) << "index " << j;
    EXPECT_EQ(got[static_cast<size_t>(e)].y, j >= 0 && j < n ? j * 10 : -7) << "index " << j;
  }
}

// The example of docs/programming-model.md ("Boundary modes of streams"), as written there but
// on each backend: one element past each end of a 4-element stream, read through four handles
// with the four modes.
TEST_P(StreamGatherTest, TheDocumentedBoundaryExampleRuns) {
  Stream<Float> ring(std::vector<float>{1, 2, 3, 4});  // uploaded, or written by a launch
  Stream<Float> clamped = ring, wrapped = ring, mirrored = ring, zero = ring;  // one data
  wrapped.boundary(Boundary::Wrap);
  mirrored.boundary(Boundary::Mirror);
  zero.boundary(Boundary::Constant, 0.0f);
  Stream<Float4> out(6, "out");
  Program edges = program("edges", [&] {
    Output<Float4> o("o");
    Int i = element_index() - 1;  // -1 .. 4: one element past each end
    o = Float4(clamped[i], wrapped[i], mirrored[i], zero[i]);
  });
  compile(edges).bind("o", out).execute();
  const std::vector<glm::vec4> want = {{1, 4, 1, 0}, {1, 1, 1, 1}, {2, 2, 2, 2},
                                       {3, 3, 3, 3}, {4, 4, 4, 4}, {4, 1, 4, 0}};
  EXPECT_EQ(out.download(), want);
  // Only Constant takes a value for outside.
  EXPECT_THROW(wrapped.boundary(Boundary::Wrap, 1.0f), Error);
}

TEST_P(StreamGatherTest, GatheringFromTheStreamBeingWrittenIsAnError) {
  Stream<Float> s(16, "field");
  Program p = program("smooth_in_place", [&] {
    Output<Float> out("out");
    Int i = element_index();
    out = s[i - 1] + s[i + 1];
  });
  Kernel k = compile(p);
  k.bind("out", s);
  try {
    k.execute();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("smooth_in_place"), std::string::npos) << m;
    EXPECT_NE(m.find("'field'"), std::string::npos) << m;
    EXPECT_NE(m.find("'out'"), std::string::npos) << m;
  }
  // Reading the element's own value through an input bound to the same stream stays allowed.
  Program own = program("double_in_place", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  s.fill(1.5f);
  compile(own).bind("x", s).bind("y", s).execute();
  EXPECT_TRUE(bits_equal(s.download(), std::vector<float>(16, 3.0f)));
}

TEST_P(StreamGatherTest, WrongNumberOfIndicesIsAnError) {
  Stream<Float> line(8, "line"), image(4, 2, "image");
  EXPECT_THROW(program("bad_line",
                       [&] {
                         Output<Float> o("o");
                         o = line(element_index(), 0);
                       }),
               Error);
  EXPECT_THROW(program("bad_image",
                       [&] {
                         Output<Float> o("o");
                         o = image[element_index()];
                       }),
               Error);
}

// A stream written by this backend, gathered by the CPU backend, and the other way round.
TEST_P(StreamGatherTest, GathersAcrossBackends) {
  const int n = 40;
  Stream<Float> a(n, "a"), b(n, "b"), c(n, "c");
  Program ramp = program("ramp", [] {
    Output<Float> o("o");
    o = to_float(element_index()) * 0.25f;
  });
  Program shift_b = program("shift_a", [&] {
    Output<Float> o("o");
    o = a[element_index() + 1];
  });
  Program shift_c = program("shift_b", [&] {
    Output<Float> o("o");
    o = b[element_index() + 1];
  });
  compile(ramp).bind("o", a).execute();
  rill::compile(shift_b, "cpu").bind("o", b).execute();
  compile(shift_c).bind("o", c).execute();
  std::vector<float> got = c.download();
  for (int i = 0; i < n; ++i)
    EXPECT_EQ(got[static_cast<size_t>(i)], static_cast<float>(std::min(i + 2, n - 1)) * 0.25f);
}

// Arrays and streams longer than a texture row (4096 texels on the fragment stage, where
// element g is texel (g % 4096, g / 4096)): gathers reach every row, the last one partial.
TEST_P(StreamGatherTest, GathersReachEveryRowOfLongArraysAndStreams) {
  const int n = 10007;
  std::vector<int32_t> values(n);
  std::vector<glm::vec3> triples(n);
  for (int i = 0; i < n; ++i) {
    values[static_cast<size_t>(i)] = 3 * i + 1;
    triples[static_cast<size_t>(i)] =
        glm::vec3(static_cast<float>(i), 0.5f * static_cast<float>(i), -1.0f);
  }
  Array<Int> table(values, "table");
  Stream<Float3> stream(triples);
  const int m = 3000;
  Program p = program("long_gather", [&] {
    Output<Int> a("a");
    Output<Float3> b("b");
    Int i = element_index();
    Int j = (i * 7919 + 4090) % n;  // spread over all rows, across the 4096 boundaries
    a = table[j];
    b = stream[j];
  });
  Stream<Int> a(m);
  Stream<Float3> b(m);
  compile(p).bind("a", a).bind("b", b).execute();
  const std::vector<int32_t> ga = a.download();
  const std::vector<glm::vec3> gb = b.download();
  for (int i = 0; i < m; ++i) {
    const int j = (i * 7919 + 4090) % n;
    ASSERT_EQ(ga[static_cast<size_t>(i)], 3 * j + 1) << "element " << i << " reads " << j;
    ASSERT_EQ(gb[static_cast<size_t>(i)], triples[static_cast<size_t>(j)])
        << "element " << i << " reads " << j;
  }
}

}  // namespace

RILL_BACKEND_TEST_SUITE(StreamGatherTest);

}  // namespace rill::testing
