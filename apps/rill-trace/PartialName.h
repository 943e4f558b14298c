// The name of a partial output: an image of fewer samples or tiles than asked for, written
// where a render was cut short (a signal, a lost MPI rank), never under the whole image's name.
#pragma once

#include <string>

namespace trace_cli {

// x.png -> x.partial.png; a name without an extension (or a dot file) gets ".partial" appended.
inline std::string partial_name(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  const size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash) ||
      dot == (slash == std::string::npos ? 0 : slash + 1))
    return path + ".partial";
  return path.substr(0, dot) + ".partial" + path.substr(dot);
}

}  // namespace trace_cli
