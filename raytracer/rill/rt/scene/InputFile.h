// Reading the files a scene names (scene JSON, OBJ, MTL, PNG and PFM), which may come from
// other people: only regular files, and only up to a size limit, so that a path naming a
// device or an endless stream (/dev/zero, a pipe) is an error instead of memory growing
// without bound.
//
// The limit is 4 GiB per file by default; RILL_MAX_INPUT_MB raises or lowers it.
#pragma once

#include <cstdint>
#include <string>

namespace rt {

// The size limit for one input file, in bytes (RILL_MAX_INPUT_MB, else 4 GiB).
uint64_t max_input_bytes();

// Throws SceneError naming the path when it is missing, a directory, not a regular file
// (a device, pipe or socket), unreadable, or over max_input_bytes(). `kind` names what the
// file should be, with its article ("an OBJ file", "a scene file", ...). Returns the file's size.
uint64_t check_input_file(const std::string& path, const std::string& kind);

// The whole file, after check_input_file.
std::string read_input_file(const std::string& path, const std::string& kind);

}  // namespace rt
