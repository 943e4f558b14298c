// passes::canonicalize: the listing does not depend on the order C++ evaluated the DSL in.
//
// GCC and clang evaluate a call's arguments (and the operands of `a * b + c * d`) in
// different orders. These tests write one kernel in two statement orders, as the two compilers
// would record it, and expect one listing, one hash and one set of results.
#include <memory>

#include "TestUtil.h"

namespace rill {
namespace {

using test::normalized;

// y = (x * 2) + (z * 3), the two products recorded in either order.
Program sum_of_products(bool left_first) {
  return program("products", [left_first] {
    Input<Float> x("x");
    Input<Float> z("z");
    Output<Float> y("y");
    std::optional<Float> left, right;
    if (left_first) {
      left = x * 2.0f;
      right = z * 3.0f;
    } else {
      right = z * 3.0f;
      left = x * 2.0f;
    }
    y = *left + *right;
  });
}

TEST(Canonicalize, OperandsRecordedInEitherOrderGiveOneListing) {
  Program a = sum_of_products(true), b = sum_of_products(false);
  EXPECT_EQ(a.print(), b.print());
  EXPECT_EQ(a.hash(), b.hash());
  // Operands first, left to right, just before the statement that needs them.
  EXPECT_HAS(a.print(),
             "  t3 = mul(x_0, 2.0)\n  t4 = mul(z_1, 3.0)\n  t5 = add(t3, t4)\n  y_2 = copy(t5)\n");
}

// Values passed by value are copied into locals, in the order C++ evaluates the arguments.
Float difference(Float a, Float b) {
  return a - b;
}

TEST(Canonicalize, CopiesMadeInEitherOrderGiveOneListing) {
  auto kernel = [](bool left_first) {
    return program("copies", [left_first] {
      Input<Float> x("x");
      Input<Float> z("z");
      Output<Float> y("y");
      Float u = x * 2.0f, w = z + 1.0f;
      std::optional<Float> a, b;
      if (left_first) {
        a.emplace(u);  // copies of lvalues, as a by-value argument makes them
        b.emplace(w);
      } else {
        b.emplace(w);
        a.emplace(u);
      }
      y = difference(*a, *b);
    });
  };
  Program a = kernel(true), b = kernel(false);
  EXPECT_EQ(a.print(), b.print());
  EXPECT_EQ(test::count_ops(a.ir(), ir::Op::Copy), 5) << a.print();  // four copies and y
}

// Reads two uniforms and two arrays, in either order.
struct Interface {
  Uniform<Float> gain{2.0f, "gain"};
  Uniform<Float> bias{0.5f, "bias"};
  Array<Float> first{std::vector<float>{10.0f, 20.0f}, "first"};
  Array<Float> second{std::vector<float>{1.0f, 3.0f}, "second"};

  Program kernel(bool gain_first) {
    return program("interface", [this, gain_first] {
      Input<Int> i("i");
      Output<Float> y("y");
      std::optional<Float> g, b, s;
      if (gain_first) {
        g = gain * first[i];
        b = bias * second[i];
      } else {
        b = bias * second[i];
        g = gain * first[i];
      }
      y = *g - *b;
    });
  }
};

TEST(Canonicalize, UniformsAndArraysAreOrderedByFirstUse) {
  Interface in;
  Program a = in.kernel(true), b = in.kernel(false);
  EXPECT_EQ(a.print(), b.print());
  for (const Program* p : {&a, &b}) {
    const ir::Function& f = p->ir();
    ASSERT_EQ(f.uniforms.size(), 2u);
    EXPECT_EQ(f.var(f.uniforms[0]).name, "gain");
    EXPECT_EQ(f.var(f.uniforms[0]).slot, 0);
    EXPECT_EQ(f.var(f.uniforms[1]).name, "bias");
    EXPECT_EQ(f.var(f.uniforms[1]).slot, 1);
    ASSERT_EQ(f.arrays.size(), 2u);
    EXPECT_EQ(f.arrays[0].name, "first");
    EXPECT_EQ(f.arrays[1].name, "second");
    // The lists a launch binds by slot follow the same permutation.
    EXPECT_EQ(p->captured().uniforms[0].get(), in.gain.ref().uniform.get());
    EXPECT_EQ(p->captured().arrays[1].get(), in.second.state().get());
  }
}

TEST(CanonicalizeCpu, PermutedUniformsAndArraysStillBindTheirData) {
  Interface in;
  for (bool gain_first : {true, false}) {
    std::vector<float> y =
        test::run_cpu<Float, Int>(in.kernel(gain_first), CompileOptions{}, std::vector{0, 1});
    EXPECT_EQ(y, (std::vector<float>{2.0f * 10.0f - 0.5f * 1.0f, 2.0f * 20.0f - 0.5f * 3.0f}));
  }
}

// A temporary that reads a variable stays ahead of the next write to it, even though the
// statement that needs it comes after that write.
Program read_before_write() {
  return program("war", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float v = x;
    label(v, "v");
    Float before = v + 1.0f;  // reads v as it is now
    v = v * 10.0f;
    y = before + v;
  });
}

TEST(Canonicalize, AReadStaysAheadOfTheNextWrite) {
  const std::string text = normalized(read_before_write().print());
  // v_# = copy(x_0); the product and the read (both of the first v); v_# = copy(product).
  EXPECT_HAS(text,
             "  v_2 = copy(x_0)\n  t# = mul(v_2, 10.0)\n  t# = add(v_2, 1.0)\n  v_2 = copy(t#)\n");
}

TEST(CanonicalizeCpu, AReadStaysAheadOfTheNextWriteAndKeepsItsValue) {
  std::vector<float> y =
      test::run_cpu<Float, Float>(read_before_write(), CompileOptions{}, std::vector{1.0f, 2.0f});
  EXPECT_EQ(y, (std::vector<float>{(1.0f + 1.0f) + 10.0f, (2.0f + 1.0f) + 20.0f}));
}

// Nothing moves ahead of a jump: the product after the break is computed after it.
TEST(Canonicalize, NothingMovesAheadOfAJump) {
  Program p = program("jump", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    RILL_WHILE(y < 100.0f) {
      Float twice = y * 2.0f;
      RILL_IF(y > 50.0f) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      y = twice;
    }
    RILL_ENDWHILE;
  });
  std::string text = normalized(p.print());
  const size_t jump = text.find("break");
  const size_t mul = text.find("mul(y_1, 2.0)");
  ASSERT_NE(jump, std::string::npos) << text;
  ASSERT_NE(mul, std::string::npos) << text;
  EXPECT_LT(jump, mul) << text;  // recorded before the if, needed only after it
  EXPECT_EQ(test::problems(p.ir()), "");
}

