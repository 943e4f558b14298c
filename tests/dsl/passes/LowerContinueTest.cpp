// passes::lower_continue: `continue` in for and do-until loops becomes a guard flag, so a
// continue still runs a for loop's step and a do-until loop's condition.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::LoopKind;
using ir::Op;
using ir::StmtKind;
using test::count_kind;

ir::Function lowered(const Program& p, bool expect_change = true) {
  return test::after(p,
                     [&](ir::Function& f) { EXPECT_EQ(passes::lower_continue(f), expect_change); });
}

const ir::Stmt& only_loop(const ir::Function& f) {
  for (const auto& s : f.body)
    if (s.kind == StmtKind::Loop) return s;
  throw std::runtime_error("no loop");
}

TEST(LowerContinue, ForLoopContinueBecomesAGuard) {
  Program p = program("for", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF((i & 1) == 1) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += i;
      y += 1;
    }
    RILL_ENDFOR;
  });
  ir::Function f = lowered(p);
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 0) << ir::print(f);
  const ir::Stmt& loop = only_loop(f);
  EXPECT_EQ(loop.loop, LoopKind::For);
  // skip = false; ...; if (...) { skip = true }; go = not(skip); if go { rest }
  ASSERT_GE(loop.body.size(), 4u) << ir::print(f);
  const ir::Stmt& reset = loop.body.front();
  EXPECT_EQ(reset.op, Op::Copy);
  EXPECT_EQ(f.var(reset.dst).name, "skip");
  EXPECT_EQ(reset.args[0].value, ir::Constant::of_bool(false));
  const ir::Stmt& guard = loop.body.back();
  ASSERT_EQ(guard.kind, StmtKind::If);
  EXPECT_EQ(test::count_ops(p.ir(), Op::Add) - 1, [&] {  // the step's add stays in the step
    int n = 0;
    ir::for_each_stmt(guard.then_body, [&](const ir::Stmt& s) { n += s.op == Op::Add; });
    return n;
  }()) << ir::print(f);
  EXPECT_FALSE(loop.step.empty());
  std::string text = ir::print(f);
  EXPECT_EQ(test::count_matching(text, R"(skip_\d+ = copy\(true\))"), 1) << text;
  EXPECT_EQ(test::count_matching(text, R"(var bool skip_\d+)"), 1) << text;
}

TEST(LowerContinue, DoUntilContinueBecomesAGuard) {
  Program p = program("do", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    Int i = 0;
    RILL_DO {
      i += 1;
      RILL_IF(i == 2) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += i;
    }
    RILL_UNTIL(i >= n);
  });
  ir::Function f = lowered(p);
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 0);
  EXPECT_FALSE(only_loop(f).cond_body.empty());
}

TEST(LowerContinue, WhileLoopsKeepTheirContinue) {
  Program p = program("while", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_WHILE(y < n) {
      y += 1;
      RILL_IF(y == 3) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += 1;
    }
    RILL_ENDWHILE;
  });
  ir::Function f = lowered(p, false);
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 1);
  EXPECT_EQ(ir::print(f), p.print());
}

TEST(LowerContinue, OnlyTheLoopTheContinueBelongsTo) {
  Program p = program("nested", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      Int j = 0;
      RILL_WHILE(j < i) {
        j += 1;
        RILL_IF(j == 2) {
          RILL_CONTINUE;
        }  // the while's
        RILL_ENDIF;
        y += j;
      }
      RILL_ENDWHILE;
    }
    RILL_ENDFOR;
  });
  ir::Function f = lowered(p, false);  // the for has no continue of its own
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 1);
}

TEST(LowerContinue, ContinueDeepInsideIfs) {
  Program p = program("deep", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF(i > 2) {
        y += 100;
        RILL_IF(i == 4) {
          RILL_CONTINUE;
        }
        RILL_ELSE_IF(i == 6) {
          RILL_CONTINUE;
        }
        RILL_ENDIF;
        y += 10;
      }
      RILL_ELSE {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += 1;
    }
    RILL_ENDFOR;
  });
  ir::Function f = lowered(p);
  EXPECT_EQ(count_kind(f, StmtKind::Continue), 0) << ir::print(f);
  EXPECT_EQ(test::count_matching(ir::print(f), R"(skip_\d+ = copy\(true\))"), 3) << ir::print(f);
}

