// Program algebra (Algebra.h) at the IR level: the interface of connected and combined
// programs (names, order, types, roles, slots), uniforms and arrays merged once, b's body
// remapped onto the fused program's variables, and every misuse with its message. That the
// fused kernels compute what separate launches compute is tests/backends/AlgebraTest.cpp.
#include "TestUtil.h"

namespace rill {
namespace {

using test::error_of;
using test::here;

#define LOC(line) here(__FILE__, line)

// The names and types of f's inputs or outputs: "x:float n:int".
std::string signature(const ir::Function& f, const std::vector<ir::VarId>& list) {
  std::string s;
  for (ir::VarId v : list) s += (s.empty() ? "" : " ") + f.var(v).name + ":" + f.var(v).type.str();
  return s;
}

void expect_slots(const ir::Function& f) {
  for (size_t i = 0; i < f.inputs.size(); ++i) {
    EXPECT_EQ(f.var(f.inputs[i]).role, ir::VarRole::Input);
    EXPECT_EQ(f.var(f.inputs[i]).slot, static_cast<int>(i));
  }
  for (size_t i = 0; i < f.outputs.size(); ++i) {
    EXPECT_EQ(f.var(f.outputs[i]).role, ir::VarRole::Output);
    EXPECT_EQ(f.var(f.outputs[i]).slot, static_cast<int>(i));
  }
  for (size_t i = 0; i < f.uniforms.size(); ++i) {
    EXPECT_EQ(f.var(f.uniforms[i]).role, ir::VarRole::Uniform);
    EXPECT_EQ(f.var(f.uniforms[i]).slot, static_cast<int>(i));
  }
}

// Variables with this role, any name.
int count_role(const ir::Function& f, ir::VarRole r) {
  int n = 0;
  for (const auto& v : f.vars) n += v.role == r;
  return n;
}

Program producer() {
  return program("a", [] {
    Input<Float> x("x");
    Input<Int> n("n");
    Output<Float> y("y");
    Output<Int3> extra("extra");
    y = x * 2.0f;
    extra = Int3(n, n + 1, n + 2);
  });
}

Program consumer() {
  return program("b", [] {
    Input<Float> y("y");
    Input<Int> n("n");
    Input<Float2> z("z");
    Output<Float> r("r");
    Output<Int> s("s");
    r = y + z.x();
    s = n * 3;
  });
}

TEST(Algebra, ConnectInterface) {
  Program a = producer(), b = consumer();
  Program c = connect(a, b);
  const ir::Function& f = c.ir();
  EXPECT_EQ(c.name(), "a>>b");
  // a's inputs, then b's unfed ones; n is one input; y is fed and gone.
  EXPECT_EQ(signature(f, f.inputs), "x:float n:int z:float2");
  // b's outputs, then the output of a that b does not read.
  EXPECT_EQ(signature(f, f.outputs), "r:float s:int extra:int3");
  expect_slots(f);
  // a's y is now a local of the fused program; no stray interface variables are left over.
  EXPECT_EQ(count_role(f, ir::VarRole::Input), 3);
  EXPECT_EQ(count_role(f, ir::VarRole::Output), 3);
  int y_locals = 0;
  for (const auto& v : f.vars) y_locals += v.name == "y" && v.role == ir::VarRole::Local;
  EXPECT_EQ(y_locals, 1);
  EXPECT_EQ(test::problems(f), "");
  // Both bodies, one after the other, nothing added.
  EXPECT_EQ(test::statements(f), test::statements(a.ir()) + test::statements(b.ir()));
  EXPECT_NE(c.hash(), a.hash());
  EXPECT_NE(c.hash(), b.hash());
  EXPECT_EQ(connect(a, b, "named").name(), "named");
  EXPECT_EQ((a >> b).hash(), c.hash());
}

TEST(Algebra, ConnectReadsTheFirstProgramsOutputVariable) {
  Program a = producer(), b = consumer();
  Program c = connect(a, b);
  const ir::Function& f = c.ir();
  const ir::VarId y = a.ir().outputs[0];  // a's variables keep their ids
  EXPECT_EQ(f.var(y).name, "y");
  EXPECT_EQ(f.var(y).role, ir::VarRole::Local);
  // a's statements come first, unchanged; in b's, `r = y + z.x` reads a's y.
  ASSERT_GT(f.body.size(), a.ir().body.size());
  int reads_in_b = 0;
  for (size_t i = a.ir().body.size(); i < f.body.size(); ++i)
    for (const auto& o : f.body[i].args) reads_in_b += o.is_var() && o.var == y;
  EXPECT_EQ(reads_in_b, 1) << ir::print(f);
  // b's n is a's n: one input read by both halves.
  const ir::VarId n = a.ir().inputs[1];
  int reads_of_n = 0;
  ir::for_each_operand(f.body,
                       [&](const ir::Operand& o) { reads_of_n += o.is_var() && o.var == n; });
  EXPECT_GE(reads_of_n, 2) << ir::print(f);
}

TEST(Algebra, CombineInterface) {
  Program a = producer(), b = consumer();
  Program c = combine(a, b);
  const ir::Function& f = c.ir();
  EXPECT_EQ(c.name(), "a&b");
  // The union by name: n is shared; b's y is an input here (combine feeds nothing).
  EXPECT_EQ(signature(f, f.inputs), "x:float n:int y:float z:float2");
  EXPECT_EQ(signature(f, f.outputs), "y:float extra:int3 r:float s:int");
  expect_slots(f);
  EXPECT_EQ(count_role(f, ir::VarRole::Input), 4);
  EXPECT_EQ(test::problems(f), "");
  EXPECT_EQ(test::statements(f), test::statements(a.ir()) + test::statements(b.ir()));
  EXPECT_EQ((a & b).hash(), c.hash());
  EXPECT_NE(c.hash(), connect(a, b).hash());
}

TEST(Algebra, UniformsAndArraysAreMergedOnce) {
  Uniform<Float> gain(2.0f, "gain");
  Uniform<Int> offset(3, "offset");
  Array<Float> table(std::vector<float>{1.0f, 2.0f, 3.0f}, "table");
  Array<Int> other(std::vector<int32_t>{4, 5}, "other");
  Program a = program("a", [&] {
    Input<Int> i("i");
    Output<Float> v("v");
    v = table[i] * gain;
  });
  Program b = program("b", [&] {
    Input<Float> v("v");
    Input<Int> i("i");
    Output<Float> w("w");
    // b gathers from `other` first: its array 0 is the fused program's array 1.
    // (separate statements: C++ leaves the order of operands unspecified).
    Int o = other[i] + offset;
    w = to_float(o) + v + table[i + 1] * gain;
  });
  for (const Program& p : {connect(a, b), combine(a, b, "ab")}) {
    const ir::Function& f = p.ir();
    SCOPED_TRACE(p.name());
    ASSERT_EQ(f.uniforms.size(), 2u);
    ASSERT_EQ(p.captured().uniforms.size(), 2u);
    EXPECT_EQ(p.captured().uniforms[0].get(), gain.ref().uniform.get());
    EXPECT_EQ(p.captured().uniforms[1].get(), offset.ref().uniform.get());
    EXPECT_EQ(f.var(f.uniforms[0]).name, "gain");
    EXPECT_EQ(f.var(f.uniforms[1]).name, "offset");
    EXPECT_EQ(count_role(f, ir::VarRole::Uniform), 2);
    expect_slots(f);
    ASSERT_EQ(f.arrays.size(), 2u);
    ASSERT_EQ(p.captured().arrays.size(), 2u);
    EXPECT_EQ(p.captured().arrays[0], table.state());
    EXPECT_EQ(p.captured().arrays[1], other.state());
    EXPECT_EQ(f.arrays[1].name, "other");
    // Every gather names the array its element type says: table's are float, other's int.
    int gathers = 0;
    ir::for_each_stmt(f.body, [&](const ir::Stmt& s) {
      if (s.kind != ir::StmtKind::Assign || s.op != ir::Op::Gather) return;
      ++gathers;
      EXPECT_EQ(f.arrays[static_cast<size_t>(s.array)].elem.kind, f.var(s.dst).type.kind);
    });
    EXPECT_EQ(gathers, 3);
    EXPECT_EQ(test::problems(f), "");
  }
  // A program connected to itself reads its uniforms once too.
  Program twice = program("twice", [&] {
    Input<Float> v("v");
    Output<Float> u("v");
    u = v * gain;
  });
  EXPECT_EQ((twice >> twice).ir().uniforms.size(), 1u);
}

TEST(Algebra, AnInputTheFirstProgramOverwritesIsCopiedForTheSecond) {
  Program a = program("a", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    x = x * 2.0f;  // a's own copy of the element
    y = x;
  });
  Program b = program("b", [] {
    Input<Float> y("y");
    Input<Float> x("x");
    Output<Float> z("z");
    z = x + y;
  });
  for (const Program& p : {connect(a, b), combine(a, program("b2", [] {
                                                    Input<Float> x("x");
                                                    Output<Float> z("z");
                                                    z = x;
                                                  }))}) {
    const ir::Function& f = p.ir();
    SCOPED_TRACE(p.name());
    ASSERT_EQ(f.inputs.size(), 1u);
    // The first statement copies the input before a overwrites it; b reads the copy.
    ASSERT_FALSE(f.body.empty());
    const ir::Stmt& first = f.body[0];
    EXPECT_EQ(first.op, ir::Op::Copy);
    ASSERT_EQ(first.args.size(), 1u);
    EXPECT_EQ(first.args[0].var, f.inputs[0]);
    EXPECT_EQ(f.var(first.dst).role, ir::VarRole::Local);
    EXPECT_EQ(f.var(first.dst).name, "x");
    bool reads_copy = false;
    ir::for_each_operand(f.body, [&](const ir::Operand& o) {
      reads_copy = reads_copy || (o.is_var() && o.var == first.dst);
    });
    EXPECT_TRUE(reads_copy) << ir::print(f);
    EXPECT_EQ(test::problems(f), "");
  }
}

TEST(Algebra, ResultsConnectAndCombineAgain) {
  Program a = producer(), b = consumer();
  Program tail = program("tail", [] {
    Input<Float> r("r");
    Output<Float> q("q");
    q = r - 1.0f;
  });
  Program c = (a >> b) >> tail;
  EXPECT_EQ(signature(c.ir(), c.ir().inputs), "x:float n:int z:float2");
  EXPECT_EQ(signature(c.ir(), c.ir().outputs), "q:float s:int extra:int3");
  EXPECT_EQ(test::problems(c.ir()), "");
}

// The example of docs/programming-model.md, "Program algebra".
TEST(Algebra, DocumentationExample) {
  Uniform<Float3> light(glm::vec3(0.0f, 0.0f, 1.0f), "light");
  Program shade = program("shade", [&] {
    Input<Float3> n("n");
    Output<Float3> rgb("rgb");
    rgb = Float3(max(dot(n, light), 0.0f));
  });
  Program luma = program("luma", [&] {
    Input<Float3> rgb("rgb");
    Output<Float> y("y");
    y = dot(rgb, Float3(0.2126f, 0.7152f, 0.0722f));
  });
  Program facing = program("facing", [&] {
    Input<Float3> n("n");
    Output<Int> front("front");
    front = to_int(sign(n.z()));
  });
  Program both = shade >> luma;
  Program side = shade & facing;
  EXPECT_EQ(signature(both.ir(), both.ir().inputs), "n:float3");
  EXPECT_EQ(signature(both.ir(), both.ir().outputs), "y:float");
  EXPECT_EQ(signature(side.ir(), side.ir().inputs), "n:float3");
  EXPECT_EQ(signature(side.ir(), side.ir().outputs), "rgb:float3 front:int");
}

// ---- errors -----------------------------------------------------------------------------------

TEST(AlgebraErrors, NothingToConnect) {
  Program a = producer();
  Program b = program("unrelated", [] {
    Input<Float> w("w");
    Output<Float> r("r");
    r = w;
  });
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, connect(a, b); });
  EXPECT_EQ(msg.rfind(LOC(at) + ": ", 0), 0u) << msg;
  EXPECT_HAS(msg, "connect('a', 'unrelated')");
  EXPECT_HAS(msg, "nothing to connect");
  EXPECT_HAS(msg, "'y' (float), 'extra' (int3)");
  EXPECT_HAS(msg, "'w' (float)");
}

