// Misuse of the DSL: every mistake throws rill::Error naming the problem and, where the
// library records it, the file:line of the user code.
//
// The control-flow macros open and close C++ braces, so a misnested pair does not compile;
// those tests call the rill::detail functions the macros expand to. `at = __LINE__, call`
// on one line records the line the call reports.
#include <optional>

#include "TestUtil.h"

namespace rill {
namespace {

using test::error_of;
using test::here;

#define LOC(line) here(__FILE__, line)

// A program with an input x and an output y (written), then `more`.
template <class F>
Program with_xy(F&& more) {
  return program("p", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    more(x, y);
  });
}

Bool positive(const Float& x) {
  return x > 0.0f;
}

// ---- misnested control flow ------------------------------------------------------------------

TEST(Errors, EndWhileClosingAnIf) {
  int open = 0, close = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      open = __LINE__, detail::begin_if(detail::condition(positive(x)), RILL_HERE);
      close = __LINE__, detail::end_while(RILL_HERE);
    });
  });
  EXPECT_HAS(msg, "RILL_ENDWHILE");
  EXPECT_HAS(msg, "RILL_IF at " + LOC(open));
  EXPECT_EQ(msg.rfind(LOC(close) + ": ", 0), 0u) << msg;  // starts with where it happened
}

TEST(Errors, EndIfClosingAWhile) {
  int open = 0, close = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      open = __LINE__, detail::begin_while(RILL_HERE);
      detail::while_body(detail::condition(positive(x)), RILL_HERE);
      close = __LINE__, detail::end_if(RILL_HERE);
    });
  });
  EXPECT_HAS(msg, "RILL_ENDIF");
  EXPECT_HAS(msg, "RILL_WHILE at " + LOC(open));
  EXPECT_HAS(msg, LOC(close));
}

TEST(Errors, EndForClosingADoAndUntilClosingAFor) {
  int open = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float&, Float&) {
      open = __LINE__, detail::begin_do(RILL_HERE);
      detail::end_for(RILL_HERE);
    });
  });
  EXPECT_HAS(msg, "RILL_ENDFOR");
  EXPECT_HAS(msg, "RILL_DO at " + LOC(open));

  msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      open = __LINE__, detail::begin_for(RILL_HERE);
      detail::for_cond(detail::condition(positive(x)), RILL_HERE);
      detail::for_body(RILL_HERE);
      detail::begin_until(RILL_HERE);
    });
  });
  EXPECT_HAS(msg, "RILL_UNTIL");
  EXPECT_HAS(msg, "RILL_FOR at " + LOC(open));
}

TEST(Errors, ElseWithoutIf) {
  int at = 0;
  std::string msg = error_of(
      [&] { with_xy([&](Float&, Float&) { at = __LINE__, detail::begin_else(RILL_HERE); }); });
  EXPECT_HAS(msg, "RILL_ELSE without a matching RILL_IF");
  EXPECT_HAS(msg, LOC(at));
}

TEST(Errors, ElseIfWithoutIf) {
  std::string msg =
      error_of([&] { with_xy([&](Float&, Float&) { detail::begin_else_if(RILL_HERE); }); });
  EXPECT_HAS(msg, "RILL_ELSE_IF without a matching RILL_IF");
}

TEST(Errors, ElseInsideALoopInsideAnIf) {
  int open = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      RILL_IF(positive(x)) {
        open = __LINE__, detail::begin_while(RILL_HERE);
        detail::while_body(detail::condition(positive(x)), RILL_HERE);
        detail::begin_else(RILL_HERE);
      }
      RILL_ENDIF;
    });
  });
  EXPECT_HAS(msg, "RILL_ELSE");
  EXPECT_HAS(msg, "RILL_WHILE at " + LOC(open));
}

TEST(Errors, SecondElse) {
  int at = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      RILL_IF(positive(x)) {}
      RILL_ELSE {}
      at = __LINE__;
      RILL_ELSE {}
      RILL_ENDIF;
    });
  });
  EXPECT_HAS(msg, "RILL_ELSE");
  EXPECT_HAS(msg, LOC(at + 1));
}

