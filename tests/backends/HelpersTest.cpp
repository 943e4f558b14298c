// Every HELPER form of the op table (dsl/include/rill/ir/Ops.def) has a body in each dialect's
// kernels. The bodies are entries of one table, backends/codegen/Helpers.cpp (C, which OpenCL
// C shares unless it has its own; GLSL, in variants for each division and square-root rule;
// lockstep C, whose emitter generates a lane-wise wrapper for an entry without vector code),
// and each emitter assembles its prelude from it. Each dialect's check reads the source its
// emitter generates for a small kernel, in every accuracy mode it has (and for GLSL under
// every driver rule). An op added without its helper's entry, or an entry without a body a
// dialect needs, fails here, naming the op and the dialect, rather than in a driver's
// compiler on some backend.
#include <gtest/gtest.h>

#include <functional>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "codegen/Helpers.h"
#include "cpu/CEmitter.h"
#include "rill/ir/Ops.h"
#include "rill/rill.h"
#include "simd/LockstepEmitter.h"
#ifdef RILL_HAVE_OPENCL
#include "opencl/OpenCLEmitter.h"
#endif
#ifdef RILL_HAVE_GLSL
#include "glsl/GLSLEmitter.h"
#endif

namespace rill {
namespace {

// Whether text defines function `name`: a line "[RILL_FN] TYPE name(" (a call has no type
// before it, or follows '=' or 'return').
bool defines(const std::string& text, const std::string& name) {
  const std::regex def("(^|\\n)[ \\t]*(RILL_FN[ \\t]+)?(?!return\\b)[A-Za-z_][A-Za-z_0-9]*[ \\t]+" +
                       name + "[ \\t]*\\(");
  return std::regex_search(text, def);
}

// A kernel for the emitters to print: its source carries the dialect's whole prelude, and the
// on-demand helpers (codegen::Helper::on_demand), since it calls them.
const ir::Function& probe() {
  static const Program p = program("helpers_probe", [] {
    Output<Float> o("o");
    Int i = element_index();
    o = unit_float(shr_logical(mul_hi_unsigned(i, i), i));
  });
  return p.ir();
}
// A kernel that calls none of the on-demand helpers.
const ir::Function& plain() {
  static const Program p = program("helpers_plain", [] {
    Output<Float> o("o");
    o = 1.0f;
  });
  return p.ir();
}

// The rill_NAME of every HELPER form, with the op it belongs to.
struct Helper {
  std::string name, op;
};
std::vector<Helper> table_helpers() {
  std::vector<Helper> out;
  for (int o = 0; o < ir::kOpCount; ++o) {
    const ir::OpInfo& info = ir::op_info(static_cast<ir::Op>(o));
    for (ir::ScalarKind k : {ir::ScalarKind::Float, ir::ScalarKind::Int, ir::ScalarKind::Bool}) {
      const ir::OpForm& f = info.form(k);
      if (f.kind == ir::FormKind::Helper) out.push_back({f.text, info.spelling});
    }
  }
  return out;
}

TEST(Helpers, TheTableHasHelpers) {
  EXPECT_GT(table_helpers().size(), 20u);
  EXPECT_TRUE(defines("RILL_FN int32_t rill_x(int32_t a) {", "rill_x"));
  EXPECT_TRUE(defines("float rill_x(float a) {", "rill_x"));
  EXPECT_FALSE(defines("  return rill_x(a);", "rill_x"));
  EXPECT_FALSE(defines("  int y = rill_x(a);", "rill_x"));
}

// One home: an entry a helper, so a body is never defined, or changed, in two places.
TEST(Helpers, EachHelperHasOneEntry) {
  std::set<std::string> seen;
  for (const codegen::Helper& h : codegen::helper_table())
    EXPECT_TRUE(seen.insert(h.name).second) << "rill_" << h.name << ": two entries in the table";
}

// An on-demand helper is defined in the kernels that call it and in no other, so that adding
// one leaves every other kernel's source, and its cache entries, as they were.
TEST(Helpers, OnDemandHelpersOnlyWhereCalled) {
  std::vector<std::pair<std::string, std::function<std::string(const ir::Function&)>>> dialects = {
      {"C", [](const ir::Function& f) { return cpu::emit_c(f, Accuracy::Strict); }},
      {"lockstep C",
       [](const ir::Function& f) { return simd::emit_c_lockstep(f, Accuracy::Strict); }}};
#ifdef RILL_HAVE_OPENCL
  dialects.push_back(
      {"OpenCL C", [](const ir::Function& f) { return opencl::emit_opencl(f, Accuracy::Strict); }});
#endif
#ifdef RILL_HAVE_GLSL
  dialects.push_back({"GLSL", [](const ir::Function& f) {
                        return glsl::glsl_helpers(f, Accuracy::Strict, glsl::DriverRules{}, true);
                      }});
#endif
  int on_demand = 0;
  for (const codegen::Helper& h : codegen::helper_table()) {
    if (!h.on_demand) continue;
    ++on_demand;
    for (const auto& [name, emit] : dialects) {
      EXPECT_TRUE(defines(emit(probe()), "rill_" + std::string(h.name)))
          << "rill_" << h.name << " not defined in a " << name << " kernel that calls it";
      EXPECT_FALSE(defines(emit(plain()), "rill_" + std::string(h.name)))
          << "rill_" << h.name << " defined in a " << name << " kernel that does not call it";
    }
  }
  EXPECT_EQ(on_demand, 3);  // shr_u, mul_hi_u, unit_f
}

TEST(Helpers, EveryHelperHasACBody) {
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast, Accuracy::Double}) {
    const std::string text = cpu::emit_c(probe(), a);
    for (const Helper& h : table_helpers())
      EXPECT_TRUE(defines(text, "rill_" + h.name))
          << "op '" << h.op << "': no rill_" << h.name << " in C (" << accuracy_name(a) << ")";
  }
}

