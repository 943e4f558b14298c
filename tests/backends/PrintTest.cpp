// rill::print on every backend: the text is formatted on the host from raw bits, so every
// backend must print exactly the text a host reference builds from the same inputs (hence
// the same text on all of them), in element order, within the print limit.
#include <charconv>

#include "BackendTest.h"

namespace rill::testing {
namespace {

class PrintTest : public BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    old_ = set_print_output(nullptr);  // the tests read Kernel::last_print()
  }
  void TearDown() override { set_print_output(old_); }
  std::ostream* old_ = nullptr;
};

// The spelling of each float the tests print: the shortest decimal that reads back as the
// same binary32, written out by hand (not by the code under test).
struct Spelled {
  float value;
  const char* text;
};
const Spelled kFloats[] = {
    {0.1f, "0.1"},
    {-0.0f, "-0"},
    {1.5f, "1.5"},
    {1e10f, "1e+10"},
    {-3.25f, "-3.25"},
    {std::numeric_limits<float>::infinity(), "inf"},
    {16777216.0f, "16777216"},
    {0.3f, "0.3"},
    {-2.0f, "-2"},
};
constexpr size_t kSpelled = sizeof kFloats / sizeof kFloats[0];

// Every kind of argument (float, int, bool, a vector), element_index(), braces.
TEST_P(PrintTest, EveryBackendPrintsTheHostReferenceText) {
  Program p = program("printer", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    print("{{e{}}} x = {} twice = {} pos = {} v = {}", element_index(), x, x * 2.0f, x > 0.0f,
          Int2(element_index(), -element_index()));
    y = x;
  });
  const int64_t n = 12;
  std::vector<float> xs;
  for (int64_t i = 0; i < n; ++i) xs.push_back(kFloats[static_cast<size_t>(i) % kSpelled].value);
  Kernel k = compile(p);
  std::vector<float> y = run_kernel<Float>(k, n, xs);
  std::string want;
  for (int64_t i = 0; i < n; ++i) {
    const Spelled& s = kFloats[static_cast<size_t>(i) % kSpelled];
    // x * 2 of each value, spelled by hand too (doubling is exact).
    static const char* kTwice[] = {"0.2", "-0",       "3",   "2e+10", "-6.5",
                                   "inf", "33554432", "0.6", "-4"};
    want += "{e" + std::to_string(i) + "} x = " + s.text +
            " twice = " + kTwice[static_cast<size_t>(i) % kSpelled] +
            " pos = " + (s.value > 0.0f ? "true" : "false") + " v = (" + std::to_string(i) + ", " +
            std::to_string(-i) + ")\n";
  }
  EXPECT_EQ(k.last_print(), want);
  EXPECT_TRUE(bits_equal(y, xs));  // printing does not touch the kernel's results
}

// print_if prints where its condition holds; a print in a loop keeps the first run's values
// and says how many times it ran.
TEST_P(PrintTest, PrintIfAndPrintsInLoops) {
  Program p = program("loops", [] {
    Input<Int> n("n");
    Output<Int> y("y");
    Int acc = 0;
    Int i = 0;
    RILL_WHILE(i < n) {
      acc += i * 10 + 1;
      print("acc {}", acc);
      i += 1;
    }
    RILL_ENDWHILE;
    print_if(n == 2, "two at {}", element_index());
    y = acc;
  });
  std::vector<int32_t> ns = {0, 1, 3, 2, 0};
  Kernel k = compile(p);
  run_kernel<Int>(k, 5, ns);
  EXPECT_EQ(k.last_print(),
            "acc 1\n"
            "acc 1  [ran 3 times]\n"
            "acc 1  [ran 2 times]\n"
            "two at 3\n");
}

// Only the first print_limit() elements that print are shown, then one line counts the rest.
TEST_P(PrintTest, TheLimitBoundsTheElementsShown) {
  Program p = program("many", [] {
    Input<Int> x("x");
    Output<Int> y("y");
    print_if(x % 2 == 0, "even {}", x);
    y = x;
  });
  const int64_t n = 100;
  std::vector<int32_t> xs;
  for (int32_t i = 0; i < n; ++i) xs.push_back(i);
  Kernel k = compile(p);
  EXPECT_EQ(k.print_limit(), 16);  // the documented default (RILL_PRINT_LIMIT unset in tests)
  run_kernel<Int>(k, n, xs);
  std::string want;
  for (int i = 0; i < 16; ++i) want += "even " + std::to_string(2 * i) + "\n";
  // 50 even elements printed, 16 shown.
  want +=
      "[rill::print: 34 more element(s) of kernel 'many' printed; Kernel::print_limit or "
      "RILL_PRINT_LIMIT (now 16) shows more]\n";
  EXPECT_EQ(k.last_print(), want);
  k.print_limit(3);
  run_kernel<Int>(k, n, xs);
  EXPECT_EQ(k.last_print().substr(0, 21), "even 0\neven 2\neven 4\n");
  EXPECT_NE(k.last_print().find("47 more element(s)"), std::string::npos) << k.last_print();
  EXPECT_THROW(k.print_limit(-1), Error);
}

// A masked launch prints from the elements it ran only (the slots are fresh each launch).
TEST_P(PrintTest, AMaskedLaunchPrintsItsElementsOnly) {
  Program p = program("masked", [] {
    Input<Int> s("s");
    Output<Int> y("y");
    print("e{} s{}", element_index(), s);
    y = s;
  });
  Stream<Int> s(std::vector<int32_t>{1, 2, 1, 3, 2});
  Stream<Int> y(5);
  Kernel k = compile(p);
  k.inputs(s).outputs(y);
  k.execute();
  k.execute(where(s, 2));
  EXPECT_EQ(k.last_print(), "e1 s2\ne4 s2\n");
}

// A format whose placeholders do not match the arguments is refused where it is written.
TEST_P(PrintTest, AMismatchedFormatIsACaptureError) {
  const int line = __LINE__ + 4;
  try {
    program("bad", [] {
      Output<Float> y("y");
      print("{} and {}", Float(1.0f));
      y = 1.0f;
    });
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("PrintTest.cpp:" + std::to_string(line)), std::string::npos) << what;
    EXPECT_NE(what.find("2 placeholder(s) {} but 1 argument(s)"), std::string::npos) << what;
  }
  EXPECT_THROW(program("lone",
                       [] {
                         Output<Float> y("y");
                         print("x } y");
                         y = 1.0f;
                       }),
               Error);
}

// connect and combine do not fuse print slots yet: they refuse, naming the program.
TEST_P(PrintTest, FusingAPrintingProgramIsRefused) {
  Program a = program("talks", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    print("{}", x);
    y = x;
  });
  Program b = program("quiet", [] {
    Input<Float> y("y");
    Output<Float> z("z");
    z = y;
  });
  try {
    connect(a, b);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("'talks' uses rill::print"), std::string::npos)
        << e.what();
  }
}

// Prints take the launch's size from the kernel's own outputs: without one, a clear error.
TEST_P(PrintTest, AKernelWithoutOutputsOfItsOwnCannotPrint) {
  Program p = program("mute", [] { print("{}", element_index()); });
  Kernel k = compile(p);
  try {
    k.execute();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("kernel 'mute' has no output of its own"),
              std::string::npos)
        << e.what();
  }
}

RILL_BACKEND_TEST_SUITE(PrintTest);

}  // namespace
}  // namespace rill::testing
