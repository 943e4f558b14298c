// Programs: capturing a kernel definition.
//
//   rill::Program grow = rill::program("grow", [&] {
//     rill::Input<Float> x("x");
//     rill::Output<Float> y("y");
//     RILL_IF(x >= 1.0f) { RILL_DISCARD; } RILL_ENDIF;
//     y = min(x * 2.0f, 1.0f);
//   });
//
// The body runs once, now, recording IR; afterwards the Program is an immutable value that
// can be printed (print(), dump(), <<), hashed and compiled for any backend (Kernel.h).
#pragma once

#include <functional>
#include <iostream>
#include <memory>
#include <string>

#include "rill/Capture.h"
#include "rill/ir/IR.h"
#include "rill/ir/Printer.h"

namespace rill {

class Program {
 public:
  Program() = default;
  explicit Program(detail::CapturedProgram captured);

  const std::string& name() const { return d_->fn->name; }
  // The captured IR, before optimization.
  const ir::Function& ir() const { return *d_->fn; }
  // Readable IR text (returned, not printed: dump() prints it).
  std::string print() const;
  // The same, with what `options` adds: print({.locations = true}) puts each statement's
  // source line after it.
  std::string print(const ir::PrintOptions& options) const;
  // Writes print() to `os` (standard error by default), for debugging: p.dump();
  void dump(std::ostream& os = std::cerr) const;
  // Stable hash of the IR (the kernel caches' key).
  uint64_t hash() const { return hash_; }
  // Milliseconds its definition took (running the body, checking and hashing the IR):
  // reported as Kernel::info().capture_ms by every kernel compiled from it.
  double capture_ms() const { return d_->capture_ms; }

  const detail::CapturedProgram& captured() const { return *d_; }
  bool valid() const { return d_ != nullptr; }

 private:
  std::shared_ptr<const detail::CapturedProgram> d_;
  uint64_t hash_ = 0;
};

// Writes the captured IR (print()): std::cout << program;
std::ostream& operator<<(std::ostream& os, const Program& p);

// Runs `body` once inside a new program scope and returns the captured program.
template <class F>
Program program(std::string name, F&& body, SourceLoc loc = RILL_HERE) {
  detail::ProgramScope scope(std::move(name), loc);
  std::forward<F>(body)();
  return Program(scope.finish());
}

}  // namespace rill
