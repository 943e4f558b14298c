// ControlFlow.h: what the RILL_* macros record, and (ControlFlowCpu) what they compute.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::LoopKind;
using ir::StmtKind;
using test::normalized;

// The last top-level statement of a kind.
const ir::Stmt& last(const ir::Function& f, StmtKind k) {
  for (auto it = f.body.rbegin(); it != f.body.rend(); ++it)
    if (it->kind == k) return *it;
  throw std::runtime_error("no such statement");
}

TEST(ControlFlow, IfElseIfElseNests) {
  Program p = program("ifs", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_IF(x < 0.0f) {
      y = -x;
    }
    RILL_ELSE_IF(x < 1.0f) {
      y = x * x;
    }
    RILL_ELSE_IF(x < 2.0f) {
      y = x + x;
    }
    RILL_ELSE {
      y = 1.0f;
    }
    RILL_ENDIF;
    y = y + 1.0f;
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(test::count_kind(f, StmtKind::If), 3);
  const ir::Stmt& outer = last(f, StmtKind::If);
  // The else branch computes the else-if's condition, then holds the chained if.
  ASSERT_GE(outer.else_body.size(), 2u) << p.print();
  EXPECT_EQ(outer.else_body[outer.else_body.size() - 2].op, ir::Op::Lt) << p.print();
  const ir::Stmt& second = outer.else_body.back();
  ASSERT_EQ(second.kind, StmtKind::If);
  const ir::Stmt& third = second.else_body.back();
  ASSERT_EQ(third.kind, StmtKind::If);
  EXPECT_FALSE(third.else_body.empty());
  EXPECT_EQ(outer.cond.type, ir::bool_type(1));
  // The statement after RILL_ENDIF is back at the top level.
  EXPECT_EQ(f.body.back().kind, StmtKind::Assign);
  EXPECT_EQ(test::problems(f), "");
}

TEST(ControlFlow, IfWithoutElseAndHostBoolConditions) {
  Program p = program("hostcond", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_IF(true) {
      y = x * 2.0f;
    }
    RILL_ENDIF;
    RILL_IF(x > 1.0f) {
      y = x * 3.0f;
    }
    RILL_ENDIF;
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(test::count_kind(f, StmtKind::If), 2);
  EXPECT_TRUE(f.body[1].cond.is_const());  // recorded as is; constant_fold removes it
  EXPECT_TRUE(f.body.back().else_body.empty());
  EXPECT_LACKS(p.print(), "else");
}

TEST(ControlFlow, WhileComputesItsConditionInTheConditionBlock) {
  Program p = program("while", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    Int i = 0;
    RILL_WHILE(i * 2 < n) {
      i += 1;
    }
    RILL_ENDWHILE;
    y = i;
  });
  const ir::Stmt& loop = last(p.ir(), StmtKind::Loop);
  EXPECT_EQ(loop.loop, LoopKind::While);
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Mul), 1);
  int cond_muls = 0;
  for (const auto& s : loop.cond_body) cond_muls += s.op == ir::Op::Mul;
  EXPECT_EQ(cond_muls, 1);
  EXPECT_EQ(loop.cond_body.back().op, ir::Op::Lt);
  EXPECT_EQ(loop.cond.var, loop.cond_body.back().dst);
  EXPECT_TRUE(loop.step.empty());
  std::string text = normalized(p.print());
  EXPECT_HAS(text, "  while {\n");
  EXPECT_LINE(text, "exit unless t#");
}

TEST(ControlFlow, DoUntilRunsTheBodyBeforeTheCondition) {
  Program p = program("do", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_DO {
      y = y * 0.5f;
    }
    RILL_UNTIL(y < 1.0f);
  });
  const ir::Stmt& loop = last(p.ir(), StmtKind::Loop);
  EXPECT_EQ(loop.loop, LoopKind::DoUntil);
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Mul), 1);
  ASSERT_FALSE(loop.cond_body.empty());
  EXPECT_EQ(loop.cond_body.back().op, ir::Op::Lt);
  std::string text = normalized(p.print());
  EXPECT_HAS(text, "  do {\n");
  EXPECT_LINE(text, "until:");
  EXPECT_LINE(text, "exit if t#");
}

TEST(ControlFlow, ForHasInitBeforeConditionStepAndBody) {
  Program p = program("for", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = 0.0f;
    RILL_FOR(Int i = 0, i < 4, i += 1) {
      y = y + x;
    }
    RILL_ENDFOR;
  });
  const ir::Function& f = p.ir();
  const ir::Stmt& loop = last(f, StmtKind::Loop);
  EXPECT_EQ(loop.loop, LoopKind::For);
  // init (i = 0) is emitted before the loop
  const ir::Stmt& init = f.body[f.body.size() - 2];
  EXPECT_EQ(init.kind, StmtKind::Assign);
  EXPECT_EQ(loop.cond_body.back().op, ir::Op::Lt);
  ASSERT_FALSE(loop.step.empty());
  EXPECT_EQ(loop.step.back().dst, init.dst);  // the step writes the counter
  int adds_in_body = 0;
  for (const auto& s : loop.body) adds_in_body += s.op == ir::Op::Add;
  EXPECT_EQ(adds_in_body, 1);
  std::string text = normalized(p.print());
  EXPECT_HAS(text, "  for {\n");
  EXPECT_LINE(text, "step:");
}

