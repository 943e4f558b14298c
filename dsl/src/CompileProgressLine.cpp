#include "rill/CompileProgressLine.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

#include "rill/Stopwatch.h"

namespace rill {

CompileProgressLine::CompileProgressLine(std::FILE* out, double delay_ms, Where where)
    : out_(out),
      delay_ms_(delay_ms),
      enabled_(out != nullptr && (where == Where::Always || isatty(fileno(out)) == 1)) {
  // Not a terminal: install nothing, so embedders' observers and compiles run as without it.
  if (!enabled_) return;
  previous_ = set_compile_observer([this](const CompileProgress& p) { on_progress(p); });
  ticker_ = std::thread([this] { tick(); });
}

CompileProgressLine::~CompileProgressLine() {
  if (!enabled_) return;
  set_compile_observer(std::move(previous_));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  ticker_.join();
}

std::string CompileProgressLine::text(const CompileProgress& p) {
  std::string what = std::to_string(p.total) + (p.total == 1 ? " kernel" : " kernels") + " for " +
                     p.backend + (p.driver.empty() ? "" : " (" + p.driver + ")");
  if (p.finished) {
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.1f s", p.elapsed_ms / 1000);
    return "compiled " + what + " in " + secs;
  }
  return "compiling " + what + "... " + std::to_string(p.done) + "/" + std::to_string(p.total);
}

void CompileProgressLine::on_progress(const CompileProgress& p) {
  if (previous_) previous_(p);
  std::lock_guard<std::mutex> lock(mutex_);
  if (p.done == 0 && !p.finished) {
    // A new batch. One still shown (overlapping batches) is ended on its own line first.
    if (shown_) std::fputc('\n', out_);
    active_ = true;
    shown_ = false;
    started_ = std::chrono::steady_clock::now() -
               std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                   std::chrono::duration<double, std::milli>(p.elapsed_ms));
  }
  last_ = p;
  if (!active_) return;
  if (p.finished) {
    if (shown_) draw(true);
    active_ = shown_ = false;
    return;
  }
  if (ms_since(started_) >= delay_ms_) draw(false);
}

void CompileProgressLine::tick() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, std::chrono::milliseconds(100));
    if (stop_) break;
    // The first draw of a slow batch happens here when no kernel finishes within the delay.
    if (active_ && !shown_ && ms_since(started_) >= delay_ms_) draw(false);
  }
}

void CompileProgressLine::draw(bool finished) {
  CompileProgress p = last_;
  p.finished = finished;
  // "\r\033[K": back to the line's start and clear it, so a shorter text leaves no tail.
  std::fprintf(out_, "\r\033[K%s%s", text(p).c_str(), finished ? "\n" : "");
  std::fflush(out_);
  shown_ = !finished;
}

}  // namespace rill
