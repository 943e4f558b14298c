// Output files are written whole or not at all, and every write is checked: each goes to a
// temporary file beside its final name (NAME.partial-PID) and is renamed over the final name
// once complete. A write error (a full disk, /dev/full, a pipe whose reader left), a backend
// that fails, a crash or an interrupt never leaves a half-written file under the name the user
// asked for, and never ends in success: each write, and the final close, is checked, and an
// error names the file. An earlier file of that name stays as it was until the new one is
// whole. A symbolic link is followed: its target is the file replaced.
//
// A device or FIFO that exists under the name (/dev/null, /dev/stdout, a pipe) is written in
// place, not replaced. A FIFO that no process is reading is an error at once, not a wait
// without end (it is opened without blocking first, which fails then).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <utility>

namespace rt {

// Where an output's bytes go (write_output_file): every write is checked, and an error throws
// SceneError (a std::runtime_error) "cannot write PATH: REASON", PATH as the caller spelled it.
class OutputSink {
 public:
  OutputSink(int fd, std::string path) : fd_(fd), path_(std::move(path)) {}
  OutputSink(const OutputSink&) = delete;
  OutputSink& operator=(const OutputSink&) = delete;
  void write(const void* data, size_t bytes);
  void write(std::string_view text) { write(text.data(), text.size()); }
  const std::string& path() const { return path_; }

 private:
  int fd_;
  std::string path_;
};

// Opens the file a write to `path` goes to (a temporary file beside it, or a device or FIFO in
// place), calls write(sink), closes it (checked) and renames the temporary file to `path`. If
// anything throws, the temporary file is removed and the exception passes on.
void write_output_file(const std::string& path, const std::function<void(OutputSink&)>& write);
// The same for bytes already in memory.
void write_output_file(const std::string& path, std::string_view bytes);

// The file a write to `path` replaces or writes in place: a chain of symbolic links followed
// (the links stay), as written. Throws SceneError on a loop of links.
std::string output_target(const std::string& path);

// Installs SIGINT and SIGTERM handlers that remove the temporary file being written (if any)
// and then end the process as the signal would have. For programs (rill-trace); a library
// user with handlers of their own can call remove_partial_output() from theirs.
void remove_partial_output_on_interrupt();
// Removes the temporary file being written, if any. Async-signal-safe.
void remove_partial_output();

}  // namespace rt
