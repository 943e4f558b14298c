// passes::lower_lockstep: control flow becomes lane masks, so that a group of lanes can run a
// kernel together (the simd backend's lowering).
//
// Each kernel here is checked three ways against the reference interpreter on the kernel as
// optimize() leaves it:
// - the lowered kernel read as a scalar kernel (one lane: "some lane has it" is "it"), with
//   `if (!alive) discard` appended, computes the same outputs and count;
// - the lowered kernel run by LockstepMachine below, which executes it as lockstep hardware
//   does: groups of W elements, every lane executing every statement the group reaches, an if
//   or loop taken when any lane has its condition, computes the same outputs and count;
// - the lowered kernel has the shape its printer relies on: no continue or discard, only
//   while loops, and breaks only as a loop's "no lane left" exit.
#include <algorithm>
#include <random>

#include "TestUtil.h"
#include "rill/Reference.h"

namespace rill {
namespace {

using ir::Constant;
using ir::Function;
using ir::Op;
using ir::Stmt;
using ir::StmtKind;

// The words a kernel reads and writes, and how many elements it runs over.
struct Data {
  int64_t count = 0, width = 0;
  std::vector<std::vector<uint32_t>> in, out;  // one vector per stream
};

ir::InterpreterLaunch launch_of(const Program& p, const Data& d, Data& result) {
  ir::InterpreterLaunch l = reference_launch(p);
  result = d;
  for (const auto& v : d.in) l.inputs.push_back(v.data());
  for (auto& v : result.out) l.outputs.push_back(v.data());
  l.count = d.count;
  l.width = d.width;
  return l;
}

// Runs a lowered kernel over groups of W consecutive elements in lockstep. A group shorter
// than W repeats its last element in the spare lanes, which store nothing (as the simd
// backend does).
class LockstepMachine {
 public:
  LockstepMachine(const passes::LockstepFunction& k, const ir::InterpreterLaunch& l, int lanes)
      : f_(k.f), alive_(k.alive), l_(l), w_(lanes) {}

  int64_t run() {
    int64_t written = 0;
    for (int64_t g = 0; g < l_.count; g += w_) {
      const int n = static_cast<int>(std::min<int64_t>(w_, l_.count - g));
      element_.assign(static_cast<size_t>(w_), 0);
      for (int lane = 0; lane < w_; ++lane)
        element_[static_cast<size_t>(lane)] = g + std::min(lane, n - 1);
      start_group();
      EXPECT_FALSE(block(f_.body)) << "a break outside a loop";
      for (int lane = 0; lane < n; ++lane) {
        if (alive_ != ir::kNoVar && !value(alive_, lane).b(0)) continue;
        const int64_t e = element_[static_cast<size_t>(lane)];
        for (size_t o = 0; o < f_.outputs.size(); ++o) {
          const Constant& c = value(f_.outputs[o], lane);
          for (int k = 0; k < c.type.width; ++k)
            l_.outputs[o][e * c.type.width + k] = c.bits[static_cast<size_t>(k)];
        }
        ++written;
      }
    }
    return written;
  }

 private:
  Constant& value(ir::VarId v, int lane) { return vals_[v][static_cast<size_t>(lane)]; }

  void start_group() {
    vals_.assign(f_.vars.size(), std::vector<Constant>(static_cast<size_t>(w_)));
    for (ir::VarId v = 0; v < f_.vars.size(); ++v) {
      const ir::Variable& var = f_.vars[v];
      const int w = var.type.width;
      for (int lane = 0; lane < w_; ++lane) {
        const int64_t e = element_[static_cast<size_t>(lane)];
        Constant& c = value(v, lane);
        c.type = var.type;
        for (int k = 0; k < w; ++k) {
          const size_t s = static_cast<size_t>(var.slot);
          uint32_t bits = 0;
          if (var.role == ir::VarRole::Input) bits = l_.inputs[s][e * w + k];
          if (var.role == ir::VarRole::Output) bits = l_.outputs[s][e * w + k];
          if (var.role == ir::VarRole::Uniform) bits = l_.uniforms[s][static_cast<size_t>(k)];
          c.bits[static_cast<size_t>(k)] = bits;
        }
      }
    }
  }