TEST(LowerContinue, NoContinueNoChange) {
  Program p = program("plain", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      y += i;
    }
    RILL_ENDFOR;
  });
  ir::Function f = lowered(p, false);
  EXPECT_EQ(ir::print(f), p.print());
}

// ---- on the CPU backend, against C++ loops ---------------------------------------------------

int32_t for_reference(int32_t n) {
  int32_t y = 0;
  for (int32_t i = 0; i < n; ++i) {
    if (i > 2) {
      y += 100;
      if (i == 4) continue;
      if (i == 6) continue;
      y += 10;
    } else {
      continue;
    }
    y += 1;
  }
  return y;
}

TEST(LowerContinueCpu, ContinueInAForStillRunsTheStep) {
  Program p = program("for_continue", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF(i > 2) {
        y += 100;
        RILL_IF(i == 4) {
          RILL_CONTINUE;
        }
        RILL_ELSE_IF(i == 6) {
          RILL_CONTINUE;
        }
        RILL_ENDIF;
        y += 10;
      }
      RILL_ELSE {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += 1;
    }
    RILL_ENDFOR;
  });
  std::vector<int32_t> ns;
  for (int32_t v = -2; v < 40; ++v) ns.push_back(v);
  for (const auto& cfg : test::pass_configs()) {
    SCOPED_TRACE(cfg.name);
    auto out = test::run_cpu<Int, Int>(p, cfg.options, ns);
    for (size_t k = 0; k < ns.size(); ++k) ASSERT_EQ(out[k], for_reference(ns[k])) << ns[k];
  }
}

TEST(LowerContinueCpu, ContinueInADoUntilStillEvaluatesTheCondition) {
  // If the continue skipped the condition, i == 2 would loop forever or overshoot n.
  Program p = program("do_continue", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    Int i = 0;
    RILL_DO {
      i += 1;
      RILL_IF((i & 1) == 0) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      y += i * 10;
    }
    RILL_UNTIL(i >= n);
    y += i * 1000;
  });
  std::vector<int32_t> ns;
  for (int32_t v = -3; v < 40; ++v) ns.push_back(v);
  auto reference = [](int32_t n) {
    int32_t y = 0, i = 0;
    do {
      i += 1;
      if ((i & 1) == 0) continue;
      y += i * 10;
    } while (!(i >= n));
    return y + i * 1000;
  };
  for (const auto& cfg : test::pass_configs()) {
    SCOPED_TRACE(cfg.name);
    auto out = test::run_cpu<Int, Int>(p, cfg.options, ns);
    for (size_t k = 0; k < ns.size(); ++k) ASSERT_EQ(out[k], reference(ns[k])) << ns[k];
  }
}

TEST(LowerContinueCpu, NestedLoopsWithContinueAndBreak) {
  Program p = program("nested_continue", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF(i == 5) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      Int j = 0;
      RILL_DO {
        j += 1;
        RILL_IF(j == i) {
          RILL_CONTINUE;
        }
        RILL_ENDIF;
        RILL_IF(j > 6) {
          RILL_BREAK;
        }
        RILL_ENDIF;
        y += j;
      }
      RILL_UNTIL(j >= i);
      Int k = 0;
      RILL_WHILE(k < i) {
        k += 1;
        RILL_IF((k % 3) == 0) {
          RILL_CONTINUE;
        }
        RILL_ENDIF;
        y += 1000;
      }
      RILL_ENDWHILE;
      RILL_IF(y > 200000) {
        RILL_BREAK;
      }
      RILL_ENDIF;
    }
    RILL_ENDFOR;
  });
  auto reference = [](int32_t n) {
    int32_t y = 0;
    for (int32_t i = 0; i < n; ++i) {
      if (i == 5) continue;
      int32_t j = 0;
      do {
        j += 1;
        if (j == i) continue;
        if (j > 6) break;
        y += j;
      } while (!(j >= i));
      int32_t k = 0;
      while (k < i) {
        k += 1;
        if (k % 3 == 0) continue;
        y += 1000;
      }
      if (y > 200000) break;
    }
    return y;
  };
  std::vector<int32_t> ns;
  for (int32_t v = -1; v < 60; ++v) ns.push_back(v);
  auto out = test::run_cpu<Int, Int>(p, {}, ns);
  for (size_t k = 0; k < ns.size(); ++k) ASSERT_EQ(out[k], reference(ns[k])) << ns[k];
}

}  // namespace
}  // namespace rill