TEST(Errors, UntilWithoutDo) {
  int at = 0;
  std::string msg = error_of(
      [&] { with_xy([&](Float&, Float&) { at = __LINE__, detail::begin_until(RILL_HERE); }); });
  EXPECT_HAS(msg, "RILL_UNTIL without a matching RILL_DO");
  EXPECT_HAS(msg, LOC(at));
}

TEST(Errors, ClosingMacrosWithNothingOpen) {
  EXPECT_HAS(error_of([] { with_xy([](Float&, Float&) { detail::end_if(RILL_HERE); }); }),
             "RILL_ENDIF without a matching RILL_IF");
  EXPECT_HAS(error_of([] { with_xy([](Float&, Float&) { detail::end_while(RILL_HERE); }); }),
             "RILL_ENDWHILE without a matching RILL_WHILE");
  EXPECT_HAS(error_of([] { with_xy([](Float&, Float&) { detail::end_for(RILL_HERE); }); }),
             "RILL_ENDFOR without a matching RILL_FOR");
}

TEST(Errors, ConstructLeftOpenAtTheEndOfTheProgram) {
  int open = 0, defined = 0;
  auto body = [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    open = __LINE__, detail::begin_do(RILL_HERE);
  };
  std::string msg = error_of([&] { defined = __LINE__, program("unclosed", body); });
  EXPECT_HAS(msg, "program 'unclosed'");
  EXPECT_HAS(msg, "RILL_DO at " + LOC(open) + " is still open");
  EXPECT_EQ(msg.rfind(LOC(defined) + ": ", 0), 0u) << msg;
}

TEST(Errors, CaptureRecoversAfterAnError) {
  EXPECT_HAS(error_of([] {
               with_xy([](Float& x, Float&) {
                 RILL_WHILE(positive(x)) {
                   detail::end_if(RILL_HERE);
                 }
                 RILL_ENDWHILE;
               });
             }),
             "RILL_ENDIF");
  EXPECT_FALSE(detail::in_program());
  Program p = with_xy([](Float& x, Float& y) {
    RILL_IF(positive(x)) {
      y = -x;
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(test::count_kind(p.ir(), ir::StmtKind::If), 1);
  EXPECT_EQ(test::problems(p.ir()), "");
}

// ---- jumps -----------------------------------------------------------------------------------

TEST(Errors, BreakAndContinueOutsideALoop) {
  int at = 0;
  std::string msg = error_of([&] { with_xy([&](Float&, Float&) { at = __LINE__, RILL_BREAK; }); });
  EXPECT_HAS(msg, "RILL_BREAK outside a loop");
  EXPECT_HAS(msg, LOC(at));

  msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      RILL_IF(positive(x)) {
        at = __LINE__, RILL_CONTINUE;
      }
      RILL_ENDIF;
    });
  });
  EXPECT_HAS(msg, "RILL_CONTINUE outside a loop");
  EXPECT_HAS(msg, LOC(at));
}

TEST(Errors, BreakInsideAConditionOrStep) {
  int at = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float&, Float&) {
      at = __LINE__;
      RILL_FOR(Int i = 0, i < 3, (i += 1, RILL_BREAK)) {}
      RILL_ENDFOR;
    });
  });
  EXPECT_HAS(msg, "RILL_BREAK inside the condition or step of RILL_FOR");
  EXPECT_HAS(msg, LOC(at + 1));

  msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      RILL_WHILE((RILL_CONTINUE, positive(x))) {}
      RILL_ENDWHILE;
    });
  });
  EXPECT_HAS(msg, "RILL_CONTINUE inside the condition or step of RILL_WHILE");
}

