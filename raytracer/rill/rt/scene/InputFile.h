// Reading the files a scene names (scene JSON, OBJ, MTL, PNG and PFM), which may come from
// other people: only regular files, and only up to a size limit, so that a path naming a
// device or an endless stream (/dev/zero, a pipe) is an error instead of memory growing
// without bound.
//
// The limit is 4 GiB per file by default; RILL_MAX_INPUT_MB raises or lowers it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rt {

// The size limit for one input file, in bytes (RILL_MAX_INPUT_MB, else 4 GiB).
uint64_t max_input_bytes();

// Throws SceneError naming the path when it has a NUL character (the system would read the
// name only up to it: another file), is missing, a directory, not a regular file
// (a device, pipe or socket), unreadable, or over max_input_bytes(). `kind` names what the
// file should be, with its article ("an OBJ file", "a scene file", ...). Returns the file's size.
uint64_t check_input_file(const std::string& path, const std::string& kind);

// The whole file, after check_input_file.
std::string read_input_file(const std::string& path, const std::string& kind);

// Records the path of every file read_input_file reads on this thread while it lives (a scene
// file, its OBJ, MTL and texture files, however deep), for a program that must not write over
// its inputs: rill-trace refuses an output that is one. Logs nest; each sees every read made
// while it lives.
class InputFileLog {
 public:
  InputFileLog();
  ~InputFileLog();
  InputFileLog(const InputFileLog&) = delete;
  InputFileLog& operator=(const InputFileLog&) = delete;
  const std::vector<std::string>& paths() const { return paths_; }

 private:
  friend std::string read_input_file(const std::string&, const std::string&);
  InputFileLog* outer_;
  std::vector<std::string> paths_;
};

}  // namespace rt
