// ir/Hash.h: a stable hash of the IR, the kernel caches' key.
#include "TestUtil.h"

namespace rill {
namespace {

// y = (x op c) * x, with the op and the constant as parameters.
Program shaped(const std::string& name, int op, float c) {
  return program(name, [&] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float k = c;
    Float t = op == 0 ? x + k : op == 1 ? x - k : op == 2 ? min(x, k) : max(x, k);
    y = t * x;
  });
}

TEST(Hash, FnvOfBytesIsTheStandardFnv1a) {
  EXPECT_EQ(ir::hash_bytes(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(ir::hash_bytes("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(ir::hash_bytes("foobar"), 0x85944171f73967e8ull);
  EXPECT_EQ(ir::hex(0x1234ull), "0000000000001234");
  EXPECT_EQ(ir::hex(0xaf63dc4c8601ec8cull), "af63dc4c8601ec8c");
}

TEST(Hash, TheSameProgramDefinedTwiceHashesTheSame) {
  Program a = shaped("k", 0, 2.0f), b = shaped("k", 0, 2.0f);
  EXPECT_EQ(a.hash(), b.hash());
  EXPECT_EQ(a.hash(), ir::hash(a.ir()));
  ir::Function copy = a.ir();  // a deep copy, elsewhere in memory
  EXPECT_EQ(ir::hash(copy), a.hash());
}

TEST(Hash, RenamingTheKernelDoesNotChangeIt) {
  EXPECT_EQ(shaped("first", 0, 2.0f).hash(), shaped("second", 0, 2.0f).hash());
  EXPECT_EQ(shaped("k", 1, 2.0f).hash(), shaped("a much longer kernel name", 1, 2.0f).hash());
}

TEST(Hash, RenamingTheKernelDoesNotChangeItWhateverTheName) {
  EXPECT_EQ(shaped("plain", 0, 2.0f).hash(), shaped("with (parens)", 0, 2.0f).hash());
}

TEST(Hash, AChangedConstantChangesIt) {
  uint64_t base = shaped("k", 0, 2.0f).hash();
  EXPECT_NE(base, shaped("k", 0, 2.5f).hash());
  EXPECT_NE(base, shaped("k", 0, std::nextafter(2.0f, 3.0f)).hash());
  EXPECT_NE(shaped("k", 0, 0.0f).hash(), shaped("k", 0, -0.0f).hash());
  EXPECT_NE(shaped("k", 0, std::bit_cast<float>(0x7fc00001u)).hash(),
            shaped("k", 0, std::bit_cast<float>(0x7fc00002u)).hash());
}

TEST(Hash, AChangedOpChangesIt) {
  uint64_t add = shaped("k", 0, 2.0f).hash(), sub = shaped("k", 1, 2.0f).hash(),
           mn = shaped("k", 2, 2.0f).hash(), mx = shaped("k", 3, 2.0f).hash();
  EXPECT_NE(add, sub);
  EXPECT_NE(add, mn);
  EXPECT_NE(mn, mx);
  EXPECT_NE(sub, mx);
}

TEST(Hash, OperandOrderSwizzlesMasksAndTypesMatter) {
  auto sub = [](bool swap) {
    return program("s", [&] {
      Input<Float> x("x");
      Input<Float> z("z");
      Output<Float> y("y");
      y = swap ? z - x : x - z;
    });
  };
  EXPECT_NE(sub(false).hash(), sub(true).hash());

  auto swz = [](int a) {
    return program("w", [&] {
      Input<Float3> v("v");
      Output<Float3> y("y");
      y = v;
      y(a) = v.y();
    });
  };
  EXPECT_NE(swz(0).hash(), swz(2).hash());

  auto kind = [](bool as_int) {
    return program("t", [&] {
      Input<Int> n("n");
      Output<Float> y("y");
      y = as_int ? as_float(n) : to_float(n);
    });
  };
  EXPECT_NE(kind(false).hash(), kind(true).hash());
}

TEST(Hash, ControlFlowStructureMatters) {
  auto loop = [](int which) {
    return program("l", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = x;
      if (which == 0) {
        RILL_WHILE(y > 1.0f) {
          y = y * 0.5f;
        }
        RILL_ENDWHILE;
      } else if (which == 1) {
        RILL_DO {
          y = y * 0.5f;
        }
        RILL_UNTIL(y > 1.0f);
      } else {
        RILL_IF(y > 1.0f) {
          y = y * 0.5f;
        }
        RILL_ENDIF;
      }
    });
  };
  EXPECT_NE(loop(0).hash(), loop(1).hash());
  EXPECT_NE(loop(0).hash(), loop(2).hash());
  EXPECT_NE(loop(1).hash(), loop(2).hash());
}

TEST(Hash, InterfaceMatters) {
  auto iface = [](bool wide) {
    return program("i", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      if (wide) {
        Output<Float> z("z");
        z = x;
      }
      y = x;
    });
  };
  EXPECT_NE(iface(false).hash(), iface(true).hash());
  Uniform<Float> u(1.0f, "u");
  Uniform<Int> ui(1, "u");
  auto uni = [&](bool as_int) {
    return program("u", [&] {
      Input<Float> x("x");
      Output<Float> y("y");
      y = as_int ? x * to_float(ui) : x * u;
    });
  };
  EXPECT_NE(uni(false).hash(), uni(true).hash());
}

// Two arrays may share a name (the default name is "array"); programs gathering from
// different ones must not hash alike, or the kernel cache hands one the other's code.
TEST(Hash, GathersFromDifferentArraysWithTheSameName) {
  Array<Float> a(std::vector<float>{1.0f, 2.0f});
  Array<Float> b(std::vector<float>{10.0f, 20.0f});
  auto make = [&](bool last_from_a) {
    return program("g", [&] {
      Input<Int> i("i");
      Output<Float> y("y");
      Float first = a[i];
      Float second = b[i];
      Int j = i + 1;
      Float third = last_from_a ? a[j] : b[j];
      y = first + second + third;
    });
  };
  auto last_gather = [](const Program& p) {
    int array = -1;
    ir::for_each_stmt(p.ir().body, [&](const ir::Stmt& s) {
      if (s.kind == ir::StmtKind::Assign && s.op == ir::Op::Gather) array = s.array;
    });
    return array;
  };
  Program pa = make(true), pb = make(false);
  EXPECT_EQ(last_gather(pa), 0);
  EXPECT_EQ(last_gather(pb), 1);
  EXPECT_NE(pa.print(), pb.print()) << "the printed IR is documented to be complete";
  EXPECT_NE(pa.hash(), pb.hash());
}

}  // namespace
}  // namespace rill
