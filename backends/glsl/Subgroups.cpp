// What a GL driver says of GL_KHR_shader_subgroup in compute shaders (Subgroups.h).
#include "Subgroups.h"

#include <cstdlib>
#include <cstring>

#include "rill/Error.h"

namespace rill::glsl {

namespace {

bool has_extension(const GL& gl, const char* name) {
  GLint n = 0;
  gl.glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const GLubyte* e = gl.glGetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
    if (e && std::strcmp(reinterpret_cast<const char*>(e), name) == 0) return true;
  }
  return false;
}

}  // namespace

GLSubgroups query_subgroups(const GL& gl) {
  GLSubgroups s;
  if (!has_extension(gl, "GL_KHR_shader_subgroup")) {
    s.why_not = "the driver lacks GL_KHR_shader_subgroup";
    return s;
  }
  // Errors left by earlier calls are not these queries' (a bounded drain: a lost context
  // may report one forever).
  for (int i = 0; i < 16 && gl.glGetError() != GL_NO_ERROR; ++i) {
  }
  GLint size = 0, stages = 0, features = 0;
  gl.glGetIntegerv(GL_SUBGROUP_SIZE_KHR, &size);
  gl.glGetIntegerv(GL_SUBGROUP_SUPPORTED_STAGES_KHR, &stages);
  gl.glGetIntegerv(GL_SUBGROUP_SUPPORTED_FEATURES_KHR, &features);
  if (gl.glGetError() != GL_NO_ERROR) {
    s.why_not = "the driver lists GL_KHR_shader_subgroup but refuses its queries";
    return s;
  }
  s.size = size;
  const GLint needed = GL_SUBGROUP_FEATURE_BASIC_BIT_KHR | GL_SUBGROUP_FEATURE_VOTE_BIT_KHR |
                       GL_SUBGROUP_FEATURE_BALLOT_BIT_KHR | GL_SUBGROUP_FEATURE_ARITHMETIC_BIT_KHR |
                       GL_SUBGROUP_FEATURE_SHUFFLE_BIT_KHR;
  if (!(stages & GL_COMPUTE_SHADER_BIT))
    s.why_not = "the driver's subgroup operations are not in compute shaders";
  else if ((features & needed) != needed)
    s.why_not = "the driver's subgroups lack basic, vote, ballot, arithmetic or shuffle operations";
  else if (size < 1 || size > 128)  // the ballot is 128 bits (rill/Group.h)
    s.why_not =
        "the driver's subgroups have " + std::to_string(size) + " invocations, outside 1 .. 128";
  s.usable = s.why_not.empty();
  return s;
}

bool subgroups_wanted() {
  const char* g = std::getenv("RILL_GLSL_SUBGROUPS");
  if (!g || !*g) return true;
  const std::string v = g;
  if (v != "on" && v != "off") throw Error("RILL_GLSL_SUBGROUPS='" + v + "' is not one of on, off");
  return v == "on";
}

std::string lane_groups_text(const GLSubgroups& s, bool used) {
  if (used) return "subgroups of " + std::to_string(s.size);
  return "one element (" + (s.usable ? std::string("RILL_GLSL_SUBGROUPS=off") : s.why_not) + ")";
}

}  // namespace rill::glsl
