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

INSTANTIATE_TEST_SUITE_P(Suite, Conformance, ::testing::ValuesIn(params()),
                         [](const ::testing::TestParamInfo<Param>& info) {
                           return info.param.backend + "_" +
                                  rill::accuracy_name(info.param.accuracy);
                         });

}  // namespace
