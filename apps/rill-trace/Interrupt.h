// SIGINT and SIGTERM while rill-trace renders (docs/cli.md, "Signals"). A render cannot be
// stopped inside a launch, and an output half written is worse than none, so the handler only
// notes the signal; the render looks at it between passes, launches and frames, stops there,
// writes what --save asks for, and rill-trace exits 128 + the signal's number.
#pragma once

namespace trace_cli {

// While one lives, SIGINT and SIGTERM are noted (interrupted()) instead of ending the process.
// A second one ends the process at once, as the signal would, the checked writer's temporary
// file removed first (rt/scene/OutputFile.h): the way out of a save that takes too long. A
// signal the process was started ignoring (nohup, a background job's SIGINT) stays ignored.
// The handlers before it come back when it ends.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
};

// The signal noted (SIGINT or SIGTERM), or 0.
int interrupted();
// "SIGINT", "SIGTERM".
const char* signal_name(int sig);
// The exit status of a render stopped by sig: 128 + sig, as a shell reports a process ended
// by it (130 for SIGINT, 143 for SIGTERM).
int interrupted_status(int sig);

}  // namespace trace_cli
