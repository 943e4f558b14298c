// The conformance suite (conformance/) as tests: one test per backend, accuracy mode and part
// of the suite, named "<Part>/<backend>_<mode>" and labelled with the backend in CTest, so
// `ctest -L opencl` runs the OpenCL backend's share.
//
// A backend that cannot run here, or a mode it does not have (double on GLSL), is skipped
// with the reason. A failing test prints the rows that failed: the operation, the first
// mismatching inputs with what the backend gave and what the reference expects.
#include <gtest/gtest.h>
#include <rill/rill.h>

#include <ostream>
#include <string>
#include <vector>

#include "Conformance.h"
#include "ParamName.h"

namespace {

struct Param {
  std::string backend;
  rill::Accuracy accuracy;
};

// How CTest shows the parameter (gtest_discover_tests keeps it in the test's name).
void PrintTo(const Param& p, std::ostream* os) {
  *os << p.backend << " " << rill::accuracy_name(p.accuracy);
}

std::vector<Param> params() {
  std::vector<Param> v;
  for (rill::Backend* b : rill::backends())
    for (rill::Accuracy a : {rill::Accuracy::Strict, rill::Accuracy::Fast, rill::Accuracy::Double})
      v.push_back({b->name(), a});
  return v;
}

// Compiled kernels hold GL objects: release them while the GL context still exists rather
// than from static destructors at exit.
class ReleaseKernels : public ::testing::Environment {
 public:
  void TearDown() override { rill::clear_kernel_cache(); }
};
const auto* const kReleaseKernels = ::testing::AddGlobalTestEnvironment(new ReleaseKernels);

class Conformance : public ::testing::TestWithParam<Param> {
 protected:
  // Runs the named cases (or a part of the suite) and fails for every row that fails.
  void check(rill::conformance::Options o) {
    const Param& p = GetParam();
    rill::conformance::Report r = rill::conformance::run(p.backend, p.accuracy, o);
    if (r.skipped)
      GTEST_SKIP() << p.backend << " " << rill::accuracy_name(p.accuracy) << ": " << r.skip_reason;
    std::cout << rill::conformance::summary({r});
    if (r.flushes_denormals) std::cout << "  denormals: " << r.denormal_probe << "\n";
    for (const auto& row : r.rows) {
      if (row.status != rill::conformance::Status::Fail &&
          row.status != rill::conformance::Status::Error)
        continue;
      ADD_FAILURE() << p.backend << " " << row.accuracy << " " << row.op << ": "
                    << rill::conformance::status_name(row.status) << ", " << row.mismatches
                    << " of " << row.elements << " outside the contract"
                    << (row.max_ulp >= 0 ? ", max " + std::to_string(row.max_ulp) + " ulp" : "")
                    << (row.bound >= 0 ? " (bound " + std::to_string(row.bound) + ")" : "")
                    << "\n  " << row.note;
    }
  }
  void cases(std::vector<std::string> names) {
    rill::conformance::Options o;
    o.cases = std::move(names);
    o.specials = false;
    check(o);
  }
};

TEST_P(Conformance, FloatArithmetic) {
  cases({"float_unary", "float_binary"});
}

TEST_P(Conformance, Transcendental) {
  cases({"exp", "exp2", "log", "log2", "sin", "cos", "tan", "atan", "pow", "atan2"});
}

TEST_P(Conformance, IntegerBoolCompare) {
  cases({"int_unary", "int_arith", "int_bits", "compare_float", "compare_int", "bool"});
}

TEST_P(Conformance, SelectSwizzleConvert) {
  cases({"select", "swizzle", "convert"});
}

TEST_P(Conformance, Geometry) {
  cases({"geometry", "optics"});
}

TEST_P(Conformance, ControlFlow) {
  rill::conformance::Options o;
  o.operations = false;
  o.specials = false;
  check(o);
}

TEST_P(Conformance, HardInputs) {
  rill::conformance::Options o;
  o.operations = false;
  o.control = false;
  check(o);
}

// Fast-mode bounds follow the driver, not only the backend: the drivers the bounds were
// measured on get those, any other driver (NVIDIA's OpenCL, ...) the documented contract.
TEST(FastBounds, MeasuredDriversAndOthers) {
  using rill::conformance::fast_bound;
  const std::string pocl = "opencl: Portable Computing Language / pthread-haswell";
  const std::string nvidia = "opencl: NVIDIA CUDA / NVIDIA H200 (OpenCL 3.0 CUDA)";
  const std::string llvmpipe = "glsl: osmesa, llvmpipe (LLVM 15.0.6, 256 bits)";
  const std::string nvidia_gl = "glsl: egl, NVIDIA H200/PCIe/SSE2, OpenGL 4.3.0 NVIDIA";
  EXPECT_TRUE(rill::conformance::measured_driver("opencl", pocl));
  EXPECT_FALSE(rill::conformance::measured_driver("opencl", nvidia));
  EXPECT_TRUE(rill::conformance::measured_driver("glsl", llvmpipe));
  EXPECT_FALSE(rill::conformance::measured_driver("glsl", nvidia_gl));
  for (const char* op : {"exp", "sin", "tan", "atan2"}) {
    EXPECT_LT(fast_bound(op, "opencl", pocl), fast_bound(op, "opencl", nvidia)) << op;
    EXPECT_LT(fast_bound(op, "glsl", llvmpipe), fast_bound(op, "glsl", nvidia_gl)) << op;
  }
  // sin and cos: OpenCL relaxed math and Vulkan allow an absolute error of 2^-11 on [-pi, pi]
  // (the measure is in units of 2^-23 there).
  EXPECT_EQ(fast_bound("sin", "opencl", nvidia), 4096);
  EXPECT_EQ(fast_bound("cos", "glsl", nvidia_gl), 4096);
  // Exact and correctly rounded operations stay so on every driver.
  EXPECT_EQ(fast_bound("floor", "opencl", nvidia), 0);
  EXPECT_EQ(fast_bound("add", "glsl", nvidia_gl), 0.5);
}

INSTANTIATE_TEST_SUITE_P(Suite, Conformance, ::testing::ValuesIn(params()),
                         [](const ::testing::TestParamInfo<Param>& info) {
                           return rill::testing::param_name(info.param.backend) + "_" +
                                  rill::accuracy_name(info.param.accuracy);
                         });

}  // namespace