// A temporary read inside a nested block is computed in its own block, before the
// statement holding that block; one read after its block (a loop's condition) stays put.
TEST(Canonicalize, TemporariesStayInTheirBlock) {
  Program p = program("blocks", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = 0.0f;
    Float h = x * 0.5f;
    RILL_IF(x > 1.0f) {
      y = h;
    }
    RILL_ENDIF;
    RILL_DO {
      y = y + 1.0f;
    }
    RILL_UNTIL(y > x);
  });
  std::string text = normalized(p.print());
  // The if's condition first, then what its blocks read.
  EXPECT_HAS(text, "  t# = gt(x_0, 1.0)\n  t# = mul(x_0, 0.5)\n  if t# {\n    y_1 = copy(t#)\n");
  EXPECT_HAS(text, "    until:\n    t# = gt(y_1, x_0)\n    exit if t#\n");
  EXPECT_EQ(test::problems(p.ir()), "");
}

TEST(Canonicalize, IsIdempotentAndKeepsDeadCode) {
  Program p = program("dead", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float unused = x * 3.0f;
    y = x + 1.0f;
  });
  ir::Function f = p.ir();
  passes::canonicalize(f);
  EXPECT_EQ(ir::print(f), p.print());
  EXPECT_EQ(test::count_ops(f, ir::Op::Mul), 1);  // the captured program keeps dead code
}

// A chain of values as long as the kernel (a sum built term by term, each term a new value)
// keeps every link and its order. (The walk keeps its own stack; a recursive one also passed
// this length in an optimized build, so this does not prove the stack is safe.)
TEST(Canonicalize, LongChainsOfValues) {
  constexpr int kLinks = 100000;
  Program p = program("chain", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    auto sum = std::make_unique<Float>(x + 1.0f);
    for (int i = 1; i < kLinks; ++i) sum = std::make_unique<Float>(*sum + 1.0f);
    y = *sum;
  });
  EXPECT_EQ(test::count_ops(p.ir(), ir::Op::Add), kLinks);
  EXPECT_EQ(p.ir().body.back().op, ir::Op::Copy);  // y, after every link
}

// Strict lowering records Rill's math routines with the DSL too: optimize() canonicalizes
// after it, so both orders give one kernel.
TEST(Canonicalize, OptimizedStrictKernelsMatchToo) {
  auto kernel = [](bool left_first) {
    return program("strict", [left_first] {
      Input<Float> x("x");
      Output<Float> y("y");
      std::optional<Float> a, b;
      if (left_first) {
        a = pow(x, 2.5f);
        b = exp(x);
      } else {
        b = exp(x);
        a = pow(x, 2.5f);
      }
      y = *a + *b;
    });
  };
  ir::Function a = passes::optimize(kernel(true).ir(), PassOptions{}, Accuracy::Strict);
  ir::Function b = passes::optimize(kernel(false).ir(), PassOptions{}, Accuracy::Strict);
  EXPECT_EQ(ir::print(a), ir::print(b));
  EXPECT_EQ(test::problems(a), "");
}

}  // namespace
}  // namespace rill
