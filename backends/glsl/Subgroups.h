// Whether glsl-compute's lane groups (rill/Group.h) are the driver's subgroups: what a GL
// context says of GL_KHR_shader_subgroup in compute shaders, and RILL_GLSL_SUBGROUPS.
//
// The lane-group ops map to subgroup operations through the GLSL shared with the vulkan
// backend (GLSLEmitter.cpp, DriverRules::subgroups), which needs the basic, vote, ballot,
// arithmetic and shuffle operations in the compute stage, and a subgroup of at most 128
// invocations (the ballot's width). Where any of that is missing the ops keep their group of
// one; the fragment stage (`glsl`) always does.
#pragma once

#include <string>

#include "GLContext.h"

namespace rill::glsl {

struct GLSubgroups {
  int size = 0;         // GL_SUBGROUP_SIZE_KHR; 0 without the extension
  bool usable = false;  // the lane-group ops can be subgroup operations here
  std::string why_not;  // when not usable: what the driver lacks
};

// Asks the current context (GL 4.3 or later): the extension string, then the three
// GL_KHR_shader_subgroup queries.
GLSubgroups query_subgroups(const GL& gl);

// RILL_GLSL_SUBGROUPS = on (default) | off: lane groups as subgroups where the driver has the
// operations, or a group of one everywhere (for comparing; both pass the group tests).
// Throws Error on another value.
bool subgroups_wanted();

// The description's words, as the vulkan backend's: "subgroups of 32", or "one element (why)".
std::string lane_groups_text(const GLSubgroups& s, bool used);

}  // namespace rill::glsl
