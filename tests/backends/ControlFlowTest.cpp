// Data-dependent control flow: every construct (RILL_IF / ELSE_IF / ELSE, WHILE, DO / UNTIL,
// FOR) with BREAK and CONTINUE in each loop kind, nested loops, and trip counts that differ per
// element. Each kernel is mirrored by the same C++ control flow as the reference.
//
// Loops that use RILL_CONTINUE carry a guard counter in their condition, so that a backend
// whose `continue` skips a for loop's step or a do-until loop's condition fails the test
// instead of hanging it.
#include "BackendTest.h"

namespace rill::testing {
namespace {

class ControlFlowTest : public BackendTest {};

TEST_P(ControlFlowTest, IfElseIfElse) {
  auto xs = sweep_floats(1, 2048);
  Program p = program("if_chain", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> branch("branch");
    RILL_IF(x < 0.0f) {
      y = -x;
      branch = 0;
    }
    RILL_ELSE_IF(x < 1.0f) {
      y = x * x;
      branch = 1;
    }
    RILL_ELSE_IF(x < 2.0f) {
      y = 2.0f;
      branch = 2;
      RILL_IF(x > 1.5f) {  // nested
        y = 3.0f;
        branch = 5;
      }
      RILL_ENDIF;
    }
    RILL_ELSE {  // also NaN, for which every comparison is false
      y = x + 1.0f;
      branch = 3;
    }
    RILL_ENDIF;
    RILL_IF(true) {
      branch = branch * 10;
    }  // a host constant condition
    RILL_ENDIF;
  });
  auto [y, branch] = run<Float, Int>(p, xs);
  auto ref = [](float x) -> std::pair<float, int32_t> {
    if (x < 0.0f) return {-x, 0};
    if (x < 1.0f) return {x * x, 1};
    if (x < 2.0f) return x > 1.5f ? std::pair{3.0f, 5} : std::pair{2.0f, 2};
    return {x + 1.0f, 3};
  };
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(y, map(xs, [&](float x) { return ref(x).first; }), d));
  EXPECT_TRUE(bits_equal(branch, map(xs, [&](float x) { return ref(x).second * 10; }), d));
}

TEST_P(ControlFlowTest, WhileDataDependentTripCount) {
  auto ns = small_ints(2, 3000, -5, 5000);
  Program p = program("collatz", [] {
    Input<Int> n("n");
    Output<Int> steps("steps");
    Int v = n;
    Int k = 0;
    RILL_WHILE(v != 1 && k < 1000) {
      RILL_IF((v & 1) == 0) {
        v = v / 2;
      }
      RILL_ELSE {
        v = v * 3 + 1;
      }
      RILL_ENDIF;
      k += 1;
    }
    RILL_ENDWHILE;
    steps = k;
  });
  auto steps = run<Int>(p, ns);
  auto ref = [](int32_t v) {
    int32_t k = 0;
    while (v != 1 && k < 1000) {
      v = (v & 1) == 0 ? v / 2 : static_cast<int32_t>(static_cast<uint32_t>(v) * 3u + 1u);
      k += 1;
    }
    return k;
  };
  EXPECT_TRUE(bits_equal(steps, map(ns, ref), describe_inputs(ns)));
}

TEST_P(ControlFlowTest, WhileBreakContinue) {
  auto ns = small_ints(3, 2000, -3, 60);
  auto ms = small_ints(4, 2000, 0, 400);
  Program p = program("while_break_continue", [] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> acc_out("acc");
    Output<Int> i_out("i");
    Int i = 0;
    Int acc = 0;
    RILL_WHILE(i < n) {
      i += 1;
      RILL_IF(i % 3 == 0) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      acc += i;
      RILL_IF(acc > m) {
        RILL_BREAK;
      }
      RILL_ENDIF;
    }
    RILL_ENDWHILE;
    acc_out = acc;
    i_out = i;
  });
  auto [acc, iv] = run<Int, Int>(p, ns, ms);
  auto ref = [](int32_t n, int32_t m) {
    int32_t i = 0, acc = 0;
    while (i < n) {
      i += 1;
      if (i % 3 == 0) continue;
      acc += i;
      if (acc > m) break;
    }
    return std::pair{acc, i};
  };
  Describe d = describe_inputs(ns, ms);
  EXPECT_TRUE(
      bits_equal(acc, map(ns, ms, [&](int32_t n, int32_t m) { return ref(n, m).first; }), d));
  EXPECT_TRUE(
      bits_equal(iv, map(ns, ms, [&](int32_t n, int32_t m) { return ref(n, m).second; }), d));
}

