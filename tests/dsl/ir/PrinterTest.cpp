// ir/Printer.h: the readable, complete text form of the IR.
#include "TestUtil.h"

namespace rill {
namespace {

using ir::Constant;
using ir::print_constant;

// Constants made outside any program are inlined as operands, which keeps the golden text
// below independent of how capture spells host scalars.
const Float kHalf = 0.5f;
const Int kZero = 0;
const Int kOne = 1;

Program golden_program(Uniform<Float>& gain, Array<Float3>& palette) {
  return program("golden", [&] {
    Input<Float2> c("c");
    Input<Int> n("n");
    Output<Float> y("y");
    Output<Float3> rgb("rgb");
    Float2 z = c;
    Int i = kZero;
    RILL_WHILE(i < n) {
      z(1) = z.x() * kHalf;
      i += kOne;
    }
    RILL_ENDWHILE;
    RILL_IF(z.y() > gain) {
      y = z.x();
    }
    RILL_ELSE {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    rgb = palette[i];
  });
}

TEST(Printer, GoldenProgram) {
  Uniform<Float> gain(1.0f, "gain");
  Array<Float3> palette(4, "palette");
  Program p = golden_program(gain, palette);
  const char* expected =
      R"(kernel golden(in float2 c_0, in int n_1) -> (out float y_2, out float3 rgb_3)
  uniform float gain_4
  array1d float3 a0:palette
  var float2 t5
  var int t6
  var bool t7
  var float t8
  var float t9
  var float t10
  var int t11
  var float t12
  var bool t13
  var float t14
  var float3 t15
  t5 = copy(c_0)
  t6 = copy(0)
  while {
    t7 = lt(t6, n_1)
    exit unless t7
    t8 = copy(t5.y)
    t9 = copy(t5.x)
    t10 = mul(t9, 0.5)
    t5.y = copy(t10)
    t11 = add(t6, 1)
    t6 = copy(t11)
  }
  t12 = copy(t5.y)
  t13 = gt(t12, gain_4)
  if t13 {
    t14 = copy(t5.x)
    y_2 = copy(t14)
  } else {
    discard
  }
  t15 = gather a0:palette(t6)
  rgb_3 = copy(t15)
)";
  EXPECT_EQ(p.print(), expected);
  EXPECT_EQ(ir::print(p.ir()), p.print());
  // Stable: printing again, or capturing the same program again, gives the same text.
  EXPECT_EQ(p.print(), p.print());
  EXPECT_EQ(golden_program(gain, palette).print(), p.print());
}

TEST(Printer, ConstantsPrintExactly) {
  auto f = [](float v) { return print_constant(Constant::of_float(v)); };
  EXPECT_EQ(f(0.0f), "0.0");
  EXPECT_EQ(f(-0.0f), "-0.0");
  EXPECT_EQ(f(1.0f), "1.0");
  EXPECT_EQ(f(0.1f), "0.1");  // shortest text that reads back as the same float
  EXPECT_EQ(f(0.3f), "0.3");
  EXPECT_EQ(f(0.1f + 0.2f), "0.3");
  EXPECT_EQ(f(1.0f / 3.0f), "0.33333334");
  EXPECT_EQ(f(16777216.0f), "16777216.0");
  EXPECT_EQ(f(1e20f), "1e+20");
  EXPECT_EQ(f(1e-45f), "1e-45");
  EXPECT_EQ(f(3.4028235e38f), "3.4028235e+38");
  EXPECT_EQ(f(std::numeric_limits<float>::infinity()), "inf");
  EXPECT_EQ(f(-std::numeric_limits<float>::infinity()), "-inf");
  EXPECT_EQ(f(std::bit_cast<float>(0x7fc12345u)), "nan(0x7fc12345)");  // payload kept
  EXPECT_EQ(f(std::bit_cast<float>(0xffc00000u)), "nan(0xffc00000)");
  EXPECT_EQ(print_constant(Constant::of_int(-7)), "-7");
  EXPECT_EQ(print_constant(Constant::of_int(std::numeric_limits<int32_t>::min())), "-2147483648");
  EXPECT_EQ(print_constant(Constant::of_bool(true)), "true");
  EXPECT_EQ(print_constant(Constant::of_bool(false)), "false");

  Constant v;
  v.type = ir::float_type(3);
  v.bits = {std::bit_cast<uint32_t>(1.0f), std::bit_cast<uint32_t>(-0.0f),
            std::bit_cast<uint32_t>(2.5f), 0};
  EXPECT_EQ(print_constant(v), "float3(1.0, -0.0, 2.5)");
  Constant b;
  b.type = ir::bool_type(2);
  b.bits = {1, 0, 0, 0};
  EXPECT_EQ(print_constant(b), "bool2(true, false)");
  Constant i;
  i.type = ir::int_type(4);
  i.bits = {1, 2, static_cast<uint32_t>(-3), 4};
  EXPECT_EQ(print_constant(i), "int4(1, 2, -3, 4)");
}

TEST(Printer, DistinctFloatBitsPrintDistinctly) {
  // The text is what the hash hashes: every float must have its own spelling.
  std::mt19937 rng(7);
  for (int k = 0; k < 20000; ++k) {
    uint32_t a = rng(), b = a ^ (1u << (rng() % 32));
    ASSERT_NE(print_constant(Constant::of_float(std::bit_cast<float>(a))),
              print_constant(Constant::of_float(std::bit_cast<float>(b))))
        << std::hex << a << " vs " << b;
  }
}

TEST(Printer, OperandsShowSwizzlesButNotIdentity) {
  ir::Function f;
  ir::VarId v = f.add_var(ir::float_type(4), ir::VarRole::Local, "v");
  ir::VarId s = f.add_var(ir::float_type(1));
  EXPECT_EQ(f.var_name(v), "v_0");
  EXPECT_EQ(f.var_name(s), "t1");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(v, ir::float_type(4))), "v_0");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(v, ir::ScalarKind::Float, {3, 2, 1, 0})),
            "v_0.wzyx");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(v, ir::ScalarKind::Float, {0, 1, 2})),
            "v_0.xyz");  // a prefix is not the whole variable
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(v, ir::ScalarKind::Float, {1})), "v_0.y");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(s, ir::float_type(1))), "t1");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_var(s, ir::ScalarKind::Float, {0, 0})), "t1.xx");
  EXPECT_EQ(ir::print_operand(f, ir::Operand::of_const(Constant::of_int(3))), "3");
}

