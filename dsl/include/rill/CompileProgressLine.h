// A compile progress line on a terminal, drawn from the compile observer (Kernel.h):
//
//   rill::CompileProgressLine line;  // while it lives, on stderr if that is a terminal
//   auto ks = rill::compile_all(requests);
//
// prints, once a batch of compiles has run for a second,
//   compiling 7 kernels for opencl (PoCL)... 3/7
// redrawn in place as kernels finish (and every tenth of a second meanwhile), and ends it with
//   compiled 7 kernels for opencl (PoCL) in 4.2 s
// A batch that ends within the delay (a kernel cache had it, a fast compiler) prints nothing,
// and nothing is ever printed where the stream is not a terminal (a log, a pipe), so scripts
// read what they did before. Batches that overlap (compile() on two threads) share the line:
// it shows the one that started last.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "rill/Kernel.h"

namespace rill {

class CompileProgressLine {
 public:
  enum class Where { TerminalOnly, Always };  // Always: any stream (tests, forced output)
  // Installs itself as the compile observer (passing every report on to the one it replaces,
  // which it restores when destroyed). delay_ms: how long a batch runs before the line shows.
  explicit CompileProgressLine(std::FILE* out = stderr, double delay_ms = 1000,
                               Where where = Where::TerminalOnly);
  ~CompileProgressLine();
  CompileProgressLine(const CompileProgressLine&) = delete;
  CompileProgressLine& operator=(const CompileProgressLine&) = delete;

  // The line's text for a report: "compiling 7 kernels for opencl (PoCL)... 3/7", or when
  // finished "compiled 7 kernels for opencl (PoCL) in 4.2 s".
  static std::string text(const CompileProgress& p);

 private:
  void on_progress(const CompileProgress& p);
  void tick();
  void draw(bool finished);  // with mutex_ held

  std::FILE* out_;
  double delay_ms_;
  bool enabled_;
  CompileObserver previous_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool active_ = false;  // a batch is running
  bool shown_ = false;   // and its line is on the terminal
  bool stop_ = false;
  CompileProgress last_;
  std::chrono::steady_clock::time_point started_;
  std::thread ticker_;  // redraws the elapsed time while no kernel finishes
};

}  // namespace rill