TEST(AlgebraErrors, ConnectedTypesDiffer) {
  Program a = producer();
  Program b = program("wide", [] {
    Input<Float3> y("y");
    Output<Float3> r("r");
    r = y;
  });
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, connect(a, b); });
  EXPECT_HAS(msg, LOC(at));
  EXPECT_HAS(msg, "connect('a', 'wide')");
  EXPECT_HAS(msg, "'y' is output float of 'a' but input float3 of 'wide'");
}

TEST(AlgebraErrors, SharedInputTypesDiffer) {
  Program a = producer();  // n is an int
  Program b = program("b", [] {
    Input<Float> y("y");
    Input<Float> n("n");
    Output<Float> r("r");
    r = y + n;
  });
  std::string msg = error_of([&] { connect(a, b); });
  EXPECT_HAS(msg, "'n' is input int of 'a' but input float of 'b'");
  msg = error_of([&] { combine(a, b); });
  EXPECT_HAS(msg, "combine('a', 'b')");
  EXPECT_HAS(msg, "'n' is input int of 'a' but input float of 'b'");
}

Program discarding(const char* name, const char* in, const char* out) {
  return program(name, [&] {
    Input<Float> x(in);
    Output<Float> y(out);
    y = x;
    RILL_IF(x < 0.0f) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
  });
}

