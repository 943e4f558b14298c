// Paths with a frame number: "frame-%04d.png" for rill-trace's numbered outputs, and
// "wave-%03d.obj" for an OBJ sequence in a scene file. One printf conversion, %d with an
// optional zero flag and a width of at most 20, and %% for a percent sign; anything else is
// an error naming the option or key (what) and the pattern.
#pragma once

#include <string>

namespace rt {

// Whether `pattern` has the frame number; throws SceneError for a second one or any other
// conversion.
bool has_frame_number(const std::string& pattern, const std::string& what);
// The pattern with its frame number written as `frame` (and %% as %).
std::string frame_path(const std::string& pattern, int frame);

}  // namespace rt
