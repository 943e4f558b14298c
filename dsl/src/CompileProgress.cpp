// The process-wide compile observer and the batches that report to it (CompileProgress.h).
#include "CompileProgress.h"

#include <utility>

namespace rill {

namespace {
std::mutex& observer_mutex() {
  static std::mutex m;
  return m;
}
CompileObserver& observer() {
  static CompileObserver o;
  return o;
}
}  // namespace

CompileObserver set_compile_observer(CompileObserver o) {
  std::lock_guard<std::mutex> lock(observer_mutex());
  return std::exchange(observer(), std::move(o));
}

namespace detail {

bool& in_compile_batch() {
  thread_local bool in = false;
  return in;
}

CompileBatch::CompileBatch(std::string backend, std::string driver, int total) {
  {
    std::lock_guard<std::mutex> lock(observer_mutex());
    observer_ = observer();
  }
  progress_.backend = std::move(backend);
  progress_.driver = std::move(driver);
  progress_.total = total;
  std::lock_guard<std::mutex> lock(mutex_);
  report(false);
}

CompileBatch::~CompileBatch() {
  // An observer that throws must not escape a destructor (or a compile's unwinding).
  try {
    finish();
  } catch (...) {
  }
}

void CompileBatch::done() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ended_) return;
  ++progress_.done;
  report(false);
}

void CompileBatch::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (ended_) return;
  ended_ = true;
  report(true);
}

void CompileBatch::report(bool finished) {
  if (!observer_) return;
  progress_.finished = finished;
  progress_.elapsed_ms = clock_.ms();
  observer_(progress_);
}

}  // namespace detail
}  // namespace rill