TEST(AlgebraErrors, DiscardInTheFirstProgram) {
  Program a = discarding("cull", "x", "y");
  Program b = program("b", [] {
    Input<Float> y("y");
    Output<Float> r("r");
    r = y;
  });
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, connect(a, b); });
  EXPECT_HAS(msg, LOC(at));
  EXPECT_HAS(msg, "connect('cull', 'b')");
  EXPECT_HAS(msg, "'cull' contains RILL_DISCARD");
  EXPECT_HAS(msg, "stale intermediate element");
  EXPECT_HAS(msg, "skip 'b'");
  msg = error_of([&] { combine(a, b); });
  EXPECT_HAS(msg, "combine('cull', 'b')");
  EXPECT_HAS(msg, "'cull' contains RILL_DISCARD");
  EXPECT_HAS(msg, "skip 'b'");
}

TEST(AlgebraErrors, DiscardInTheSecondProgram) {
  Program b = discarding("cull", "y", "r");
  // connect: fine when b reads every output of a (the intermediate is not observable) ...
  Program a1 = program("a1", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + 1.0f;
  });
  Program ok = connect(a1, b);
  EXPECT_EQ(signature(ok.ir(), ok.ir().outputs), "r:float");
  // ... not when a has an output b's discard would unwrite.
  Program a2 = program("a2", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Output<Float> kept("kept");
    y = x + 1.0f;
    kept = x;
  });
  std::string msg = error_of([&] { connect(a2, b); });
  EXPECT_HAS(msg, "connect('a2', 'cull')");
  EXPECT_HAS(msg, "'cull' contains RILL_DISCARD");
  EXPECT_HAS(msg, "'kept' (float)");
  // combine: always.
  msg = error_of([&] { combine(a1, b); });
  EXPECT_HAS(msg, "combine('a1', 'cull')");
  EXPECT_HAS(msg, "'cull' contains RILL_DISCARD");
  EXPECT_HAS(msg, "none of the outputs of 'a1'");
}