TEST_P(ControlFlowTest, DoUntil) {
  auto xs = sweep_floats(5, 2048);
  Program p = program("halve", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> count("count");
    Float v = x;
    Int k = 0;
    RILL_DO {  // runs at least once, even when v < 1 already
      v = v * 0.5f;
      k += 1;
    }
    RILL_UNTIL(v < 1.0f || k >= 200);
    y = v;
    count = k;
  });
  auto [y, count] = run<Float, Int>(p, xs);
  auto ref = [](float v) {
    int32_t k = 0;
    do {
      v = v * 0.5f;
      k += 1;
    } while (!(v < 1.0f || k >= 200));
    return std::pair{v, k};
  };
  Describe d = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(y, map(xs, [&](float x) { return ref(x).first; }), d));
  EXPECT_TRUE(bits_equal(count, map(xs, [&](float x) { return ref(x).second; }), d));
}

// RILL_CONTINUE in a do-until loop goes to the condition (it must not skip it).
TEST_P(ControlFlowTest, DoUntilBreakContinue) {
  auto ns = small_ints(6, 2000, -2, 40);
  auto ms = small_ints(7, 2000, 0, 300);
  Program p = program("do_break_continue", [] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> acc_out("acc");
    Output<Int> i_out("i");
    Output<Int> guard_out("guard");
    Int i = 0;
    Int acc = 0;
    Int guard = 0;
    RILL_DO {
      guard += 1;
      i += 1;
      RILL_IF(i % 2 == 0) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      acc += i;
      RILL_IF(acc > m) {
        RILL_BREAK;
      }
      RILL_ENDIF;
    }
    RILL_UNTIL(i >= n || guard >= 1000);
    acc_out = acc;
    i_out = i;
    guard_out = guard;
  });
  auto [acc, iv, guard] = run<Int, Int, Int>(p, ns, ms);
  auto ref = [](int32_t n, int32_t m) {
    int32_t i = 0, acc = 0, guard = 0;
    do {
      guard += 1;
      i += 1;
      if (i % 2 == 0) continue;  // C++ continue also goes to the condition
      acc += i;
      if (acc > m) break;
    } while (!(i >= n || guard >= 1000));
    return std::tuple{acc, i, guard};
  };
  Describe d = describe_inputs(ns, ms);
  EXPECT_TRUE(bits_equal(
      acc, map(ns, ms, [&](int32_t n, int32_t m) { return std::get<0>(ref(n, m)); }), d));
  EXPECT_TRUE(
      bits_equal(iv, map(ns, ms, [&](int32_t n, int32_t m) { return std::get<1>(ref(n, m)); }), d));
  EXPECT_TRUE(bits_equal(
      guard, map(ns, ms, [&](int32_t n, int32_t m) { return std::get<2>(ref(n, m)); }), d));
}

// RILL_CONTINUE in a for loop still runs the step.
TEST_P(ControlFlowTest, ForBreakContinue) {
  auto ns = small_ints(8, 2000, -2, 50);
  auto ms = small_ints(9, 2000, 0, 500);
  Program p = program("for_break_continue", [] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> acc_out("acc");
    Output<Int> guard_out("guard");
    Int acc = 0;
    Int guard = 0;
    RILL_FOR(Int i = 0, i < n && guard < 1000, i += 1) {
      guard += 1;
      RILL_IF(i % 3 == 1) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      acc += i;
      RILL_IF(acc > m) {
        RILL_BREAK;
      }
      RILL_ENDIF;
    }
    RILL_ENDFOR;
    acc_out = acc;
    guard_out = guard;
  });
  auto [acc, guard] = run<Int, Int>(p, ns, ms);
  auto ref = [](int32_t n, int32_t m) {
    int32_t acc = 0, guard = 0;
    for (int32_t i = 0; i < n && guard < 1000; i += 1) {
      guard += 1;
      if (i % 3 == 1) continue;
      acc += i;
      if (acc > m) break;
    }
    return std::pair{acc, guard};
  };
  Describe d = describe_inputs(ns, ms);
  EXPECT_TRUE(
      bits_equal(acc, map(ns, ms, [&](int32_t n, int32_t m) { return ref(n, m).first; }), d));
  EXPECT_TRUE(
      bits_equal(guard, map(ns, ms, [&](int32_t n, int32_t m) { return ref(n, m).second; }), d));
}

// For loops with host-constant bounds (unrollable; zero trips) and a float counter.
TEST_P(ControlFlowTest, ForConstantBounds) {
  auto xs = sweep_floats(10, 1024);
  Program p = program("for_constant", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = 0.0f;
    RILL_FOR(Int i = 0, i < 8, i += 1) {
      acc = acc * x + to_float(i);
    }
    RILL_ENDFOR;
    RILL_FOR(Int i = 5, i < 5, i += 1) {
      acc = -1.0f;
    }  // never runs
    RILL_ENDFOR;
    RILL_FOR(Float t = 0.0f, t < 1.0f, t += 0.25f) {
      acc += t;
    }
    RILL_ENDFOR;
    y = acc;
  });
  auto y = run<Float>(p, xs);
  auto ref = [](float x) {
    float acc = 0.0f;
    for (int i = 0; i < 8; ++i) acc = acc * x + static_cast<float>(i);
    for (float t = 0.0f; t < 1.0f; t += 0.25f) acc += t;
    return acc;
  };
  EXPECT_TRUE(bits_equal(y, map(xs, ref), describe_inputs(xs)));
}

