// Source locations beside the IR (ir::Stmt::loc): the line each captured statement records,
// what a statement made by an operator gets, the chain of calls through functions marked
// with rill::CallSite, and that none of it changes a program's hash, text or generated code.
//
// Line numbers are the subject here: each test takes __LINE__ on the very line of the call
// it checks (`at = __LINE__, call`, or inside a declaration's argument), so moving code
// keeps the tests right.
#include "TestUtil.h"

namespace rill {
namespace {

using test::error_of;
using test::here;

#define LOC(line) here(__FILE__, line)

// The statements of f, nested ones included, in program order.
std::vector<const ir::Stmt*> statements_of(const ir::Function& f) {
  std::vector<const ir::Stmt*> out;
  ir::for_each_stmt(f.body, [&](const ir::Stmt& s) { out.push_back(&s); });
  return out;
}

const ir::Stmt* first_of(const ir::Function& f, ir::StmtKind kind, ir::Op op = ir::Op::Copy) {
  for (const ir::Stmt* s : statements_of(f))
    if (s->kind == kind && (kind != ir::StmtKind::Assign || s->op == op)) return s;
  return nullptr;
}

TEST(SourceLocation, FilesAreNamedRelativeToTheProject) {
  int at = 0;
  SourceLoc l = (at = __LINE__, RILL_HERE);
  EXPECT_EQ(l.str(), "tests/dsl/SourceLocationTest.cpp:" + std::to_string(at));
  EXPECT_EQ(relative_path("./a/b.cpp"), "a/b.cpp");
  EXPECT_EQ(relative_path("../../a/b.cpp"), "a/b.cpp");
  EXPECT_EQ(SourceLoc{}.str(), "");
  EXPECT_EQ(SourceLoc{}.describe(), "");
}

TEST(SourceLocation, MacrosAndCallsRecordTheirLineOperatorsTheNearest) {
  int out_line = 0, if_line = 0, label_line = 0;
  Program p = program("p", [&] {
    Input<Float> x("x");
    Output<Float> y((out_line = __LINE__, "y"));
    Float t = x * 2.0f;  // an operator: near the Output's line
    label_line = __LINE__, label(t, "t");
    RILL_IF((if_line = __LINE__, x > 0.0f)) {
      y = t;
    }
    RILL_ENDIF;
  });
  const ir::Function& f = p.ir();

  const ir::Stmt* mul = first_of(f, ir::StmtKind::Assign, ir::Op::Mul);
  ASSERT_NE(mul, nullptr);
  EXPECT_TRUE(mul->loc.nearest);
  EXPECT_EQ(mul->loc.str(), LOC(out_line));
  EXPECT_EQ(mul->loc.describe(), "near " + LOC(out_line));

  const ir::Stmt* branch = first_of(f, ir::StmtKind::If);
  ASSERT_NE(branch, nullptr);
  EXPECT_FALSE(branch->loc.nearest);
  EXPECT_EQ(branch->loc.describe(), LOC(if_line));
  // The comparison is evaluated before RILL_IF records itself: near the label's line.
  const ir::Stmt* gt = first_of(f, ir::StmtKind::Assign, ir::Op::Gt);
  ASSERT_NE(gt, nullptr);
  EXPECT_EQ(gt->loc.describe(), "near " + LOC(label_line));
  // `y = t` inside the branch: near the RILL_IF.
  ASSERT_EQ(branch->then_body.size(), 1u);
  EXPECT_EQ(branch->then_body[0].loc.describe(), "near " + LOC(if_line));
  // Every statement has a location.
  for (const ir::Stmt* s : statements_of(f)) EXPECT_TRUE(s->loc.known());
}

// Library functions take their call site: every statement normalize() records (its dot,
// square root and division) names the user's line, not Math.h's.
TEST(SourceLocation, MathCallsAndDeclarationsRecordTheUserLine) {
  int norm_line = 0, decl_line = 0, copy_line = 0;
  Program p = program("p", [&] {
    Input<Float3> v("v");
    Output<Float3> y("y");
    Float3 n = (norm_line = __LINE__, normalize(v));
    Float k = (decl_line = __LINE__, 2.0f);
    Float3 m = n;
    copy_line = __LINE__ - 1;
    y = m * k;
  });
  const ir::Function& f = p.ir();
  for (ir::Op op : {ir::Op::Dot, ir::Op::Sqrt, ir::Op::Div}) {
    const ir::Stmt* s = first_of(f, ir::StmtKind::Assign, op);
    ASSERT_NE(s, nullptr) << ir::op_name(op);
    EXPECT_EQ(s->loc.describe(), LOC(norm_line)) << ir::op_name(op);
  }
  int declared = 0, copied = 0;
  for (const ir::Stmt* s : statements_of(f)) {
    if (s->kind != ir::StmtKind::Assign || s->op != ir::Op::Copy) continue;
    declared += s->loc.describe() == LOC(decl_line);
    copied += s->loc.describe() == LOC(copy_line);
  }
  EXPECT_EQ(declared, 1);
  EXPECT_EQ(copied, 1);
  // The multiplication that follows is near the copy.
  EXPECT_EQ(first_of(f, ir::StmtKind::Assign, ir::Op::Mul)->loc.describe(),
            "near " + LOC(copy_line));
}

TEST(SourceLocation, ThePrinterShowsLocationsOnlyWhenAsked) {
  int if_line = 0;
  Program p = program("p", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    RILL_IF((if_line = __LINE__, x > 0.0f)) {
      y = x;
    }
    RILL_ENDIF;
  });
  const std::string plain = p.print(), located = p.print(ir::PrintOptions{.locations = true});
  EXPECT_EQ(plain.find(" @ "), std::string::npos) << plain;
  EXPECT_HAS(located, " {  @ " + LOC(if_line) + "\n");
  EXPECT_HAS(located, "  @ near " + LOC(if_line) + "\n");
  // Less the locations, the same text.
  EXPECT_EQ(std::regex_replace(located, std::regex("  @ [^\n]*"), ""), plain);
}

// Two programs alike but for the lines they were written on: one macro, expanded on two
// lines (a macro's locations are those of the line that expands it).
#define RILL_TEST_DOUBLING_PROGRAM \
  program("p", [] {                \
    Input<Float> x("x");           \
    Output<Float> y("y");          \
    RILL_IF(x > 0.0f) {            \
      y = x * 2.0f;                \
    }                              \
    RILL_ENDIF;                    \
  })
Program written_here() {
  return RILL_TEST_DOUBLING_PROGRAM;
}
Program written_further_down() {
  return RILL_TEST_DOUBLING_PROGRAM;
}
#undef RILL_TEST_DOUBLING_PROGRAM

TEST(SourceLocation, LocationsChangeNeitherHashNorText) {
  const Program a = written_here(), b = written_further_down();
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_EQ(a.print(), b.print());
  EXPECT_NE(a.print(ir::PrintOptions{.locations = true}),
            b.print(ir::PrintOptions{.locations = true}));
}

TEST(SourceLocationCpu, LocationsChangeNoGeneratedCode) {
  const Program a = written_here(), b = written_further_down();
  clear_kernel_cache();
  const std::string first = compile(a, "cpu").source();
  clear_kernel_cache();  // compile b itself, not a's cache entry
  const std::string second = compile(b, "cpu").source();
  EXPECT_EQ(first, second);
  EXPECT_EQ(first.find("#line"), std::string::npos);
}

TEST(SourceLocation, AssigningAnOutsideValueNamesTheNearestLine) {
  Float outside = 1.0f;
  int at = 0;
  const std::string msg = error_of([&] {
    program("p", [&] {
      Input<Float> x("x");
      Output<Float> y((at = __LINE__, "y"));
      outside = x;
      y = x;
    });
  });
  EXPECT_EQ(msg.rfind("near " + LOC(at) +
                          ": a value created outside this program cannot be "
                          "assigned inside it",
                      0),
            0u)
      << msg;
  EXPECT_HAS(msg, "operators such as = and + cannot record one");
}

TEST(SourceLocation, SwizzleOutOfRangeNamesTheNearestLine) {
  int at = 0;
  const std::string msg = error_of([&] {
    program("p", [&] {
      Input<Float2> x("x");
      Output<Float> y("y");
      Float t = x.x();
      at = __LINE__, label(t, "t");
      y = x(2);
    });
  });
  EXPECT_EQ(msg.rfind("near " + LOC(at) + ": swizzle component 2", 0), 0u) << msg;
}

// Functions of the user's, marked with CallSite: errors and statements inside them name
// the chain of calls.
Float misnested(const Float& x, int* line, SourceLoc at = RILL_HERE) {
  CallSite site(at);
  Float y = x + 1.0f;
  *line = __LINE__, detail::begin_else(RILL_HERE);  // a RILL_ELSE with no RILL_IF open
  return y;
}
Float calls_misnested(const Float& x, int* inner, int* middle, SourceLoc at = RILL_HERE) {
  CallSite site(at);
  return (*middle = __LINE__, misnested(x, inner));
}
Float doubled(const Float& x, int* line, SourceLoc at = RILL_HERE) {
  CallSite site(at);
  Float y;
  *line = __LINE__, label(y, "doubled");
  y = x * 2.0f;
  return y;
}

TEST(SourceLocation, ErrorsInsideAFunctionNameTheChainOfCalls) {
  int inner = 0, call = 0;
  std::string msg = error_of([&] {
    program("p", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = (call = __LINE__, misnested(x, &inner));
    });
  });
  EXPECT_EQ(msg.rfind(LOC(inner) + ", called from " + LOC(call) + ": RILL_ELSE without", 0), 0u)
      << msg;

