// Output files are written whole or not at all: each goes to a temporary file beside its final
// name (NAME.partial-PID) and is renamed over the final name once complete. A write error, a
// backend that fails, a crash or an interrupt never leaves a half-written image under the name
// the user asked for; an earlier file of that name stays as it was until the new one is whole.
// A symbolic link is followed: its target is the file replaced. A device or FIFO that exists
// under the name (/dev/null, /dev/stdout, a pipe) is written in place, not replaced.
#pragma once

#include <functional>
#include <string>

namespace rt {

// Calls write(tmp) to write the file at a temporary path, then renames it to `path`. If write
// throws, the temporary file is removed and the exception passes on.
void write_output_file(const std::string& path,
                       const std::function<void(const std::string&)>& write);

// Installs SIGINT and SIGTERM handlers that remove the temporary file being written (if any)
// and then end the process as the signal would have. For programs (rill-trace); a library
// user with handlers of their own can call remove_partial_output() from theirs.
void remove_partial_output_on_interrupt();
// Removes the temporary file being written, if any. Async-signal-safe.
void remove_partial_output();

}  // namespace rt
