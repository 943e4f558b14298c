// glsl-compute's choice of lane groups (backends/glsl/Subgroups.h) from what a GL driver
// answers, on drivers made up here: the real one on this machine (Mesa 22.3's llvmpipe) has
// no GL_KHR_shader_subgroup, so the answers a GPU gives (NVIDIA: every stage, every feature,
// 32 invocations) and the ways one can fall short are played by a fake GL whose queries
// return them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "glsl/Subgroups.h"

namespace rill::glsl {
namespace {

constexpr GLint kAllFeatures =
    GL_SUBGROUP_FEATURE_BASIC_BIT_KHR | GL_SUBGROUP_FEATURE_VOTE_BIT_KHR |
    GL_SUBGROUP_FEATURE_ARITHMETIC_BIT_KHR | GL_SUBGROUP_FEATURE_BALLOT_BIT_KHR |
    GL_SUBGROUP_FEATURE_SHUFFLE_BIT_KHR | GL_SUBGROUP_FEATURE_CLUSTERED_BIT_KHR |
    GL_SUBGROUP_FEATURE_QUAD_BIT_KHR;

// The fake driver's answers (one test at a time reads them).
struct Answers {
  std::vector<std::string> extensions = {"GL_ARB_compute_shader", "GL_KHR_shader_subgroup"};
  GLint size = 32;
  GLint stages = GL_VERTEX_SHADER_BIT | GL_FRAGMENT_SHADER_BIT | GL_COMPUTE_SHADER_BIT;
  GLint features = kAllFeatures;
  bool refuses = false;  // the subgroup queries raise GL_INVALID_ENUM
};
Answers answers;
GLenum pending = GL_NO_ERROR;

GL fake_gl() {
  GL gl;
  gl.glGetIntegerv = [](GLenum e, GLint* v) {
    if (e == GL_NUM_EXTENSIONS) {
      *v = static_cast<GLint>(answers.extensions.size());
    } else if (answers.refuses) {
      pending = GL_INVALID_ENUM;
    } else if (e == GL_SUBGROUP_SIZE_KHR) {
      *v = answers.size;
    } else if (e == GL_SUBGROUP_SUPPORTED_STAGES_KHR) {
      *v = answers.stages;
    } else if (e == GL_SUBGROUP_SUPPORTED_FEATURES_KHR) {
      *v = answers.features;
    } else {
      pending = GL_INVALID_ENUM;
    }
  };
  gl.glGetStringi = [](GLenum e, GLuint i) -> const GLubyte* {
    if (e != GL_EXTENSIONS || i >= answers.extensions.size()) return nullptr;
    return reinterpret_cast<const GLubyte*>(answers.extensions[i].c_str());
  };
  gl.glGetError = []() -> GLenum {
    const GLenum e = pending;
    pending = GL_NO_ERROR;
    return e;
  };
  return gl;
}

GLSubgroups ask(const Answers& a) {
  answers = a;
  pending = GL_NO_ERROR;
  const GL gl = fake_gl();
  return query_subgroups(gl);
}

TEST(GLSubgroupQuery, AGPUsSubgroupsAreUsed) {
  const GLSubgroups s = ask(Answers{});
  EXPECT_TRUE(s.usable) << s.why_not;
  EXPECT_EQ(s.size, 32);
  EXPECT_EQ(lane_groups_text(s, true), "subgroups of 32");
  EXPECT_EQ(lane_groups_text(s, false), "one element (RILL_GLSL_SUBGROUPS=off)");
  Answers wide;
  wide.size = 128;  // the ballot's width: still fits
  EXPECT_TRUE(ask(wide).usable);
}

TEST(GLSubgroupQuery, EachMissingPieceKeepsOneElementAndSaysWhy) {
  Answers none;
  none.extensions = {"GL_ARB_shader_ballot", "GL_ARB_shader_group_vote"};  // Mesa 22.3's llvmpipe
  GLSubgroups s = ask(none);
  EXPECT_FALSE(s.usable);
  EXPECT_EQ(lane_groups_text(s, false), "one element (the driver lacks GL_KHR_shader_subgroup)");

  Answers fragment_only;
  fragment_only.stages = GL_FRAGMENT_SHADER_BIT;
  s = ask(fragment_only);
  EXPECT_FALSE(s.usable);
  EXPECT_NE(s.why_not.find("not in compute shaders"), std::string::npos) << s.why_not;

  for (GLint missing : {GL_SUBGROUP_FEATURE_BASIC_BIT_KHR, GL_SUBGROUP_FEATURE_VOTE_BIT_KHR,
                        GL_SUBGROUP_FEATURE_ARITHMETIC_BIT_KHR, GL_SUBGROUP_FEATURE_BALLOT_BIT_KHR,
                        GL_SUBGROUP_FEATURE_SHUFFLE_BIT_KHR}) {
    Answers lacking;
    lacking.features = kAllFeatures & ~missing;
    s = ask(lacking);
    EXPECT_FALSE(s.usable) << "without feature bit " << missing;
    EXPECT_NE(s.why_not.find("lack basic, vote, ballot, arithmetic or shuffle"), std::string::npos)
        << s.why_not;
  }

  Answers too_wide;
  too_wide.size = 256;  // more lanes than the 128-bit ballot holds
  s = ask(too_wide);
  EXPECT_FALSE(s.usable);
  EXPECT_NE(s.why_not.find("256 invocations"), std::string::npos) << s.why_not;

  Answers refusing;
  refusing.refuses = true;
  s = ask(refusing);
  EXPECT_FALSE(s.usable);
  EXPECT_NE(s.why_not.find("refuses its queries"), std::string::npos) << s.why_not;
}

// An error left by an earlier call is not the queries' own.
TEST(GLSubgroupQuery, AnEarlierErrorIsNotTheQueriesOwn) {
  answers = Answers{};
  pending = GL_INVALID_OPERATION;
  const GL gl = fake_gl();
  EXPECT_TRUE(query_subgroups(gl).usable);
}

}  // namespace
}  // namespace rill::glsl
