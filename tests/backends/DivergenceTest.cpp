// Divergence: programs whose elements take different paths, in the patterns a lockstep backend
// (`simd`: groups of lanes share one instruction stream, masks say which lanes are on) can get
// wrong while a scalar one cannot:
//
// - a value assigned on one side of a branch only, read after it by lanes that did not
//   assign it (they must keep the old value, not the other lanes' new one);
// - a loop's value read after the loop by lanes that left it in earlier iterations, while the
//   other lanes kept iterating;
// - break, continue and discard taken by some lanes of a group, with statements after them;
// - streams whose length is not a multiple of the lane count (the last group is short),
//   runs of selected elements in masked launches, and 2D streams of every shape (simd runs
//   them in tiles of two rows).
//
// Every test runs on every backend and compares with the same control flow in C++.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class DivergenceTest : public BackendTest {};

TEST_P(DivergenceTest, OneSidedAssignmentsKeepOldValuesInOtherLanes) {
  const std::vector<int32_t> ns = small_ints(3, 1001, -5, 5);
  Program p = program("one_sided", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    Output<Float> z("z");
    Int a = 7;
    Float b = 0.5f;
    RILL_IF(n > 0) {
      Int t = n * 3;  // a temporary that only the lanes in the branch compute
      a = t + 1;
      RILL_IF(n > 3) {
        b = to_float(t) * 0.25f;
      }
      RILL_ENDIF;
    }
    RILL_ELSE_IF(n < -2) {
      b = -1.0f;
    }
    RILL_ENDIF;
    y = a;
    z = b;
  });
  auto [y, z] = run<Int, Float>(p, ns);
  for (size_t i = 0; i < ns.size(); ++i) {
    int32_t n = ns[i], a = 7;
    float b = 0.5f;
    if (n > 0) {
      a = n * 3 + 1;
      if (n > 3) b = static_cast<float>(n * 3) * 0.25f;
    } else if (n < -2) {
      b = -1.0f;
    }
    ASSERT_EQ(y[i], a) << "n=" << n << " at " << i;
    ASSERT_EQ(std::bit_cast<uint32_t>(z[i]), std::bit_cast<uint32_t>(b))
        << "n=" << n << " at " << i;
  }
}

TEST_P(DivergenceTest, LoopValuesSurviveForLanesThatLeftEarly) {
  // Trip counts from 0 to 40 side by side; `last` is written in every iteration and read
  // after the loop, `found` only in the iteration that breaks.
  const std::vector<int32_t> ns = small_ints(5, 999, 0, 40);
  Program p = program("left_early", [] {
    Input<Int> n("n");
    Output<Int> last_out("last");
    Output<Int> found_out("found");
    Int i = 0, last = -1, found = -1;
    RILL_WHILE(i < n) {
      Int sq = i * i;
      last = sq + n;
      RILL_IF(sq > 3 * n && found < 0) {
        found = i;
        RILL_BREAK;
      }
      RILL_ENDIF;
      i += 1;
    }
    RILL_ENDWHILE;
    last_out = last;
    found_out = found;
  });
  auto [last, found] = run<Int, Int>(p, ns);
  for (size_t k = 0; k < ns.size(); ++k) {
    int32_t n = ns[k], l = -1, f = -1;
    for (int32_t i = 0; i < n; ++i) {
      l = i * i + n;
      if (i * i > 3 * n && f < 0) {
        f = i;
        break;
      }
    }
    ASSERT_EQ(last[k], l) << "n=" << n << " at " << k;
    ASSERT_EQ(found[k], f) << "n=" << n << " at " << k;
  }
}

TEST_P(DivergenceTest, ContinueAndDiscardInSomeLanes) {
  const std::vector<int32_t> ns = small_ints(9, 777, 0, 30);
  Program p = program("continue_discard", [] {
    Input<Int> n("n");
    Output<Int> sum_out("sum");
    Int i = 0, sum = 0;
    RILL_WHILE(i < n) {
      i += 1;
      RILL_IF(i % 3 == 0) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      RILL_IF(n == 17 && i == 9) {
        RILL_DISCARD;
      }  // some lanes leave the whole kernel
      RILL_ENDIF;
      sum += i;
    }
    RILL_ENDWHILE;
    sum_out = sum;
  });
  Kernel k = compile(p);
  Stream<Int> in(ns), out(static_cast<int64_t>(ns.size()));
  out.fill(-5);
  k.inputs(in).outputs(out);
  const int64_t written = k.execute();
  const std::vector<int32_t> got = out.download();
  int64_t want_written = 0;
  for (size_t e = 0; e < ns.size(); ++e) {
    const int32_t n = ns[e];
    int32_t sum = 0;
    bool discarded = false;
    for (int32_t i = 1; i <= n; ++i) {
      if (i % 3 == 0) continue;
      if (n == 17 && i == 9) {
        discarded = true;
        break;
      }
      sum += i;
    }
    want_written += discarded ? 0 : 1;
    ASSERT_EQ(got[e], discarded ? -5 : sum) << "n=" << n << " at " << e;
  }
  EXPECT_EQ(written, want_written);
}