TEST(Errors, DiscardIsAllowedAnywhere) {
  Program p = with_xy([](Float& x, Float&) {
    RILL_DISCARD;
    RILL_IF(positive(x)) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(test::count_kind(p.ir(), ir::StmtKind::Discard), 2);
}

// ---- values in the wrong place ---------------------------------------------------------------

TEST(Errors, ValueOfAnotherProgram) {
  std::optional<Float> leaked;
  program("first", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
    leaked.emplace(x * 2.0f);
  });
  std::string msg = error_of([&] {
    program("second", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = *leaked + x;
    });
  });
  EXPECT_HAS(msg, "program 'first'");
  EXPECT_HAS(msg, "program 'second'");

  msg = error_of([&] {
    program("third", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = x;
      *leaked = x;
    });
  });
  EXPECT_HAS(msg, "program 'first'");
  EXPECT_HAS(msg, "program 'third'");
}

TEST(Errors, ValueOfTheEnclosingProgramInANestedOne) {
  std::string msg = error_of([] {
    program("outer", [] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = x;
      program("inner", [&] {
        Output<Float> z("z");
        z = x;
      });
    });
  });
  EXPECT_HAS(msg, "program 'outer'");
  EXPECT_HAS(msg, "program 'inner'");
  EXPECT_FALSE(detail::in_program());
}

TEST(Errors, OutputNeverWritten) {
  int defined = 0;
  auto body = [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> z("z");
    z = x;
  };
  std::string msg = error_of([&] { defined = __LINE__, program("forgetful", body); });
  EXPECT_HAS(msg, "output 'y' is never written");
  EXPECT_HAS(msg, "program 'forgetful'");
  EXPECT_HAS(msg, LOC(defined));
}

TEST(Errors, OutputWrittenOnOnePathIsFine) {
  Program p = program("some", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF(x > 0.0f) {
      y = x;
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(test::problems(p.ir()), "");
}

TEST(Errors, AssigningToAUniform) {
  Uniform<Float> gain(1.0f, "gain");
  std::string msg = error_of([&] { with_xy([&](Float&, Float&) { gain += 1.0f; }); });
  EXPECT_HAS(msg, "uniform is read-only");
  msg = error_of([&] { with_xy([&](Float& x, Float&) { static_cast<Float&>(gain) = x; }); });
  EXPECT_HAS(msg, "uniform is read-only");
}

TEST(Errors, AssigningToAUniformThroughAWriteMask) {
  Uniform<Float3> tint(glm::vec3(1.0f), "tint");
  std::string msg = error_of([&] { with_xy([&](Float&, Float&) { tint(0) = 2.0f; }); });
  EXPECT_HAS(msg, "uniform");
}

TEST(Errors, AssigningToAConstantMadeOutside) {
  Float3 shared(1.0f, 2.0f, 3.0f);
  std::string msg = error_of([&] { with_xy([&](Float& x, Float&) { shared = Float3(x, x, x); }); });
  EXPECT_HAS(msg, "created outside this program");
  EXPECT_EQ(shared.ref().value.f(0), 1.0f);
}

TEST(Errors, DslOperationsOutsideAnyProgram) {
  ASSERT_FALSE(detail::in_program());
  Float a = 1.0f;
  EXPECT_HAS(error_of([&] { (void)(a + 2.0f); }), "outside a program");
  EXPECT_HAS(error_of([&] { (void)sqrt(a); }), "outside a program");
  EXPECT_HAS(error_of([] { (void)element_index(); }), "outside a program");
  Uniform<Float> gain(2.0f, "gain");
  EXPECT_HAS(error_of([&] { (void)(gain * 2.0f); }), "outside a program");
  Array<Float> table(4, "table");
  EXPECT_HAS(error_of([&] { (void)table[Int(1)]; }), "outside a program");
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, Input<Float>("x"); });
  EXPECT_HAS(msg, "declaring an Input outside a program");
  EXPECT_HAS(msg, LOC(at));
  msg = error_of([&] { at = __LINE__, detail::begin_if(detail::condition(true), RILL_HERE); });
  EXPECT_HAS(msg, "RILL_IF outside a program");
  EXPECT_HAS(msg, LOC(at));
  EXPECT_HAS(error_of([] { detail::emit_break(RILL_HERE); }), "RILL_BREAK outside a program");
}

