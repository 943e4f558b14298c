// Capture: what IR each DSL construct records (Capture.h, Program.h, Parameters.h, Math.h).
#include <atomic>
#include <optional>
#include <thread>

#include "TestUtil.h"

namespace rill {
namespace {

using test::count_ops;
using test::normalized;

TEST(Capture, InterfaceIsDeclaredInOrder) {
  Program p = program("iface", [] {
    Input<Float> x("x");
    Input<Int3> n("n");
    Output<Float4> c("c");
    Output<Int> k("k");
    c = Float4(x, x, x, x);
    k = n.y();
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(p.name(), "iface");
  EXPECT_EQ(test::lines(p.print())[0],
            "kernel iface(in float x_0, in int3 n_1) -> (out float4 c_2, out int k_3)");
  ASSERT_EQ(f.inputs.size(), 2u);
  ASSERT_EQ(f.outputs.size(), 2u);
  EXPECT_EQ(f.var(f.inputs[1]).name, "n");
  EXPECT_EQ(f.var(f.inputs[1]).type, ir::int_type(3));
  EXPECT_EQ(f.var(f.inputs[1]).role, ir::VarRole::Input);
  EXPECT_EQ(f.var(f.inputs[1]).slot, 1);
  EXPECT_EQ(f.var(f.outputs[0]).role, ir::VarRole::Output);
  EXPECT_EQ(f.var(f.outputs[1]).slot, 1);
}

TEST(Capture, UnnamedInterfaceValuesAreNumbered) {
  Program p = program("", [] {
    Input<Float> a;
    Input<Float> b;
    Output<Float> y;
    y = a + b;
  });
  EXPECT_EQ(p.name(), "kernel");
  EXPECT_EQ(test::lines(p.print())[0],
            "kernel kernel(in float in0_0, in float in1_1) -> (out float out0_2)");
}

TEST(Capture, TheBodyRunsOnceAtDefinition) {
  int runs = 0;
  Program p = program("once", [&] {
    ++runs;
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
  });
  EXPECT_EQ(runs, 1);
  (void)p.print();
  (void)p.hash();
  EXPECT_EQ(runs, 1);
  EXPECT_FALSE(detail::in_program());
}

TEST(Capture, EachOperatorRecordsOneOperation) {
  Program p = program("arith", [] {
    Input<Float> x("x");
    Input<Float> z("z");
    Input<Float> w("w");
    Output<Float> y("y");
    y = x * z + w;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = mul(x_0, z_1)");
  EXPECT_LINE(text, "t# = add(t#, w_2)");
  EXPECT_LINE(text, "y_3 = copy(t#)");
  EXPECT_EQ(test::statements(p.ir()), 3) << text;
}

// Operators.h: "a value and a host scalar (which becomes a constant)".
TEST(Capture, HostScalarOperandIsAConstant) {
  Program p = program("scalar", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = mul(x_0, 2.0)");
  EXPECT_EQ(test::statements(p.ir()), 2) << text;
}

TEST(Capture, OperatorSpellings) {
  Program p = program("ops", [] {
    Input<Int> i("i");
    Input<Int> j("j");
    Input<Float> x("x");
    Output<Int> r("r");
    Output<Float> f("f");
    Int a = (i % j) & (i | j);
    Int b = (i ^ j) << (i >> j);
    Int c = ~(-a) / b;
    Bool t = ((i < j) && !(i >= j)) || ((i != j) == (i <= j));
    r = select(t, c, a - b * c) + abs(sign(i));
    f = floor(x) + ceil(x) + fract(x) + sqrt(x) + rsqrt(x) + exp(x) + log(x) + exp2(x) + log2(x) +
        sin(x) + cos(x) + tan(x) + atan(x) + pow(x, x) + atan2(x, x) + mod(x, x) + min(x, x) +
        max(x, x) + as_float(as_int(x)) + to_float(to_int(x));
  });
  const ir::Function& f = p.ir();
  for (ir::Op op : {ir::Op::Mod,
                    ir::Op::BitAnd,
                    ir::Op::BitOr,
                    ir::Op::BitXor,
                    ir::Op::Shl,
                    ir::Op::Shr,
                    ir::Op::BitNot,
                    ir::Op::Neg,
                    ir::Op::Div,
                    ir::Op::Lt,
                    ir::Op::And,
                    ir::Op::Not,
                    ir::Op::Ge,
                    ir::Op::Or,
                    ir::Op::Ne,
                    ir::Op::Eq,
                    ir::Op::Le,
                    ir::Op::Select,
                    ir::Op::Sub,
                    ir::Op::Abs,
                    ir::Op::Sign,
                    ir::Op::Floor,
                    ir::Op::Ceil,
                    ir::Op::Fract,
                    ir::Op::Sqrt,
                    ir::Op::Rsqrt,
                    ir::Op::Exp,
                    ir::Op::Log,
                    ir::Op::Exp2,
                    ir::Op::Log2,
                    ir::Op::Sin,
                    ir::Op::Cos,
                    ir::Op::Tan,
                    ir::Op::Atan,
                    ir::Op::Pow,
                    ir::Op::Atan2,
                    ir::Op::Min,
                    ir::Op::Max,
                    ir::Op::IntBitsToFloat,
                    ir::Op::FloatBitsToInt,
                    ir::Op::IntToFloat,
                    ir::Op::FloatToInt})
    EXPECT_EQ(count_ops(f, op), op == ir::Op::Mod ? 2 : 1) << ir::op_name(op);
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = mod(i_0, j_1)");
  EXPECT_LINE(text, "t# = bitnot(t#)");
  EXPECT_LINE(text, "t# = atan2(x_2, x_2)");
  EXPECT_LINE(text, "t# = float_bits_to_int(x_2)");
  EXPECT_EQ(test::problems(f), "");
}

TEST(Capture, ComparisonsGiveBoolVectors) {
  Program p = program("cmp", [] {
    Input<Float3> a("a");
    Input<Float3> b("b");
    Output<Float3> y("y");
    Bool3 lt = a < b;
    y = select(lt, a, b) + select(any(lt), a, b) + select(all(a == b), a, b);
  });
  const ir::Function& f = p.ir();
  bool found = false;
  ir::for_each_stmt(f.body, [&](const ir::Stmt& s) {
    if (s.kind == ir::StmtKind::Assign && s.op == ir::Op::Lt) {
      EXPECT_EQ(f.var(s.dst).type, ir::bool_type(3));
      found = true;
    }
  });
  EXPECT_TRUE(found);
  EXPECT_EQ(count_ops(f, ir::Op::Or), 2);   // any() of three components
  EXPECT_EQ(count_ops(f, ir::Op::And), 2);  // all()
  EXPECT_EQ(count_ops(f, ir::Op::Select), 3);
}

TEST(Capture, GeometryIsBuiltFromDocumentedOperations) {
  Program p = program("geom", [] {
    Input<Float3> a("a");
    Input<Float3> b("b");
    Output<Float3> y("y");
    Output<Float> l("l");
    y = cross(a, b) + normalize(a) + reflect(a, b) + lerp(a, b, 0.25f) + clamp(a, 0.0f, 1.0f);
    l = length(a) + distance(a, b) + dot(a, b);
  });
  const ir::Function& f = p.ir();
  EXPECT_EQ(count_ops(f, ir::Op::Cross), 1);
  // normalize (1), reflect (1), length (1), distance (1), dot (1)
  EXPECT_EQ(count_ops(f, ir::Op::Dot), 5);
  EXPECT_EQ(count_ops(f, ir::Op::Sqrt), 3);  // normalize, length, distance
  EXPECT_EQ(count_ops(f, ir::Op::Min), 1);   // clamp = min(max(x, lo), hi)
  EXPECT_EQ(count_ops(f, ir::Op::Max), 1);
  EXPECT_EQ(test::problems(f), "");
}

TEST(Capture, ElementIndexAndCoord) {
  Program p = program("where", [] {
    Output<Int> i("i");
    Output<Int2> c("c");
    i = element_index();
    c = element_coord();
  });
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "t# = element_index()");
  EXPECT_LINE(text, "t# = element_coord()");
  EXPECT_LINE(text, "var int2 t#");
}

// Host C++ runs once at definition time: loops unroll, ifs choose what code exists.
TEST(Capture, HostLoopsUnrollAndHostIfsSelectCode) {
  auto power = [](int n, bool bias) {
    return program("power", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      Float acc = 1.0f;
      for (int k = 0; k < n; ++k) acc = acc * x;
      if (bias) acc = acc + 1.0f;
      y = acc;
    });
  };
  Program p5 = power(5, false), p7 = power(7, true), p0 = power(0, false);
  EXPECT_EQ(count_ops(p5.ir(), ir::Op::Mul), 5);
  EXPECT_EQ(count_ops(p7.ir(), ir::Op::Mul), 7);
  EXPECT_EQ(count_ops(p0.ir(), ir::Op::Mul), 0);
  EXPECT_EQ(count_ops(p5.ir(), ir::Op::Add), 0);
  EXPECT_EQ(count_ops(p7.ir(), ir::Op::Add), 1);
  EXPECT_EQ(ir::count_loops(p7.ir().body), 0);
  EXPECT_NE(p5.hash(), p7.hash());
  EXPECT_EQ(p5.hash(), power(5, false).hash());
}

TEST(Capture, HostFunctionsComposeKernels) {
  auto smooth = [](const Float& t) { return t * t * (3.0f - 2.0f * t); };
  Program p = program("compose", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = smooth(smooth(x));
  });
  EXPECT_EQ(count_ops(p.ir(), ir::Op::Mul), 6);
  EXPECT_EQ(count_ops(p.ir(), ir::Op::Sub), 2);
}

TEST(Capture, UniformsAreRegisteredOncePerProgram) {
  Uniform<Float> gain(2.0f, "gain");
  Uniform<Float3> tint(glm::vec3(1.0f, 0.5f, 0.25f), "tint");
  auto make = [&] {
    return program("uni", [&] {
      Input<Float3> x("x");
      Output<Float3> y("y");
      Float3 a = x * gain;  // statements sequence the first uses: gain, then tint
      Float3 b = tint * gain;
      y = a + b - gain * tint(2, 1, 0);
    });
  };
  Program p = make();
  const ir::Function& f = p.ir();
  ASSERT_EQ(f.uniforms.size(), 2u);
  EXPECT_EQ(f.var(f.uniforms[0]).name, "gain");
  EXPECT_EQ(f.var(f.uniforms[0]).role, ir::VarRole::Uniform);
  EXPECT_EQ(f.var(f.uniforms[0]).slot, 0);
  EXPECT_EQ(f.var(f.uniforms[1]).type, ir::float_type(3));
  EXPECT_EQ(f.var(f.uniforms[1]).slot, 1);
  ASSERT_EQ(p.captured().uniforms.size(), 2u);
  EXPECT_EQ(p.captured().uniforms[0].get(), gain.ref().uniform.get());
  std::string text = p.print();
  EXPECT_EQ(test::count_occurrences(text, "uniform float gain_"), 1) << text;
  EXPECT_EQ(test::count_occurrences(text, "uniform float3 tint_"), 1) << text;
  // Another program registers the same uniform for itself.
  Program q = make();
  EXPECT_EQ(q.ir().uniforms.size(), 2u);
  EXPECT_EQ(p.hash(), q.hash());
  // The host value is not part of the program: changing it needs no new program.
  gain.set(3.0f);
  EXPECT_EQ(make().hash(), p.hash());
  EXPECT_EQ(gain.ref().uniform->bits[0], std::bit_cast<uint32_t>(3.0f));
}

TEST(Capture, UniformsUnusedByAProgramAreNotPartOfIt) {
  Uniform<Float> unused(1.0f, "unused");
  Program p = program("none", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x;
  });
  EXPECT_TRUE(p.ir().uniforms.empty());
  EXPECT_TRUE(p.captured().uniforms.empty());
}

TEST(Capture, ArraysAreRegisteredOncePerProgram) {
  Array<Float> table(std::vector<float>{1.0f, 2.0f, 3.0f}, "table");
  Array<Float3> grid(4, 3, "grid");
  Array<Int> vol(2, 2, 2, "vol");
  Program p = program("arrays", [&] {
    Input<Int> i("i");
    Output<Float3> y("y");
    Float t0 = table[i];
    Float t1 = table(i + 1);
    Float v = to_float(vol(i, i, i));
    Float3 g = grid(i, i);
    y = g * (t0 + t1 + v);
  });
  // Arrays are numbered in the order the canonical listing first reads them: each gather
  // just before the statement that needs it, operands left to right (g first), whatever
  // order C++ ran the body in.
  const ir::Function& f = p.ir();
  ASSERT_EQ(f.arrays.size(), 3u);
  EXPECT_EQ(f.arrays[0].name, "grid");
  EXPECT_EQ(f.arrays[0].dims, 2);
  EXPECT_EQ(f.arrays[0].elem, ir::float_type(3));
  EXPECT_EQ(f.arrays[1].name, "table");
  EXPECT_EQ(f.arrays[1].dims, 1);
  EXPECT_EQ(f.arrays[2].name, "vol");
  EXPECT_EQ(f.arrays[2].elem, ir::int_type(1));
  EXPECT_EQ(p.captured().arrays.size(), 3u);
  EXPECT_EQ(p.captured().arrays[0].get(), grid.state().get());
  EXPECT_EQ(p.captured().arrays[1].get(), table.state().get());
  EXPECT_EQ(p.captured().arrays[2].get(), vol.state().get());
  EXPECT_EQ(count_ops(f, ir::Op::Gather), 4);
  std::string text = normalized(p.print());
  EXPECT_LINE(text, "array2d float3 a0:grid");
  EXPECT_LINE(text, "array1d float a1:table");
  EXPECT_LINE(text, "array3d int a2:vol");
  EXPECT_LINE(text, "t# = gather a0:grid(i_0, i_0)");
  EXPECT_LINE(text, "t# = gather a1:table(i_0)");
  EXPECT_LINE(text, "t# = gather a2:vol(i_0, i_0, i_0)");
  EXPECT_EQ(test::problems(f), "");
}

TEST(Capture, AProgramCanBeDefinedInsideAnother) {
  std::optional<Program> inner;
  Program outer = program("outer", [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * x;
    inner = program("inner", [] {
      Input<Float> a("a");
      Output<Float> b("b");
      b = -a;
    });
    y = y + x;  // the outer program carries on where it was
  });
  EXPECT_EQ(count_ops(outer.ir(), ir::Op::Mul), 1);
  EXPECT_EQ(count_ops(outer.ir(), ir::Op::Add), 1);
  EXPECT_EQ(count_ops(outer.ir(), ir::Op::Neg), 0);
  ASSERT_TRUE(inner.has_value());
  EXPECT_EQ(count_ops(inner->ir(), ir::Op::Neg), 1);
  EXPECT_EQ(test::lines(inner->print())[0], "kernel inner(in float a_0) -> (out float b_1)");
}

TEST(Capture, ProgramsCanBeCapturedOnSeveralThreads) {
  auto make = [] {
    return program("threaded", [] {
      Input<Float> x("x");
      Output<Float> y("y");
      Float acc = x;
      for (int k = 0; k < 50; ++k) acc = acc * x + 1.0f;
      y = acc;
    });
  };
  uint64_t expected = make().hash();
  std::atomic<int> same{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&] {
      for (int k = 0; k < 10; ++k) same += make().hash() == expected;
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(same.load(), 40);
}

TEST(Capture, ProgramIrIsTheUnoptimizedCapture) {
  Program p = program("raw", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float unused = x * 3.0f;
    y = x;
  });
  EXPECT_EQ(count_ops(p.ir(), ir::Op::Mul), 1);  // dead code is still there
  EXPECT_TRUE(p.valid());
  EXPECT_FALSE(Program().valid());
  EXPECT_EQ(test::problems(p.ir()), "");
}

// ---- arrays with a shape and data -------------------------------------------------------------

TEST(ArrayShape, ConstructorsWithDataAndShapeLayXFastest) {
  std::vector<float> d2 = {0, 1, 2, 10, 11, 12};  // 3 x 2
  Array<Float> a2(3, 2, d2, "plane");
  EXPECT_EQ(a2.size(), 6);
  EXPECT_EQ(a2.download(), d2);
  EXPECT_EQ(a2.state()->dims, 2);
  EXPECT_EQ(a2.state()->shape[0], 3);
  EXPECT_EQ(a2.state()->shape[1], 2);
  std::vector<glm::ivec2> d3(2 * 3 * 4);
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 2; ++x)
        d3[static_cast<size_t>(x + 2 * (y + 3 * z))] = glm::ivec2(x + 10 * y, z);
  Array<Int2> a3(2, 3, 4, d3);
  EXPECT_EQ(a3.state()->dims, 3);
  EXPECT_EQ(a3.state()->shape[2], 4);
  EXPECT_EQ(a3.state()->name, "array");
  EXPECT_EQ(a3.download(), d3);
}

TEST(ArrayShape, DataOfTheWrongSizeIsAnErrorNamingTheShape) {
  std::vector<float> five(5);
  EXPECT_HAS(test::error_of([&] { Array<Float>(3, 2, five, "plane"); }),
             "array 'plane': 5 elements given for a 3 x 2 array, which holds 6");
  EXPECT_HAS(test::error_of([&] { Array<Float>(1, 2, 3, five, "vol"); }),
             "array 'vol': 5 elements given for a 1 x 2 x 3 array, which holds 6");
  EXPECT_HAS(test::error_of([&] { Array<Float>(0, 2, five, "empty"); }),
             "every dimension must be at least 1");
}

// ---- printing and names ----------------------------------------------------------------------

TEST(Capture, DumpAndStreamOperatorWriteTheIrText) {
  Program p = program("dumped", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x * 2.0f;
  });
  std::ostringstream dumped, streamed;
  p.dump(dumped);
  streamed << p;
  EXPECT_EQ(dumped.str(), p.print());
  EXPECT_EQ(streamed.str(), p.print());
  std::ostringstream empty;
  empty << Program();
  EXPECT_EQ(empty.str(), "(empty program)\n");
}

TEST(Capture, LabelNamesTheVariableBehindAValue) {
  Program p = program("labelled", [] {
    Input<Float3> v("v");
    Output<Float> y("y");
    Float d = dot(v, v);  // the temporary dot() made
    label(d, "len2");
    Float3 n = v;  // a local of its own
    label(n, "my n!");
    y = d + n.x();
  });
  const std::string text = p.print();
  EXPECT_HAS(text, "var float len2_");
  EXPECT_HAS(text, "var float3 my_n__");  // printers keep identifier characters
  EXPECT_EQ(test::count_matching(text, R"(len2_[0-9]+ = dot\(v_0, v_0\))"), 1);
  EXPECT_EQ(test::count_matching(text, R"(my_n__[0-9]+ = copy\(v_0\))"), 1);
}

TEST(Capture, LabelRefusesValuesWithoutAVariableOfTheirOwn) {
  const Float outside = 1.0f;
  Uniform<Float> gain(1.0f, "gain");
  EXPECT_HAS(test::error_of([&] {
               program("const", [&] {
                 Output<Float> y("y");
                 label(outside, "c");
                 y = outside;
               });
             }),
             "rill::label('c'): this value is a constant made outside any program");
  EXPECT_HAS(test::error_of([&] {
               program("uniform", [&] {
                 Output<Float> y("y");
                 label(gain, "g");
                 y = gain;
               });
             }),
             "rill::label('g'): a uniform keeps the name it was declared with ('gain')");
  EXPECT_HAS(test::error_of([&] {
               program("input", [&] {
                 Input<Float> x("x");
                 Output<Float> y("y");
                 label(x, "z");
                 y = x;
               });
             }),
             "rill::label('z'): input 'x' keeps the name it was declared with");
  EXPECT_HAS(test::error_of([&] {
               program("empty", [&] {
                 Output<Float> y("y");
                 Float t = 1.0f;
                 label(t, "");
                 y = t;
               });
             }),
             "rill::label: the name is empty");
  EXPECT_HAS(test::error_of([&] { label(outside, "c"); }), "this value is a constant");
}

TEST(CaptureCpu, LabelledNamesSurviveTheOptimizerIntoGeneratedCode) {
  Program p = program("names", [] {
    Input<Float4> v("v");
    Output<Float> y("y");
    Float s = v.x() + v.y();  // a temporary: keeps its own name
    label(s, "sum");
    Float4 d = v * 2.0f;  // an unnamed temporary
    Float4 z = d;         // a local copying it: copy propagation removes the local, and the
    label(z, "zed");      // temporary takes its name
    Float w = 0.0f;       // a local written twice survives as itself
    label(w, "acc");
    w += s * z.z();
    y = w;
  });
  Kernel k = compile(p, "cpu");
  const std::string ir = k.ir(), src = k.source();
  for (const char* name : {"sum_", "zed_", "acc_"}) {
    EXPECT_HAS(ir, name);
    EXPECT_HAS(src, name);
  }
  std::ostringstream dumped, streamed;
  k.dump(dumped);
  streamed << k;
  EXPECT_EQ(dumped.str(), k.ir());
  EXPECT_EQ(streamed.str(), k.ir());

  // The names change nothing computed.
  Stream<Float4> in(std::vector<glm::vec4>{{1, 2, 3, 4}, {-1, 0.5f, 2, 0}});
  Stream<Float> out(2);
  k.inputs(in).outputs(out);
  k.execute();
  EXPECT_EQ(out.download(), (std::vector<float>{18.0f, -2.0f}));
}

}  // namespace
}  // namespace rill
