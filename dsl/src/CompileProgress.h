// The library's side of CompileProgress (Kernel.h): a batch reports to the process-wide
// observer. compile() and compile_all() make batches; nothing here prints.
#pragma once

#include <mutex>
#include <string>

#include "rill/Kernel.h"
#include "rill/Stopwatch.h"

namespace rill::detail {

// One batch of compiles. Reports its start when made (if an observer is installed then),
// each kernel as done() is called, and its end when finish() is called or it is destroyed
// (a compile that throws still ends its batch, so a progress line is never left open).
class CompileBatch {
 public:
  CompileBatch(std::string backend, std::string driver, int total);
  ~CompileBatch();
  CompileBatch(const CompileBatch&) = delete;
  CompileBatch& operator=(const CompileBatch&) = delete;
  void done();
  void finish();

 private:
  void report(bool finished);  // with mutex_ held
  CompileObserver observer_;   // the one installed when the batch began
  std::mutex mutex_;
  CompileProgress progress_;
  Stopwatch clock_;
  bool ended_ = false;
};

// Whether this thread is compiling for a compile_all() batch: its compile() calls then do
// not report batches of their own.
bool& in_compile_batch();

}  // namespace rill::detail