TEST(Errors, SwizzleIndexOutOfRange) {
  std::string msg = error_of([] {
    program("p", [] {
      Input<Float3> v("v");
      Output<Float> y("y");
      y = v(3);
    });
  });
  EXPECT_HAS(msg, "swizzle component 3 is out of range for a float3");
  EXPECT_HAS(error_of([] {
               program("p", [] {
                 Input<Float2> v("v");
                 Output<Float2> y("y");
                 y = v(0, -1);
               });
             }),
             "swizzle component -1");
  const Float2 k(1.0f, 2.0f);
  EXPECT_HAS(error_of([&] { (void)k.z(); }), "swizzle component 2 is out of range for a float2");
}

TEST(Errors, RepeatedComponentInAWriteMask) {
  std::string msg = error_of([] {
    program("p", [] {
      Input<Float3> v("v");
      Output<Float3> y("y");
      y = v;
      y(0, 0) = Float2(1.0f, 2.0f);
    });
  });
  EXPECT_HAS(msg, "write mask repeats component 0");
  EXPECT_HAS(error_of([] {
               program("p", [] {
                 Input<Float4> v("v");
                 Output<Float4> y("y");
                 y = v;
                 y(1, 2, 1) = 3.0f;
               });
             }),
             "write mask repeats component 1");
}

TEST(Errors, ArrayIndexedWithTheWrongNumberOfIndices) {
  Array<Float> grid(2, 2, "grid");
  Array<Float> line(8, "line");
  Array<Int> vol(2, 2, 2, "vol");
  auto use = [](auto&& gather) {
    return error_of([&] {
      program("p", [&] {
        Input<Int> i("i");
        Output<Float> y("y");
        y = gather(i);
      });
    });
  };
  EXPECT_HAS(use([&](const Int& i) { return grid[i]; }),
             "array 'grid' is 2D but was indexed with 1");
  EXPECT_HAS(use([&](const Int& i) { return line(i, i); }),
             "array 'line' is 1D but was indexed with 2");
  EXPECT_HAS(use([&](const Int& i) { return to_float(vol(i, i)); }),
             "array 'vol' is 3D but was indexed with 2");
}

TEST(Errors, InterfaceDeclaredInsideControlFlow) {
  int open = 0, at = 0;
  std::string msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      open = __LINE__, detail::begin_if(detail::condition(positive(x)), RILL_HERE);
      at = __LINE__, Input<Float>("late");
    });
  });
  EXPECT_HAS(msg, "declaring an Input inside RILL_IF at " + LOC(open));
  EXPECT_EQ(msg.rfind(LOC(at) + ": ", 0), 0u) << msg;

  msg = error_of([&] {
    with_xy([&](Float& x, Float&) {
      RILL_WHILE(positive(x)) {
        Output<Float> z("z");
      }
      RILL_ENDWHILE;
    });
  });
  EXPECT_HAS(msg, "declaring an Output inside RILL_WHILE");
}

TEST(Errors, DuplicateNames) {
  EXPECT_HAS(error_of([] {
               program("p", [] {
                 Input<Float> x("x");
                 Input<Float> x2("x");
                 Output<Float> y("y");
                 y = x + x2;
               });
             }),
             "the name 'x' is already taken");
  Uniform<Float> a(1.0f, "u"), b(2.0f, "u");
  EXPECT_HAS(error_of([&] { with_xy([&](Float& x, Float& y) { y = x * a + b; }); }),
             "two different uniforms named 'u'");
}

TEST(Errors, CompilingNothingOrForAnUnknownBackend) {
  EXPECT_HAS(error_of([] { compile(Program()); }), "empty");
  Program p = with_xy([](Float&, Float&) {});
  EXPECT_HAS(error_of([&] { compile(p, "no-such-backend"); }), "unknown backend 'no-such-backend'");
}

}  // namespace
}  // namespace rill
