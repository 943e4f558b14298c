// passes::optimize and the passes together: every pass leaves valid IR on a corpus of
// programs, the pipeline reaches a fixed point, and (OptimizerCpu) every pass configuration
// computes the same bits on the CPU backend.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Op;

// Every corpus program reads (Float x, Int n) and writes Float y.
struct Named {
  const char* name;
  Program program;
};

std::vector<Named> corpus() {
  static Uniform<Float> gain(1.5f, "gain");
  static Uniform<Int3> mask(glm::ivec3(1, 2, 3), "mask");
  static Array<Float> table(std::vector<float>{0.5f, -1.0f, 2.0f, 8.0f, 1e-3f}, "table");
  static Array<Float3> grid(3, 2, "grid");
  static bool uploaded = [] {
    std::vector<glm::vec3> g;
    for (int k = 0; k < 6; ++k) g.emplace_back(k, k * 0.5f, -k);
    grid.upload(g);
    return true;
  }();
  (void)uploaded;
  const Float3 up(0.0f, 1.0f, 0.0f);

  std::vector<Named> out;
  out.push_back({"vectors", program("vectors", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   Float3 v(x, x * 0.5f, -x);
                   Float3 w = v.z() * up + v;
                   w(0, 2) = Float2(w.y(), v.x());
                   Float4 q(w, to_float(n));
                   Float3 c = cross(v, w + up);
                   Float3 r = reflect(v, normalize(w + 1.0f));
                   Float3 l = lerp(v, w, 0.25f);
                   Float3 k = clamp(c, -10.0f, 10.0f);
                   Bool3 neg = v < 0.0f;
                   Float3 s = select(neg, r, l) + select(any(neg), k, w);
                   y = dot(s, s) + q.w() * q.x() + length(c) + distance(v, w);
                 })});
  out.push_back({"control", program("control", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   y = x;
                   RILL_IF(n < -900) {
                     RILL_DISCARD;
                   }
                   RILL_ENDIF;
                   Int m = n & 31;
                   Float acc = 0.0f;
                   RILL_FOR(Int i = 0, i < m, i += 1) {
                     RILL_IF((i % 3) == 0) {
                       RILL_CONTINUE;
                     }
                     RILL_ENDIF;
                     acc = acc + to_float(i) * x;
                     RILL_IF(acc > 1000.0f) {
                       RILL_BREAK;
                     }
                     RILL_ENDIF;
                   }
                   RILL_ENDFOR;
                   Int j = 0;
                   RILL_DO {
                     j += 1;
                     RILL_IF(j == 2) {
                       RILL_CONTINUE;
                     }
                     RILL_ELSE_IF(j == 5) {
                       acc = acc * 0.5f;
                     }
                     RILL_ELSE {
                       acc = acc + 1.0f;
                     }
                     RILL_ENDIF;
                   }
                   RILL_UNTIL(j >= (n & 7));
                   RILL_WHILE(acc > 10.0f && acc < 1e30f) {
                     acc = acc * 0.25f;
                   }
                   RILL_ENDWHILE;
                   y = acc + to_float(j);
                 })});
  out.push_back({"integers", program("integers", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   Int a = n * 7 + (n >> 3) - (n << 5);
                   Int b = (a ^ 0x5bd1e995) | (n & 0xff);
                   Int c = b / (n % 5) + b % (n & 3) + abs(a) - sign(b) * min(a, b) + max(n, 3);
                   Int d = to_int(x * 1000.0f) + as_int(x) + ~c;
                   y = to_float(c) + to_float(d) + as_float(d & 0x3fffffff);
                 })});
  out.push_back({"transcendental", program("transcendental", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   Float t = to_float(n & 15) * 0.125f;
                   Float2 p2(x, t);
                   Float2 s2 = sin(p2) + cos(p2 * 2.0f);
                   y = exp(t) + log(abs(x) + 1.0f) + s2.x() * s2.y() + pow(t + 0.5f, 1.5f) +
                       atan2(x, t + 1.0f) + tan(t) + atan(x) + exp2(t) + log2(t + 2.0f);
                 })});
  out.push_back({"constants", program("constants", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   Float k = Float(0.1f) + 0.2f;
                   Float z = Float(0.0f);
                   Float nan = z / z;
                   Int big = Int(2147483647) + 1;
                   Int zero = 0;
                   Float c = sqrt(Float(2.0f)) * k - fract(Float(-1.25f)) + mod(Float(7.5f), 2.0f);
                   y = x * c + to_float(big / zero + n % zero) + select(x > 0.0f, x, nan) +
                       (x + z) + floor(Float(-0.5f)) * ceil(Float(-0.5f));
                 })});
  out.push_back({"gathers", program("gathers", [&] {
                   Input<Float> x("x");
                   Input<Int> n("n");
                   Output<Float> y("y");
                   Float t0 = table[n];
                   Float t1 = table[n + 1];
                   Float3 g = grid(n, n & 1);
                   Int3 mk = mask;
                   y = (t0 + t1 + table[n]) * gain + g.x() * to_float(mk.y()) +
                       to_float(element_index() % 3);
                 })});
  return out;
}

