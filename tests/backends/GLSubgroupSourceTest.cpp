// glsl-compute's lane groups as GL_KHR_shader_subgroup operations (backends/glsl/Subgroups.h),
// checked where the local GL driver cannot run them (Mesa 22's llvmpipe has no
// GL_KHR_shader_subgroup): the compute shader the emitter writes with DriverRules::subgroups
// uses the subgroup operations, requires their extensions, and compiles and links in
// glslang's GL front end; without it the shader keeps a group of one and uses none. What the
// operations compute is the GLSL the vulkan backend runs (GroupTest on lavapipe's subgroups of
// 8); on a GPU, GroupTest and the conformance suite run it through GL itself.
#include <string>

#include "BackendTest.h"
#include "glsl/GLSLEmitter.h"
#include "rill/passes/Passes.h"
#include "vulkan/SpirvCompiler.h"

namespace rill::testing {
namespace {

// Every lane-group op, some under divergent control flow, on every kind broadcast.
Program every_group_op() {
  return program("group_every_op", [] {
    Input<Int> v("v");
    Output<Int4> a("a"), b("b");
    Output<Float> c("c");
    Int lane = lane_index();
    a = Int4(group_size(), lane, group_min(v), group_max(v));
    Int inside = 0;
    RILL_IF(v % 3 != 0) {
      inside = group_sum(v) + group_count(v > 0);
    }
    RILL_ENDIF;
    Int4 bits = group_ballot(v > 0);
    Bool flag = group_broadcast(v > 5, (lane + 1) % group_size());
    b = Int4(inside, bits.x() ^ bits.w(),
             select(group_any(v > 50), Int(1), Int(0)) + select(group_all(v > -90), Int(2), Int(0)),
             group_broadcast(v, Int(0)) + select(flag, Int(4), Int(0)));
    c = group_broadcast(to_float(v) * 0.5f, lane ^ 1);
  });
}

std::string emit(const Program& p, Accuracy accuracy, bool subgroups) {
  glsl::DriverRules rules;
  rules.subgroups = subgroups;
  const ir::Function f = passes::optimize(p.ir(), PassOptions{}, accuracy);
  return glsl::emit_glsl_compute(f, accuracy, {0, 1, 2}, true, rules, false, 64).source;
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(GLSubgroupSource, SubgroupOperationsCompileInTheGLDialect) {
  for (Accuracy accuracy : {Accuracy::Strict, Accuracy::Fast}) {
    const std::string src = emit(every_group_op(), accuracy, true);
    SCOPED_TRACE(src);
    for (const char* ext :
         {"GL_KHR_shader_subgroup_vote : require", "GL_KHR_shader_subgroup_arithmetic : require",
          "GL_KHR_shader_subgroup_shuffle : require"})
      EXPECT_TRUE(has(src, ext)) << ext;
    for (const char* op : {"gl_SubgroupSize", "gl_SubgroupInvocationID", "subgroupAny(",
                           "subgroupAll(", "subgroupBallot(", "subgroupBallotBitCount(",
                           "subgroupMin(", "subgroupMax(", "subgroupAdd(", "subgroupShuffle("})
      EXPECT_TRUE(has(src, op)) << op;
    EXPECT_EQ(vk::gl_compute_errors(src), "");
  }
}

TEST(GLSubgroupSource, WithoutSubgroupsTheGroupIsOneInvocation) {
  const std::string src = emit(every_group_op(), Accuracy::Strict, false);
  SCOPED_TRACE(src);
  for (const char* op : {"gl_SubgroupSize", "gl_SubgroupInvocationID", "subgroupAny(",
                         "subgroupMin(", "subgroupAdd(", "subgroupShuffle(", ": require"})
    EXPECT_FALSE(has(src, op)) << op;
  EXPECT_EQ(vk::gl_compute_errors(src), "");
}

// The check itself rejects what a GL driver would: a subgroup operation without its extension.
TEST(GLSubgroupSource, TheFrontEndRejectsAMissingExtension) {
  std::string src = emit(every_group_op(), Accuracy::Strict, true);
  const std::string line = "#extension GL_KHR_shader_subgroup_arithmetic : require\n";
  const size_t at = src.find(line);
  ASSERT_NE(at, std::string::npos);
  src.erase(at, line.size());
  const std::string log = vk::gl_compute_errors(src);
  EXPECT_TRUE(has(log, "required extension not requested: GL_KHR_shader_subgroup_arithmetic"))
      << log;
}

}  // namespace
}  // namespace rill::testing