// Nested loops of all three kinds, with break and continue at each level: each applies to
// its innermost loop only.
TEST_P(ControlFlowTest, NestedLoopsBreakContinue) {
  auto ns = small_ints(11, 3000, -1, 25);
  auto ms = small_ints(12, 3000, 0, 60);
  Program p = program("nested", [] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> acc_out("acc");
    Int acc = 0;
    Int guard = 0;
    RILL_FOR(Int i = 0, i < n && guard < 100000, i += 1) {
      RILL_IF(i % 4 == 3) {
        RILL_CONTINUE;
      }  // outer continue, before the inner loops
      RILL_ENDIF;
      Int j = 0;
      RILL_WHILE(j < 10) {
        j += 1;
        guard += 1;
        RILL_IF(j == 2) {
          RILL_CONTINUE;
        }  // inner continue
        RILL_ENDIF;
        RILL_IF(j * i > m) {
          RILL_BREAK;
        }  // inner break
        RILL_ENDIF;
        acc += j;
        Int k = 0;
        RILL_DO {  // third level
          k += 1;
          guard += 1;
          RILL_IF(k == 1) {
            RILL_CONTINUE;
          }
          RILL_ENDIF;
          RILL_IF(k > j) {
            RILL_BREAK;
          }
          RILL_ENDIF;
          acc += 100;
        }
        RILL_UNTIL(k >= 3 || guard >= 100000);
      }
      RILL_ENDWHILE;
      acc += j * 1000;
      RILL_IF(acc > 200000) {
        RILL_BREAK;
      }  // outer break, after the inner loops
      RILL_ENDIF;
    }
    RILL_ENDFOR;
    acc_out = acc;
  });
  auto acc = run<Int>(p, ns, ms);
  auto ref = [](int32_t n, int32_t m) {
    int32_t acc = 0, guard = 0;
    for (int32_t i = 0; i < n && guard < 100000; i += 1) {
      if (i % 4 == 3) continue;
      int32_t j = 0;
      while (j < 10) {
        j += 1;
        guard += 1;
        if (j == 2) continue;
        if (j * i > m) break;
        acc += j;
        int32_t k = 0;
        do {
          k += 1;
          guard += 1;
          if (k == 1) continue;
          if (k > j) break;
          acc += 100;
        } while (!(k >= 3 || guard >= 100000));
      }
      acc += j * 1000;
      if (acc > 200000) break;
    }
    return acc;
  };
  EXPECT_TRUE(bits_equal(acc, map(ns, ms, ref), describe_inputs(ns, ms)));
}

// A loop that never exits through its condition: RILL_WHILE(true) with a break.
TEST_P(ControlFlowTest, WhileTrueBreak) {
  auto ns = small_ints(13, 1000, 0, 100);
  Program p = program("while_true", [] {
    Input<Int> n("n");
    Output<Int> out("out");
    Int i = 0;
    RILL_WHILE(true) {
      RILL_IF(i * i >= n) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      i += 1;
    }
    RILL_ENDWHILE;
    out = i;
  });
  auto out = run<Int>(p, ns);
  EXPECT_TRUE(bits_equal(out,
                         map(ns,
                             [](int32_t n) {
                               int32_t i = 0;
                               while (i * i < n) ++i;
                               return i;
                             }),
                         describe_inputs(ns)));
}

// Vector state updated through write masks inside a loop (a Mandelbrot iteration).
TEST_P(ControlFlowTest, VectorLoopState) {
  std::vector<glm::vec2> cs;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      cs.emplace_back(-2.0f + 2.5f * x / 64.0f, -1.2f + 2.4f * y / 48.0f);
  Program p = program("mandelbrot", [] {
    Input<Float2> c("c");
    Output<Int> iters("iters");
    Output<Float2> last("last");
    Float2 z(0.0f, 0.0f);
    Int k = 0;
    RILL_WHILE(k < 64 && dot(z, z) <= 4.0f) {
      Float t = z.x() * z.x() - z.y() * z.y() + c.x();
      z.y() = 2.0f * z.x() * z.y() + c.y();
      z.x() = t;
      k += 1;
    }
    RILL_ENDWHILE;
    iters = k;
    last = z;
  });
  auto [iters, last] = run<Int, Float2>(p, cs);
  std::vector<int32_t> want_iters;
  std::vector<glm::vec2> want_last;
  for (glm::vec2 c : cs) {
    float zx = 0.0f, zy = 0.0f;
    int32_t k = 0;
    while (k < 64 && zx * zx + zy * zy <= 4.0f) {
      float t = zx * zx - zy * zy + c.x;
      zy = 2.0f * zx * zy + c.y;
      zx = t;
      k += 1;
    }
    want_iters.push_back(k);
    want_last.emplace_back(zx, zy);
  }
  Describe d = describe_inputs(cs);
  EXPECT_TRUE(bits_equal(iters, want_iters, d));
  EXPECT_TRUE(bits_equal(last, want_last, d));
}

