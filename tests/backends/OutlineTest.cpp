// Outlining in the cpu backend's C (backends/cpu/Outline.h): a kernel whose branches and loop
// bodies are large is printed as several functions, spread over translation units compiled
// at the same time, and computes the same bits as the kernel printed as one function. The
// kernel below exercises every part of an outlined function's interface: values read only
// (by value), values written that live on (by pointer), a value carried around a loop,
// values of its own (locals), a gather, the element index, and jumps that leave the outlined
// block (a break out of the loop around it, a discard).
#include <algorithm>
#include <cmath>

#include "BackendTest.h"
#include "cpu/CEmitter.h"
#include "cpu/Outline.h"
#include "rill/passes/Passes.h"

namespace rill::testing {
namespace {

// Outlining is the cpu backend's C layout, so the suite runs there only (not skipped on the
// others: a skip would count five cases that test nothing).
class OutlineTest : public BackendTest {};

// Arithmetic of `steps` dependent statements, so that the block holding it is large.
Float chain(Float v, Float w, int steps) {
  for (int s = 0; s < steps; ++s) {
    v = v * 0.75f + w;
    w = w * 0.5f - v * 0.125f;
  }
  return v + w;
}

Program probe(const Array<Float>& table) {
  return program("outline_probe", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Int> n("n");
    Float acc = 0.0f;
    Float carried = 1.0f;  // read before written in the loop body: kept across iterations
    Int i = 0;
    Float fi = 0.0f;
    RILL_WHILE(i < 6) {
      RILL_IF(x > fi - 3.0f) {
        Float t = chain(x + acc, carried, 40);  // a local of the outlined block
        carried = carried * 0.5f + t * 0.25f;
        acc = acc + t + table[element_index() % 7];
        RILL_IF(acc > 1.0e4f) {
          RILL_BREAK;
        }
        RILL_ENDIF;
      }
      RILL_ELSE {
        Float u = chain(x - acc, Float(2.0f), 40);
        acc = acc - u * 0.5f;
        RILL_IF(x < -900.0f) {
          RILL_DISCARD;
        }
        RILL_ENDIF;
      }
      RILL_ENDIF;
      i += 1;
      fi += 1.0f;
    }
    RILL_ENDWHILE;
    y = acc + carried;
    n = i;
  });
}

std::vector<float> inputs() {
  std::vector<float> xs = sweep_floats(1, 4096);
  for (float& v : xs)
    if (!std::isfinite(v)) v = 0.0f;
  xs.push_back(-1000.0f);  // discarded (as every input below -900)
  xs.push_back(5000.0f);   // breaks out of the loop
  return xs;
}

TEST_P(OutlineTest, SplitKernelComputesTheSameBits) {
  const Array<Float> table(std::vector<float>{0.5f, -1.0f, 2.0f, 0.25f, 3.0f, -0.75f, 1.5f},
                           "table");
  const Program p = probe(table);
  const std::vector<float> xs = inputs();
  std::vector<float> whole_y, split_y;
  std::vector<int32_t> whole_n, split_n;
  std::string whole_source, split_source;
  int64_t whole_written = 0;
  {
    ScopedEnv env("RILL_CPU_OUTLINE", "off");
    clear_kernel_cache();
    Kernel k = compile(p);
    whole_source = k.source();
    std::tie(whole_y, whole_n) = run_kernel<Float, Int>(k, static_cast<int64_t>(xs.size()), xs);
    whole_written = last_written_;
  }
  {
    // Small enough that each side of the branch becomes a function, in several units.
    ScopedEnv env("RILL_CPU_OUTLINE", "50:100");
    clear_kernel_cache();
    Kernel k = compile(p);
    split_source = k.source();
    std::tie(split_y, split_n) = run_kernel<Float, Int>(k, static_cast<int64_t>(xs.size()), xs);
    EXPECT_EQ(last_written_, whole_written);
    clear_kernel_cache();
    // Deterministic: the kernel caches hash the source.
    EXPECT_EQ(compile(p).source(), split_source);
  }
  clear_kernel_cache();
  EXPECT_EQ(whole_source.find("rill_part"), std::string::npos);
  EXPECT_EQ(cpu::c_units(whole_source), 1);
  // Both sides of the if (and the loop body around them, once they are calls, is small).
  size_t parts = 0;
  for (size_t at = 0;
       (at = split_source.find("\nRILL_PART int rill_part", at)) != std::string::npos; ++at)
    ++parts;
  EXPECT_GE(parts, 4u) << "prototypes and definitions of two parts at least";
  EXPECT_EQ(cpu::c_units(split_source), 4);  // the most: one unit per cost of 100
  // Every element below -900 takes the else side and discards.
  const auto kept = std::count_if(xs.begin(), xs.end(), [](float v) { return v >= -900.0f; });
  EXPECT_LT(kept, static_cast<int64_t>(xs.size()));
  EXPECT_EQ(whole_written, kept);
  EXPECT_TRUE(bits_equal(split_y, whole_y));
  EXPECT_TRUE(bits_equal(split_n, whole_n));
  // The break happened: the loop stopped before its 6 iterations for the large input.
  EXPECT_LT(*std::min_element(whole_n.begin(), whole_n.end()), 6);
}

// The plan's interface on the kernel's optimized IR: every scalar an outlined block touches
// is in exactly one of its lists, and a part is at least the threshold's cost.
TEST_P(OutlineTest, PlanListsEachScalarOnce) {
  const Array<Float> table(std::vector<float>{1.0f}, "table");
  const Program p = probe(table);
  // The optimized IR, as the emitter sees it.
  const ir::Function f = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  const cpu::OutlinePlan plan = cpu::plan_outlining(f, 50);
  ASSERT_GE(plan.parts.size(), 2u);
  for (const cpu::OutlinedPart& part : plan.parts) {
    EXPECT_GE(part.cost, 50u);
    std::vector<cpu::ScalarRef> all = part.by_value;
    all.insert(all.end(), part.by_pointer.begin(), part.by_pointer.end());
    all.insert(all.end(), part.locals.begin(), part.locals.end());
    std::sort(all.begin(), all.end());
    for (size_t i = 1; i < all.size(); ++i)
      EXPECT_TRUE(all[i - 1] < all[i]) << "a scalar in two lists of part " << part.id;
  }
  // The same plan twice: the emitted source does not depend on anything but the IR.
  const cpu::OutlinePlan again = cpu::plan_outlining(f, 50);
  ASSERT_EQ(again.parts.size(), plan.parts.size());
  for (size_t i = 0; i < plan.parts.size(); ++i) EXPECT_EQ(again.parts[i].cost, plan.parts[i].cost);
}

// A kernel whose loop body has a branch with a loop of its own on one side and
// straight-line code on the other: the side with the loop (and the inner loop's body) are
// parts that run loops, the other side is loop-free, and so compiled at -O1 in a unit of
// its own (CEmitter.h's kColdUnitsMark).
Program probe_loops() {
  return program("outline_probe_loops", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float acc = 0.0f;
    Int i = 0;
    RILL_WHILE(i < 3) {
      RILL_IF(x > 0.0f) {
        Int j = 0;
        RILL_WHILE(j < 4) {
          acc = chain(x + acc, acc * 0.25f, 40);
          j = j + 1;
        }
        RILL_ENDWHILE;
        acc = chain(acc, x, 40);  // enough beside the loop for this side to be a part too
      }
      RILL_ELSE {
        acc = acc - chain(x - acc, Float(2.0f), 40) * 0.5f;
      }
      RILL_ENDIF;
      i = i + 1;
    }
    RILL_ENDWHILE;
    y = acc;
  });
}