#ifdef RILL_HAVE_OPENCL
TEST(Helpers, EveryHelperHasAnOpenCLBody) {
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast, Accuracy::Double}) {
    const std::string text = opencl::emit_opencl(probe(), a);
    for (const Helper& h : table_helpers())
      EXPECT_TRUE(defines(text, "rill_" + h.name)) << "op '" << h.op << "': no rill_" << h.name
                                                   << " in OpenCL C (" << accuracy_name(a) << ")";
  }
}
#endif

TEST(Helpers, EveryHelperHasALockstepBody) {
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast}) {
    const std::string text = simd::emit_c_lockstep(probe(), a);
    for (const Helper& h : table_helpers()) {
      const std::string v = "rill_v_" + h.name;
      EXPECT_TRUE(defines(text, v) || text.find("(" + v + ",") != std::string::npos)
          << "op '" << h.op << "': no " << v << " in lockstep C (" << accuracy_name(a) << ")";
    }
  }
}

#ifdef RILL_HAVE_GLSL
TEST(Helpers, EveryHelperHasAGlslBodyUnderEveryDriverRule) {
  for (Accuracy a : {Accuracy::Strict, Accuracy::Fast})
    for (glsl::DivSqrt ds : {glsl::DivSqrt::Native, glsl::DivSqrt::Corrected,
                             glsl::DivSqrt::Inexact, glsl::DivSqrt::InexactCorrected})
      for (bool flushes : {false, true})
        for (bool fused : {false, true})
          for (bool lean : {false, true}) {
            glsl::DriverRules rules;
            rules.divsqrt = ds;
            rules.fused_fma = fused;
            rules.lean = lean;
            const std::string text = glsl::glsl_helpers(probe(), a, rules, flushes);
            for (const Helper& h : table_helpers())
              EXPECT_TRUE(defines(text, "rill_" + h.name))
                  << "op '" << h.op << "': no rill_" << h.name << " in the GLSL prelude ("
                  << accuracy_name(a) << ")";
          }
}

// The corrections' residual is one fma exactly when the rule says the driver's fma is fused,
// and a shader never gets both residuals (they define the same function).
TEST(Helpers, TheCorrectionsResidualFollowsTheFmaRule) {
  for (bool fused : {false, true}) {
    glsl::DriverRules rules;
    rules.divsqrt = glsl::DivSqrt::Corrected;
    rules.fused_fma = fused;
    rules.lean = false;
    const std::string text = glsl::glsl_helpers(probe(), Accuracy::Strict, rules, true);
    EXPECT_EQ(text.find("fma(-q, b, a)") != std::string::npos, fused);
    EXPECT_EQ(text.find("4097.0 * q") != std::string::npos, !fused);
  }
  glsl::DriverRules native;
  native.fused_fma = true;
  EXPECT_EQ(glsl::glsl_helpers(probe(), Accuracy::Strict, native, true).find("rill_residual"),
            std::string::npos);
}

// The lean correction (glsl/lean/*.glsl) only with a fused fma, in place of the residual's
// steps: each of rill_div_f and rill_sqrt defined once, no residual, no second driver
// division; the split rule keeps its steps whatever RILL_GLSL_FUSED says.
TEST(Helpers, TheLeanCorrectionNeedsAFusedFma) {
  for (glsl::DivSqrt ds : {glsl::DivSqrt::Corrected, glsl::DivSqrt::InexactCorrected})
    for (bool fused : {false, true}) {
      glsl::DriverRules rules;
      rules.divsqrt = ds;
      rules.fused_fma = fused;
      rules.lean = true;
      const std::string text = glsl::glsl_helpers(probe(), Accuracy::Strict, rules, true);
      EXPECT_EQ(text.find("RILL_PRECISE float q1 = fma(d0, r, q0);") != std::string::npos, fused);
      EXPECT_EQ(text.find("rill_native_rsqrt(m)") != std::string::npos, fused);
      EXPECT_EQ(text.find("rill_residual") == std::string::npos, fused);
      for (const char* f : {"float rill_div_f(", "float rill_sqrt("}) {
        const size_t first = text.find(f);
        ASSERT_NE(first, std::string::npos) << f;
        EXPECT_EQ(text.find(f, first + 1), std::string::npos) << f << " defined twice";
      }
    }
}
#endif

}  // namespace
}  // namespace rill