TEST_P(DivergenceTest, EveryStreamLengthAroundTheLaneCount) {
  // Lengths 0..33 cover short, exact and partial last groups for 4, 8 and 16 lanes; element
  // i's result depends on i, so a lane writing another element's result is caught.
  Program p = program("lengths", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float v = x;
    RILL_WHILE(v < 40.0f) {
      v = v * 2.0f + 1.0f;
    }
    RILL_ENDWHILE;
    y = v + to_float(element_index());
  });
  Kernel k = compile(p);
  for (int n = 0; n <= 33; ++n) {
    std::vector<float> xs(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i)
      xs[static_cast<size_t>(i)] = static_cast<float>((i * 7) % 11) + 0.5f;
    auto y = run_kernel<Float>(k, n, xs);
    ASSERT_EQ(static_cast<int>(y.size()), n);
    for (int i = 0; i < n; ++i) {
      float v = xs[static_cast<size_t>(i)];
      while (v < 40.0f) v = v * 2.0f + 1.0f;
      ASSERT_EQ(std::bit_cast<uint32_t>(y[static_cast<size_t>(i)]),
                std::bit_cast<uint32_t>(v + static_cast<float>(i)))
          << "length " << n << ", element " << i;
    }
  }
}

TEST_P(DivergenceTest, EveryImageShapeInTiles) {
  // 2D streams: simd runs whole rows in tiles (4 x 2 lanes at 8 lanes, 4 x 4 at 16), with
  // narrow images, partial tiles at the right edge, last rows short of a tile and several
  // threads' ranges. Each
  // element's results depend on its own input, index and coordinates, and some elements
  // discard, so a lane reading, computing or storing another element's value is caught.
  Program p = program("shapes", [] {
    Input<Int> n("n");
    Output<Int> id("id");
    Output<Int> xy("xy");
    Int2 c = element_coord();
    Int i = 0, v = n;
    RILL_WHILE(i < n % 13) {
      v = v * 3 + c.x() - c.y();
      i += 1;
    }
    RILL_ENDWHILE;
    RILL_IF(n % 29 == 5) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    id = element_index() * 7 + v;
    xy = c.x() * 4096 + c.y();
  });
  Kernel k = compile(p);
  const std::vector<std::pair<int, int>> shapes{
      {1, 1}, {1, 5}, {2, 3}, {3, 2},  {4, 1},  {4, 2},   {4, 3},    {5, 2},   {5, 5},
      {7, 4}, {8, 2}, {9, 3}, {11, 6}, {16, 1}, {37, 61}, {1024, 3}, {3, 1024}};
  for (auto [w, h] : shapes) {
    const int64_t count = int64_t{w} * h;
    std::vector<int32_t> ns(static_cast<size_t>(count));
    for (int64_t e = 0; e < count; ++e)
      ns[static_cast<size_t>(e)] = static_cast<int32_t>((e * 37 + 11) % 101);
    Stream<Int> in(w, h), id(w, h), xy(w, h);
    in.upload(ns);
    id.fill(-1);
    xy.fill(-1);
    k.inputs(in).outputs(id, xy);
    int64_t want_written = 0;
    const int64_t written = k.execute();
    const std::vector<int32_t> got_id = id.download(), got_xy = xy.download();
    for (int64_t e = 0; e < count; ++e) {
      const int32_t n = ns[static_cast<size_t>(e)], x = static_cast<int32_t>(e % w),
                    y = static_cast<int32_t>(e / w);
      int32_t v = n;
      for (int32_t i = 0; i < n % 13; ++i) v = v * 3 + x - y;
      const bool discarded = n % 29 == 5;
      want_written += discarded ? 0 : 1;
      ASSERT_EQ(got_id[static_cast<size_t>(e)], discarded ? -1 : static_cast<int32_t>(e) * 7 + v)
          << w << "x" << h << " element " << e;
      ASSERT_EQ(got_xy[static_cast<size_t>(e)], discarded ? -1 : x * 4096 + y)
          << w << "x" << h << " element " << e;
    }
    EXPECT_EQ(written, want_written) << w << "x" << h;
  }
}

RILL_BACKEND_TEST_SUITE(DivergenceTest);

}  // namespace
}  // namespace rill::testing