TEST(ControlFlow, BreakContinueAndDiscardAreRecordedWhereWritten) {
  Program p = program("jumps", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = 0.0f;
    RILL_IF(x < 0.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    RILL_FOR(Int i = 0, i < 10, i += 1) {
      RILL_IF(i == 2) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      RILL_WHILE(true) {
        RILL_BREAK;
      }
      RILL_ENDWHILE;
      RILL_IF(to_float(i) > x) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      y += 1.0f;
    }
    RILL_ENDFOR;
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(test::count_kind(f, StmtKind::Discard), 1);
  EXPECT_EQ(test::count_kind(f, StmtKind::Continue), 1);
  EXPECT_EQ(test::count_kind(f, StmtKind::Break), 2);
  EXPECT_EQ(ir::count_loops(f.body), 2);
  std::string text = p.print();
  EXPECT_LINE(text, "discard");
  EXPECT_LINE(text, "continue");
  EXPECT_LINE(text, "break");
  EXPECT_EQ(test::problems(f), "");
}

TEST(ControlFlow, DeepNestingClosesInOrder) {
  Program p = program("deep", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    y = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_WHILE(y < i) {
        RILL_DO {
          RILL_IF(y == 3) {
            y += 2;
          }
          RILL_ELSE {
            y += 1;
          }
          RILL_ENDIF;
        }
        RILL_UNTIL(y > 0);
      }
      RILL_ENDWHILE;
    }
    RILL_ENDFOR;
    y = y * 2;
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(ir::count_loops(f.body), 3);
  const ir::Stmt& outer = last(f, StmtKind::Loop);
  EXPECT_EQ(outer.loop, LoopKind::For);
  ASSERT_EQ(outer.body.size(), 1u);
  EXPECT_EQ(outer.body[0].loop, LoopKind::While);
  ASSERT_EQ(outer.body[0].body.size(), 1u);
  EXPECT_EQ(outer.body[0].body[0].loop, LoopKind::DoUntil);
  EXPECT_EQ(f.body.back().kind, StmtKind::Assign);
  EXPECT_EQ(test::problems(f), "");
}

// ---- on the CPU backend ----------------------------------------------------------------------

TEST(ControlFlowCpu, BranchesAndLoopsComputeWhatCppComputes) {
  Program p = program("mix", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    Int acc = 0;
    RILL_IF(n < 0) {
      acc = -n;
    }
    RILL_ELSE_IF(n < 10) {
      RILL_FOR(Int i = 0, i < n, i += 1) {
        RILL_IF(i == 3) {
          RILL_CONTINUE;
        }
        RILL_ENDIF;
        acc += i * i;
      }
      RILL_ENDFOR;
    }
    RILL_ELSE {
      Int m = n;
      RILL_WHILE(m > 1) {
        RILL_IF((m & 1) == 0) {
          m = m / 2;
        }
        RILL_ELSE {
          m = 3 * m + 1;
        }
        RILL_ENDIF;
        acc += 1;
        RILL_IF(acc > 50) {
          RILL_BREAK;
        }
        RILL_ENDIF;
      }
      RILL_ENDWHILE;
    }
    RILL_ENDIF;
    y = acc;
  });
  std::vector<int32_t> in;
  for (int32_t v = -5; v < 300; ++v) in.push_back(v);
  auto out = test::run_cpu<Int, Int>(p, {}, in);
  for (size_t k = 0; k < in.size(); ++k) {
    int32_t n = in[k], acc = 0;
    if (n < 0) {
      acc = -n;
    } else if (n < 10) {
      for (int32_t i = 0; i < n; ++i) {
        if (i == 3) continue;
        acc += i * i;
      }
    } else {
      int32_t m = n;
      while (m > 1) {
        m = (m & 1) == 0 ? m / 2 : 3 * m + 1;
        if (++acc > 50) break;
      }
    }
    ASSERT_EQ(out[k], acc) << "n = " << n;
  }
}

TEST(ControlFlowCpu, DoUntilRunsAtLeastOnce) {
  Program p = program("halve", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Int steps = 0;
    Float v = x;
    RILL_DO {
      v = v * 0.5f;
      steps += 1;
    }
    RILL_UNTIL(v < 1.0f);
    y = to_float(steps);
  });
  std::vector<float> in{0.0f, 0.5f, 1.0f, 2.0f, 3.0f, 1000.0f};
  auto out = test::run_cpu<Float, Float>(p, {}, in);
  for (size_t k = 0; k < in.size(); ++k) {
    int steps = 0;
    float v = in[k];
    do {
      v *= 0.5f;
      ++steps;
    } while (!(v < 1.0f));
    EXPECT_EQ(out[k], static_cast<float>(steps)) << in[k];
  }
}

TEST(ControlFlowCpu, DiscardedElementsKeepTheirValueAndAreNotCounted) {
  Program p = program("grow", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF(x >= 1.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    y = min(x * 2.0f, 1.0f);
  });
  Kernel k = compile(p);
  Stream<Float> s(std::vector<float>{0.1f, 0.3f, 0.5f, 0.9f, 1.0f, 7.0f});
  k.inputs(s).outputs(s);
  EXPECT_EQ(k.execute(), 4);
  auto after_one = s.download();
  EXPECT_EQ(after_one[0], 0.2f);
  EXPECT_EQ(after_one[3], 1.0f);
  EXPECT_EQ(after_one[5], 7.0f);
  s.upload(std::vector<float>{0.1f, 0.3f, 0.5f, 0.9f, 1.0f, 7.0f});
  EXPECT_EQ(k.loop(), 5);  // 0.1 -> 0.2 -> 0.4 -> 0.8 -> 1.0, then an empty pass
  for (float v : s.download()) EXPECT_GE(v, 1.0f);
}

}  // namespace
}  // namespace rill