// All the passes, one at a time, as the optimizer may call them.
const std::vector<std::pair<const char*, std::function<void(ir::Function&)>>>& all_passes() {
  static const std::vector<std::pair<const char*, std::function<void(ir::Function&)>>> p = {
      {"lower_math", [](ir::Function& f) { passes::lower_math(f); }},
      {"constant_fold", [](ir::Function& f) { passes::constant_fold(f); }},
      {"constant_fold(double)",
       [](ir::Function& f) { passes::constant_fold(f, Accuracy::Double); }},
      {"copy_propagate", [](ir::Function& f) { passes::copy_propagate(f); }},
      {"eliminate_common_subexpressions",
       [](ir::Function& f) { passes::eliminate_common_subexpressions(f); }},
      {"eliminate_dead_code", [](ir::Function& f) { passes::eliminate_dead_code(f); }},
      {"lower_continue", [](ir::Function& f) { passes::lower_continue(f); }},
  };
  return p;
}

TEST(Optimizer, CorpusIsValid) {
  for (const auto& [name, p] : corpus()) EXPECT_EQ(test::problems(p.ir()), "") << name;
}

TEST(Optimizer, EveryPassAloneLeavesValidIr) {
  for (const auto& [name, p] : corpus())
    for (const auto& [pass, run] : all_passes()) {
      ir::Function f = p.ir();
      run(f);
      EXPECT_EQ(test::problems(f), "") << name << " after " << pass << ":\n" << ir::print(f);
    }
}

TEST(Optimizer, EveryPassAfterAnyOtherLeavesValidIr) {
  std::mt19937 rng(5);
  for (const auto& [name, p] : corpus()) {
    ir::Function f = p.ir();
    std::string trail;
    for (int step = 0; step < 30; ++step) {
      const auto& [pass, run] = all_passes()[rng() % all_passes().size()];
      trail += std::string(" ") + pass;
      run(f);
      ASSERT_EQ(test::problems(f), "") << name << " after" << trail << ":\n" << ir::print(f);
    }
  }
}

TEST(Optimizer, OptimizeShrinksAndIsIdempotent) {
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast, Accuracy::Double})
    for (const auto& [name, p] : corpus()) {
      SCOPED_TRACE(std::string(name) + " " + accuracy_name(a));
      ir::Function o = passes::optimize(p.ir(), PassOptions{}, a);
      EXPECT_EQ(test::problems(o), "");
      if (a != Accuracy::Strict) {  // lower_math makes strict programs bigger
        // Never bigger than the program with only the (mandatory) continue lowering.
        ir::Function lowered = p.ir();
        passes::lower_continue(lowered);
        EXPECT_LE(test::statements(o), test::statements(lowered));
      }
      // Optimizing again finds nothing left to do but the dead stores lower_continue may
      // leave (a `skip` flag set by a continue that ends the body, never read).
      ir::Function again = passes::optimize(o, PassOptions{}, a);
      ir::Function swept = o;
      passes::eliminate_dead_code(swept);
      EXPECT_EQ(ir::print(again), ir::print(swept));
      EXPECT_EQ(test::count_kind(o, ir::StmtKind::Continue), 0) << "only while loops keep them";
    }
}