TEST(AlgebraErrors, DuplicateOutputNames) {
  Program a = producer();  // outputs y, extra
  Program b = program("b", [] {
    Input<Float> y("y");
    Output<Int3> extra("extra");
    extra = Int3(to_int(y));
  });
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, connect(a, b); });
  EXPECT_HAS(msg, LOC(at));
  EXPECT_HAS(msg, "connect('a', 'b')");
  EXPECT_HAS(msg, "output named 'extra' (int3 and int3");
  EXPECT_HAS(msg, "keeps the outputs of 'a' that 'b' does not read");
  msg = error_of([&] { combine(a, a); });
  EXPECT_HAS(msg, "combine('a', 'a')");
  EXPECT_HAS(msg, "output named 'y' (float and float)");
}

TEST(AlgebraErrors, ConnectedOutputNotWrittenOnEveryPath) {
  Program b = program("b", [] {
    Input<Float3> y("y");
    Output<Float3> r("r");
    r = y;
  });
  auto a_with = [](auto&& write) {
    return program("a", [&] {
      Input<Float> x("x");
      Output<Float3> y("y");
      write(x, y);
    });
  };
  // Written in one branch only.
  Program one_branch = a_with([](Float& x, Float3& y) {
    RILL_IF(x > 0.0f) {
      y = Float3(x);
    }
    RILL_ENDIF;
  });
  int at = 0;
  std::string msg = error_of([&] { at = __LINE__, connect(one_branch, b); });
  EXPECT_HAS(msg, LOC(at));
  EXPECT_HAS(msg, "output 'y' (float3) of 'a' feeds 'b'");
  EXPECT_HAS(msg, "does not write component(s) xyz");
  EXPECT_HAS(msg, "previous value");
  // Some components only on every path.
  Program partial = a_with([](Float& x, Float3& y) {
    y(0, 2) = Float2(x);
    RILL_IF(x > 0.0f) {
      y(1) = x;
    }
    RILL_ENDIF;
  });
  EXPECT_HAS(error_of([&] { connect(partial, b); }), "does not write component(s) y");
  // Only in a while loop's body (which may run zero times).
  Program loop = a_with([](Float& x, Float3& y) {
    RILL_WHILE(x < 0.0f) {
      y = Float3(x);
      x += 1.0f;
    }
    RILL_ENDWHILE;
  });
  EXPECT_HAS(error_of([&] { connect(loop, b); }), "does not write component(s) xyz");
  // Only after a break that may leave a do-until loop first.
  Program broken = a_with([](Float& x, Float3& y) {
    RILL_DO {
      RILL_IF(x > 1.0f) {
        RILL_BREAK;
      }
      RILL_ENDIF;
      y = Float3(x);
      x += 1.0f;
    }
    RILL_UNTIL(x > 4.0f);
  });
  EXPECT_HAS(error_of([&] { connect(broken, b); }), "does not write component(s) xyz");

  // Accepted: every component on every path, however it is spread.
  Program both_branches = a_with([](Float& x, Float3& y) {
    y.x() = x;
    RILL_IF(x > 0.0f) {
      y(1, 2) = Float2(x);
    }
    RILL_ELSE {
      y(2, 1) = Float2(-x);
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(connect(both_branches, b).ir().inputs.size(), 1u);
  Program do_body = a_with([](Float& x, Float3& y) {
    RILL_DO {
      y = Float3(x);
      x += 1.0f;
    }
    RILL_UNTIL(x > 4.0f);
  });
  EXPECT_EQ(connect(do_body, b).ir().inputs.size(), 1u);
  // An output b does not read may stay unwritten on some paths: it keeps its stream's value,
  // as in a's own launch.
  Program sometimes = program("a", [] {
    Input<Float> x("x");
    Output<Float3> y("y");
    Output<Float> maybe("maybe");
    y = Float3(x);
    RILL_IF(x > 0.0f) {
      maybe = x;
    }
    RILL_ENDIF;
  });
  EXPECT_EQ(signature(connect(sometimes, b).ir(), connect(sometimes, b).ir().outputs),
            "r:float3 maybe:float");
}

TEST(AlgebraErrors, TwoUniformsWithOneName) {
  Uniform<Float> g1(1.0f), g2(2.0f);  // both called "uniform"
  Program a = program("a", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * g1;
  });
  Program b = program("b", [&] {
    Input<Float> y("y");
    Output<Float> r("r");
    r = y * g2;
  });
  std::string msg = error_of([&] { connect(a, b); });
  EXPECT_HAS(msg, "connect('a', 'b')");
  EXPECT_HAS(msg, "two different uniforms are named 'uniform'");
}

TEST(AlgebraErrors, EmptyProgram) {
  Program a = producer();
  EXPECT_HAS(error_of([&] { connect(Program(), a); }), "the first program is empty");
  EXPECT_HAS(error_of([&] { combine(a, Program()); }), "the second program is empty");
}

}  // namespace
}  // namespace rill