  int middle = 0, outer = 0;
  msg = error_of([&] {
    program("p", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = (outer = __LINE__, calls_misnested(x, &inner, &middle));
    });
  });
  EXPECT_EQ(
      msg.rfind(LOC(inner) + ", called from " + LOC(middle) + ", called from " + LOC(outer) + ": ",
                0),
      0u)
      << msg;
}

TEST(SourceLocation, StatementsInsideAFunctionCarryTheChain) {
  int inner = 0, call = 0, after = 0;
  Program p = program("p", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float d = (call = __LINE__, doubled(x, &inner));
    Float e = d + 1.0f;  // back in the body: near the call
    after = __LINE__, label(e, "e");
    y = e;
  });
  const ir::Stmt* mul = first_of(p.ir(), ir::StmtKind::Assign, ir::Op::Mul);
  ASSERT_NE(mul, nullptr);
  EXPECT_EQ(mul->loc.describe(), "near " + LOC(inner) + ", called from " + LOC(call));
  const ir::Stmt* add = first_of(p.ir(), ir::StmtKind::Assign, ir::Op::Add);
  ASSERT_NE(add, nullptr);
  EXPECT_EQ(add->loc.describe(), "near " + LOC(call));
  EXPECT_HAS(p.print(ir::PrintOptions{.locations = true}),
             "@ near " + LOC(inner) + ", called from " + LOC(call));
  EXPECT_GT(after, call);
}

TEST(SourceLocation, ProgramScopeErrorsNameTheDefinition) {
  int at = 0;
  const std::string msg = error_of([&] {
    at = __LINE__, program("p", [] {
      Input<Float> x("x");
      Output<Float> y("y");
      detail::begin_if(detail::condition(x > 0.0f), RILL_HERE);
    });
  });
  EXPECT_EQ(msg.rfind(LOC(at) + ": program 'p' ends while RILL_IF at ", 0), 0u) << msg;
}

}  // namespace
}  // namespace rill