TEST(Optimizer, StrictModeLowersTranscendentalsFastModeKeepsThem) {
  Program p = corpus()[3].program;
  const std::vector<Op> transcendental = {Op::Exp, Op::Exp2, Op::Log, Op::Log2, Op::Pow,
                                          Op::Sin, Op::Cos,  Op::Tan, Op::Atan, Op::Atan2};
  ir::Function strict = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  ir::Function fast = passes::optimize(p.ir(), PassOptions{}, Accuracy::Fast);
  for (Op op : transcendental) {
    EXPECT_EQ(test::count_ops(strict, op), 0) << ir::op_name(op);
    EXPECT_GE(test::count_ops(fast, op), 1) << ir::op_name(op);
  }
  ir::Function lowered = p.ir();
  EXPECT_TRUE(passes::lower_math(lowered));
  EXPECT_EQ(test::problems(lowered), "");
  EXPECT_FALSE(passes::lower_math(lowered));
}

TEST(Optimizer, WithEveryPassOffOnlyTheMandatoryLoweringsRun) {
  PassOptions none{false, false, false, false};
  for (const auto& [name, p] : corpus()) {
    SCOPED_TRACE(name);
    ir::Function o = passes::optimize(p.ir(), none, Accuracy::Fast);
    ir::Function expected = p.ir();
    passes::lower_continue(expected);
    passes::canonicalize(expected);  // the listing's own order, which optimize() always gives
    EXPECT_EQ(ir::print(o), ir::print(expected));
  }
}

TEST(Optimizer, EachPassCanBeSwitchedOff) {
  // Work for every pass: a constant expression, a copy, a repeated product (visible only
  // once the copy is propagated) and an unused value.
  Program p = program("each", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float a = Float(0.5f) * 4.0f;
    Float b = x;
    Float unused = x * x;
    y = b * a + x * a;
  });
  for (const auto& cfg : test::pass_configs(Accuracy::Fast)) {
    SCOPED_TRACE(cfg.name);
    ir::Function o = passes::optimize(p.ir(), cfg.options.passes, Accuracy::Fast);
    EXPECT_EQ(test::problems(o), "");
    ir::Function all = passes::optimize(p.ir(), PassOptions{}, Accuracy::Fast);
    if (cfg.options.passes == PassOptions{}) {
      EXPECT_EQ(ir::print(o), ir::print(all));
    } else {
      EXPECT_GT(test::statements(o), test::statements(all)) << ir::print(o);
    }
  }
}

// ---- on the CPU backend ----------------------------------------------------------------------

TEST(OptimizerCpu, KernelIrIsTheOptimizedFunction) {
  Program p = corpus()[1].program;
  CompileOptions o;
  o.passes.common_subexpressions = false;
  Kernel k = compile(p, "cpu", o);
  EXPECT_EQ(k.ir(), ir::print(passes::optimize(p.ir(), o.passes, o.accuracy)));
}

TEST(OptimizerCpu, EveryPassConfigurationComputesTheSameBits) {
  auto xs = test::random_floats(4000, 1234);
  auto ns = test::random_ints(4000, 4321);
  for (const auto& [name, p] : corpus()) {
    SCOPED_TRACE(name);
    test::expect_passes_preserve_results<Float, Float, Int>(p, xs, ns);
  }
}

// In Accuracy::Double float arithmetic happens in binary64 whatever the passes did: copy
// propagation may turn `a + b` on two variables into an op on two constants, which must not
// then be computed in binary32.
TEST(OptimizerCpu, DoubleModePassConfigurationsAgree) {
  Program p = program("double_mode", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Float big = 1e8f;
    Float one = 1.0f;
    Float third = 1.0f / 3.0f;
    Float r = (big + one) - big;  // 1 in binary64, 0 in binary32
    y = x * r + third * 3.0f + to_float(n) * 1e-8f;
  });
  auto xs = test::random_floats(1000, 77);
  auto ns = test::random_ints(1000, 78);
  test::expect_configs_agree<Float, Float, Int>(test::pass_configs(Accuracy::Double), p, xs, ns);
  CompileOptions none;
  none.accuracy = Accuracy::Double;
  none.passes = PassOptions{false, false, false, false};
  EXPECT_EQ((test::run_cpu<Float, Float, Int>(p, none, {2.0f}, {0})[0]), 3.0f);
}

}  // namespace
}  // namespace rill