TEST_P(OutlineTest, LoopFreePartsAreColdAndComputeTheSameBits) {
  const Program p = probe_loops();
  const ir::Function f = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  const cpu::OutlinePlan plan = cpu::plan_outlining(f, 50);
  size_t loop_parts = 0, loop_free = 0;
  for (const cpu::OutlinedPart& part : plan.parts) ++(part.loops ? loop_parts : loop_free);
  EXPECT_GE(loop_parts, 2u) << "the inner loop's body and the side that runs it";
  EXPECT_EQ(loop_free, 1u) << "the straight-line side";
  // Without cold units in the layout, every unit is -O2.
  cpu::CLayout layout{.outline_min_cost = 50, .max_units = 4, .unit_cost = 100};
  EXPECT_EQ(cpu::c_cold_units(cpu::emit_c(f, Accuracy::Strict, layout)), 0);
  layout.cold_units = true;
  const std::string cold_source = cpu::emit_c(f, Accuracy::Strict, layout);
  const int units = cpu::c_units(cold_source), cold = cpu::c_cold_units(cold_source);
  EXPECT_GE(units, 2);
  EXPECT_GE(cold, 1);
  EXPECT_LT(cold, units) << "unit 0 holds the entry function, at -O2";

  // The backend's kernel, its loop-free part compiled at -O1, against the kernel printed as
  // one function at -O2: the same bits.
  std::vector<float> xs = sweep_floats(1, 2048);
  for (float& v : xs)
    if (!std::isfinite(v)) v = 0.0f;
  std::vector<float> whole_y, split_y;
  {
    ScopedEnv env("RILL_CPU_OUTLINE", "off");
    clear_kernel_cache();
    Kernel k = compile(p);
    whole_y = run_kernel<Float>(k, static_cast<int64_t>(xs.size()), xs);
  }
  {
    ScopedEnv env("RILL_CPU_OUTLINE", "50:100");
    clear_kernel_cache();
    Kernel k = compile(p);
    EXPECT_GE(cpu::c_cold_units(k.source()), 1);
    split_y = run_kernel<Float>(k, static_cast<int64_t>(xs.size()), xs);
  }
  clear_kernel_cache();
  EXPECT_TRUE(bits_equal(split_y, whole_y));
}

INSTANTIATE_TEST_SUITE_P(Backends, OutlineTest, ::testing::Values(std::string("cpu")),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return param_name(info.param);
                         });

}  // namespace
}  // namespace rill::testing