TEST(Printer, NamesAreSanitizedAndUnique) {
  ir::Function f;
  ir::VarId a = f.add_var(ir::float_type(1), ir::VarRole::Local, "my var");
  ir::VarId b = f.add_var(ir::float_type(1), ir::VarRole::Local, "2x");
  ir::VarId c = f.add_var(ir::float_type(1), ir::VarRole::Local, "while");
  EXPECT_EQ(f.var_name(a), "my_var_0");
  EXPECT_EQ(f.var_name(b), "v2x_1");
  EXPECT_EQ(f.var_name(c), "while_2");  // the id suffix keeps keywords out
}

TEST(Printer, LoopsMasksAndBlocks) {
  Program p = program("loops", [] {
    Input<Float3> v("v");
    Output<Float3> y("y");
    y = v;
    RILL_DO {
      y(2, 0) = y(0, 2);
    }
    RILL_UNTIL(y.x() > y.z());
    RILL_FOR(Int i = kZero, i < kOne, i += kOne) {
      y(1) = y.x();
    }
    RILL_ENDFOR;
  });
  std::string text = test::normalized(p.print());
  // The unread copy(y_1.zx) is the read that y(2, 0) makes as a value; it stays before the
  // assignment it was recorded for.
  EXPECT_HAS(text, "  do {\n    t# = copy(y_1.zx)\n    t# = copy(y_1.xz)\n");
  EXPECT_HAS(text, "    y_1.zx = copy(t#)\n    until:\n");
  EXPECT_HAS(text, "    exit if t#\n  }\n");
  EXPECT_HAS(text, "  for {\n    t# = lt(t#, 1)\n    exit unless t#\n");
  EXPECT_HAS(text, "    step:\n    t# = add(t#, 1)\n    t# = copy(t#)\n  }\n");
  // A block prints on its own, at any indent.
  const ir::Stmt& loop = p.ir().body.back();
  EXPECT_EQ(test::normalized(ir::print(p.ir(), loop.step, 2)),
            "    t# = add(t#, 1)\n    t# = copy(t#)\n");
}

}  // namespace
}  // namespace rill