  Constant read(const ir::Operand& o, int lane) {
    if (o.is_const()) return o.value;
    Constant c;
    c.type = o.type;
    for (int k = 0; k < o.width(); ++k)
      c.bits[static_cast<size_t>(k)] = value(o.var, lane).bits[o.swizzle[static_cast<size_t>(k)]];
    return c;
  }

  bool any(const ir::Operand& cond) {
    for (int lane = 0; lane < w_; ++lane)
      if (read(cond, lane).b(0)) return true;
    return false;
  }

  // True when a break left the block.
  bool block(const ir::Block& b) {
    for (const Stmt& s : b) {
      switch (s.kind) {
        case StmtKind::Assign:
          for (int lane = 0; lane < w_; ++lane) assign(s, lane);
          break;
        case StmtKind::If:
          if (block(any(s.cond) ? s.then_body : s.else_body)) return true;
          break;
        case StmtKind::Loop:
          EXPECT_EQ(s.loop, ir::LoopKind::While);
          for (;;) {
            EXPECT_FALSE(block(s.cond_body));
            if (!any(s.cond) || block(s.body)) break;
            EXPECT_FALSE(block(s.step));
          }
          break;
        case StmtKind::Break:
          return true;
        case StmtKind::Continue:
        case StmtKind::Discard:
          ADD_FAILURE() << "a lowered kernel has a continue or discard";
          return false;
      }
    }
    return false;
  }

  static int64_t clamp(int32_t i, int64_t n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); }

  void assign(const Stmt& s, int lane) {
    Constant& dst = value(s.dst, lane);
    const int width = s.mask.full() ? dst.type.width : s.mask.count;
    Constant r;
    r.type = dst.type.with_width(width);
    if (s.op == Op::Gather) {
      const ir::InterpreterArray& a = l_.arrays.at(static_cast<size_t>(s.array));
      int64_t idx = clamp(read(s.args[0], lane).i(0), a.shape[0]);
      if (s.args.size() > 1) idx += a.shape[0] * clamp(read(s.args[1], lane).i(0), a.shape[1]);
      const int ew = f_.arrays[static_cast<size_t>(s.array)].elem.width;
      for (int k = 0; k < width; ++k) r.bits[static_cast<size_t>(k)] = a.data[idx * ew + k];
    } else if (s.op == Op::ElementIndex) {
      r.bits[0] = static_cast<uint32_t>(element_[static_cast<size_t>(lane)]);
    } else {
      std::vector<Constant> args;
      for (const ir::Operand& a : s.args) args.push_back(read(a, lane));
      auto folded = passes::fold(s.op, r.type, args);
      ASSERT_TRUE(folded) << "cannot evaluate " << ir::op_name(s.op);
      r = *folded;
    }
    for (int k = 0; k < width; ++k)
      dst.bits[static_cast<size_t>(s.mask.full() ? k : s.mask.comps[static_cast<size_t>(k)])] =
          r.bits[static_cast<size_t>(k)];
  }

  const Function& f_;
  ir::VarId alive_;
  const ir::InterpreterLaunch& l_;
  int w_;
  std::vector<int64_t> element_;
  std::vector<std::vector<Constant>> vals_;
};

// The lowered kernel's shape (see the file comment).
void expect_lockstep_shape(const Function& f) {
  EXPECT_EQ(test::count_kind(f, StmtKind::Continue), 0) << ir::print(f);
  EXPECT_EQ(test::count_kind(f, StmtKind::Discard), 0) << ir::print(f);
  ir::for_each_stmt(f.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::Loop) {
      EXPECT_EQ(s.loop, ir::LoopKind::While) << ir::print(f);
    }
    if (s.kind == StmtKind::If && !s.else_body.empty() && s.else_body[0].kind == StmtKind::Break) {
      EXPECT_TRUE(s.then_body.empty());
      EXPECT_EQ(s.else_body.size(), 1u);
    }
  });
  int breaks = 0, exits = 0;
  ir::for_each_stmt(f.body, [&](const Stmt& s) {
    breaks += s.kind == StmtKind::Break;
    exits += s.kind == StmtKind::If && s.then_body.empty() && s.else_body.size() == 1 &&
             s.else_body[0].kind == StmtKind::Break;
  });
  EXPECT_EQ(breaks, exits) << "a break that is not a loop's exit\n" << ir::print(f);
}

