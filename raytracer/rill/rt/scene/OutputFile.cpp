// Whole-or-nothing output files (OutputFile.h).
#include "rill/rt/scene/OutputFile.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace rt {

namespace {

// The temporary file being written, for the signal handler: a fixed buffer (a handler may not
// allocate), published by `busy` once complete.
char g_partial[4096];
std::atomic<bool> g_busy{false};
std::atomic<bool> g_claimed{false};  // a writer owns g_partial

void on_signal(int sig) {
  remove_partial_output();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void remove_partial_output() {
  if (g_busy.load()) ::unlink(g_partial);
}

namespace {

namespace fs = std::filesystem;

// Where a write to `path` should land: a symbolic link is followed (the link stays, its target
// is replaced), up to the system's limit on a chain of links.
fs::path final_target(const fs::path& path) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) return p;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  throw std::runtime_error("cannot write " + path.string() + ": too many levels of symbolic links");
}

}  // namespace

void write_output_file(const std::string& asked,
                       const std::function<void(const std::string&)>& write) {
  const std::string path = final_target(asked).string();
  // A device or a FIFO (/dev/null, /dev/stdout, a pipe) is written in place: renaming a
  // regular file over it would replace the device itself.
  std::error_code st_ec;
  const fs::file_status st = fs::status(path, st_ec);
  if (!st_ec && fs::exists(st) && !fs::is_regular_file(st) && !fs::is_directory(st)) {
    write(path);
    return;
  }
  const std::string tmp = path + ".partial-" + std::to_string(::getpid());
  // One file at a time is tracked for the signal handler (the first writer claims it).
  bool expected = false;
  const bool track =
      tmp.size() < sizeof g_partial && g_claimed.compare_exchange_strong(expected, true);
  if (track) {
    std::memcpy(g_partial, tmp.c_str(), tmp.size() + 1);
    g_busy.store(true);
  }
  auto done = [&] {
    if (track) {
      g_busy.store(false);
      g_claimed.store(false);
    }
  };
  try {
    write(tmp);
  } catch (...) {
    std::remove(tmp.c_str());
    done();
    throw;
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::remove(tmp.c_str());
    done();
    throw std::runtime_error("cannot write " + asked + ": " + ec.message());
  }
  done();
}

void remove_partial_output_on_interrupt() {
  // A signal the process was started ignoring (a background job's SIGINT) stays ignored.
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction old {};
    if (sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    std::signal(sig, on_signal);
  }
}

}  // namespace rt
