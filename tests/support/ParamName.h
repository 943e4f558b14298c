// A backend's name as a GoogleTest parameter name: test names allow only letters, digits and
// '_', so "glsl-compute" becomes "glsl_compute" (tests/*/CMakeLists.txt filter on it).
#pragma once

#include <algorithm>
#include <string>

namespace rill::testing {

inline std::string param_name(std::string backend) {
  std::replace(backend.begin(), backend.end(), '-', '_');
  return backend;
}

}  // namespace rill::testing