// Lowers p and checks it against the reference interpreter the three ways above.
void check(const Program& p, const Data& d) {
  SCOPED_TRACE(p.name());
  const Function ref = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  const passes::LockstepFunction lowered = passes::lower_lockstep(ref);
  expect_lockstep_shape(lowered.f);
  EXPECT_TRUE(ir::verify(lowered.f).empty()) << test::problems(lowered.f);

  Data want, scalar, lanes8, lanes4;
  const int64_t want_count = ir::interpret(ref, launch_of(p, d, want));

  Function as_scalar = lowered.f;
  if (lowered.alive != ir::kNoVar) {
    Stmt drop = Stmt::make_if(ir::Operand::of_var(lowered.alive, ir::bool_type(1)));
    drop.else_body.push_back(Stmt::make(StmtKind::Discard));
    as_scalar.body.push_back(std::move(drop));
  }
  EXPECT_EQ(ir::interpret(as_scalar, launch_of(p, d, scalar)), want_count);
  EXPECT_EQ(scalar.out, want.out) << "the lowered kernel read as a scalar kernel";

  for (auto [w, got] : {std::pair{8, &lanes8}, std::pair{4, &lanes4}}) {
    ir::InterpreterLaunch l = launch_of(p, d, *got);
    EXPECT_EQ(LockstepMachine(lowered, l, w).run(), want_count) << w << " lanes";
    EXPECT_EQ(got->out, want.out) << w << " lanes";
  }
}

// Small ints (loop counts stay short), different in every stream.
std::vector<uint32_t> small_ints(int64_t n, uint32_t seed, int lo, int hi) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int32_t> pick(lo, hi);
  std::vector<uint32_t> v(static_cast<size_t>(n));
  for (auto& x : v) x = static_cast<uint32_t>(pick(rng));
  return v;
}

Data ints(std::initializer_list<int> widths_in, std::initializer_list<int> widths_out, int64_t n,
          uint32_t seed) {
  Data d;
  d.count = d.width = n;
  for (int w : widths_in) d.in.push_back(small_ints(n * w, seed++, -20, 20));
  for (int w : widths_out) d.out.push_back(small_ints(n * w, seed++, -5, 5));
  return d;
}

// 37 elements: groups of 8 and 4 end with a short one.
constexpr int64_t kCount = 37;

TEST(LowerLockstep, IfElseBlendsPartialWrites) {
  Program p = program("if_else", [] {
    Input<Int> a("a");
    Input<Int2> b("b");
    Output<Int2> y("y");
    Output<Int> z("z");
    Int t = a * 3;
    RILL_IF(a > 0) {
      y(1) = t + b.x();  // one component, under a mask
      RILL_IF(b.y() < 0) {
        z = b.y();
      }
      RILL_ELSE {
        y = b(1, 0);  // whole, swizzled, in a nested mask
      }
      RILL_ENDIF;
    }
    RILL_ELSE {
      y(0) = y.y() - a;  // reads what it partly writes
      t = t + 1;
    }
    RILL_ENDIF;
    z = z + t;
  });
  check(p, ints({1, 2}, {2, 1}, kCount, 11));
}

TEST(LowerLockstep, WhileLoopsWithBreakAndContinue) {
  Program p = program("while", [] {
    Input<Int> n("n");
    Input<Int> m("m");
    Output<Int> y("y");
    Int i = 0, sum = 0;
    RILL_WHILE(i < n) {
      i += 1;
      RILL_IF((i & 1) == 0) {
        RILL_CONTINUE;
      }
      RILL_ENDIF;
      sum += i;
      RILL_IF(sum > m) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      sum += 1;
    }
    RILL_ENDWHILE;
    y = sum * 100 + i;
  });
  check(p, ints({1, 1}, {1}, kCount, 21));
}