// A binary search: gathers at data-dependent indices inside a data-dependent loop, with the
// array size as a uniform.
TEST_P(ControlFlowTest, BinarySearchGathers) {
  std::vector<float> table(1000);
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> d(-100.0f, 100.0f);
  for (float& t : table) t = d(rng);
  std::sort(table.begin(), table.end());
  Array<Float> sorted(table, "sorted");
  Uniform<Int> size(static_cast<int32_t>(table.size()), "size");
  std::vector<float> xs;
  for (int i = 0; i < 3000; ++i) xs.push_back(d(rng) * 1.1f);
  xs.push_back(table[0]);
  xs.push_back(table[500]);
  Program p = program("lower_bound", [&] {
    Input<Float> x("x");
    Output<Int> pos("pos");
    Output<Int> steps("steps");
    Int lo = 0;
    Int hi = size;
    Int k = 0;
    RILL_WHILE(lo < hi) {
      Int mid = (lo + hi) >> 1;
      RILL_IF(sorted[mid] < x) {
        lo = mid + 1;
      }
      RILL_ELSE {
        hi = mid;
      }
      RILL_ENDIF;
      k += 1;
    }
    RILL_ENDWHILE;
    pos = lo;
    steps = k;
  });
  auto [pos, steps] = run<Int, Int>(p, xs);
  std::vector<int32_t> want_pos, want_steps;
  for (float x : xs) {
    int32_t lo = 0, hi = static_cast<int32_t>(table.size()), k = 0;
    while (lo < hi) {
      int32_t mid = (lo + hi) >> 1;
      if (table[static_cast<size_t>(mid)] < x)
        lo = mid + 1;
      else
        hi = mid;
      ++k;
    }
    want_pos.push_back(lo);
    want_steps.push_back(k);
  }
  Describe dx = describe_inputs(xs);
  EXPECT_TRUE(bits_equal(pos, want_pos, dx));
  EXPECT_TRUE(bits_equal(steps, want_steps, dx));
}

// Long loops: an element that runs 70,000 loop iterations (1000 x 70, nested) gets the exact
// count, or, on Mesa's llvmpipe, which ends a shader's loops after 65,535 iterations in all
// (GLSL backends: DriverRules::loop_guard), an error naming the limit instead of a wrong
// count. 61,000 iterations (1000 x 60 and the outer loop's 1000) stay within the limit
// everywhere: the guard raises no false alarm.
TEST_P(ControlFlowTest, LoopsBeyondADriversIterationLimitAreExactOrAnError) {
  auto nested = [](int inner) {
    return program("nested_" + std::to_string(inner), [inner] {
      Input<Int> seed("seed");
      Output<Int> count("count");
      Int c = seed;
      RILL_FOR(Int i = 0, i < 1000, i += 1) {
        RILL_FOR(Int j = 0, j < inner, j += 1) {
          c += 1;
        }
        RILL_ENDFOR;
      }
      RILL_ENDFOR;
      count = c;
    });
  };
  const std::vector<int32_t> seeds{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16};
  const std::vector<int32_t> within = run<Int>(nested(60), seeds);
  for (size_t i = 0; i < seeds.size(); ++i) EXPECT_EQ(within[i], seeds[i] + 60000) << i;
  const bool llvmpipe =
      rill::backend(backend_name()).description().find("llvmpipe") != std::string::npos;
  if (!llvmpipe) {
    const std::vector<int32_t> beyond = run<Int>(nested(70), seeds);
    for (size_t i = 0; i < seeds.size(); ++i) EXPECT_EQ(beyond[i], seeds[i] + 70000) << i;
    return;
  }
  try {
    (void)run<Int>(nested(70), seeds);
    ADD_FAILURE() << "llvmpipe cut the loops short and no error was raised";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("kernel 'nested_70' ran longer loops than the driver"), std::string::npos)
        << what;
    EXPECT_NE(what.find("65535 loop iterations"), std::string::npos) << what;
  }
}

RILL_BACKEND_TEST_SUITE(ControlFlowTest);

}  // namespace
}  // namespace rill::testing