TEST(LowerLockstep, ForAndDoUntilLoopsNested) {
  Program p = program("for_do", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    Int acc = 0;
    RILL_FOR(Int i = 0, i < n, i += 1) {
      RILL_IF(i == 3) {
        RILL_CONTINUE;  // still runs the step (lower_continue)
      }
      RILL_ENDIF;
      Int j = i;
      RILL_DO {
        acc += j;
        j -= 2;
        RILL_IF(acc > 40) {
          RILL_BREAK;
        }
        RILL_ENDIF;
      }
      RILL_UNTIL(j <= 0);
    }
    RILL_ENDFOR;
    y = acc;
  });
  check(p, ints({1}, {1}, kCount, 31));
}

TEST(LowerLockstep, DiscardAtTopLevelAndInsideLoops) {
  Program p = program("discard", [] {
    Input<Int> a("a");
    Output<Int> y("y");
    RILL_IF(a == 7) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    Int i = 0;
    RILL_WHILE(i < 10) {
      i += 1;
      RILL_IF(a + i == 0) {
        RILL_DISCARD;  // leaves the loop and the kernel, in some lanes
      }
      RILL_ENDIF;
    }
    RILL_ENDWHILE;
    y = a + i;
  });
  check(p, ints({1}, {1}, kCount, 41));
}

TEST(LowerLockstep, GathersAndElementIndexUnderMasks) {
  Array<Float> table(std::vector<float>{0.5f, -1.0f, 2.0f, 8.0f, -0.0f}, "table");
  Program p = program("gather", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Int i = element_index();
    RILL_IF(x > 0.0f) {
      y = table[i % 5] * x;
    }
    RILL_ELSE {
      Float acc = 0.0f;
      Int k = 0;
      RILL_WHILE(k < i % 4) {
        acc += table[k - 1];  // clamped at 0
        k += 1;
      }
      RILL_ENDWHILE;
      y = acc;
    }
    RILL_ENDIF;
  });
  Data d;
  d.count = d.width = kCount;
  d.in.push_back(test::bits_of(test::random_floats(kCount, 51)));
  d.out.push_back(test::bits_of(test::random_floats(kCount, 52)));
  check(p, d);
}

// A side of a few cheap assignments runs for every lane, blended, with no `if` around it; a
// side that gathers keeps its guard. Both still compute what the source does.
TEST(LowerLockstep, ShortSidesRunUnguarded) {
  Array<Int> table(std::vector<int32_t>{3, -1, 7}, "table");
  Program p = program("short_sides", [&] {
    Input<Int> a("a");
    Output<Int> y("y");
    Int t = a;
    RILL_IF(a > 0) {
      t = t * 2 + 1;
    }
    RILL_ELSE {
      t = t - 3;
    }
    RILL_ENDIF;
    RILL_IF(t < 4) {
      t = t + table[t];  // a gather: guarded
    }
    RILL_ENDIF;
    y = t;
  });
  check(p, ints({1}, {1}, kCount, 61));
  const Function ref = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  const passes::LockstepFunction lowered = passes::lower_lockstep(ref);
  EXPECT_EQ(test::count_kind(ref, StmtKind::If), 2) << ir::print(ref);
  EXPECT_EQ(test::count_kind(lowered.f, StmtKind::If), 1) << ir::print(lowered.f);
  int guarded_gathers = 0;
  ir::for_each_stmt(lowered.f.body, [&](const Stmt& s) {
    if (s.kind == StmtKind::If)
      for (const Stmt& inner : s.then_body) guarded_gathers += inner.op == Op::Gather;
  });
  EXPECT_EQ(guarded_gathers, 1) << ir::print(lowered.f);
}

// A kernel without control flow needs no masks: the lowering leaves it as it is.
TEST(LowerLockstep, StraightLineCodeIsUnchanged) {
  Program p = program("straight", [] {
    Input<Float3> v("v");
    Output<Float> y("y");
    y = dot(v, v) + 1.0f;
  });
  const Function ref = passes::optimize(p.ir(), PassOptions{}, Accuracy::Strict);
  const passes::LockstepFunction lowered = passes::lower_lockstep(ref);
  EXPECT_EQ(lowered.alive, ir::kNoVar);
  EXPECT_EQ(ir::print(lowered.f), ir::print(ref));
}

}  // namespace
}  // namespace rill
