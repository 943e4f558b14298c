// Whole-or-nothing, checked output files (OutputFile.h).
#include "rill/rt/scene/OutputFile.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "rill/rt/scene/Scene.h"

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

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw SceneError("cannot write " + path + ": " + why);
}

[[noreturn]] void fail_errno(const std::string& path, int err) {
  fail(path, std::strerror(err));
}

// A write to a pipe whose reader has gone raises SIGPIPE, which ends the process without a
// word about the file. Blocked while a device or FIFO is written, the write fails with EPIPE
// instead and the error names the file; a SIGPIPE raised meanwhile is then taken off the
// thread's pending signals, so that unblocking it does not end the process after all.
class SigpipeBlocked {
 public:
  SigpipeBlocked() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    sigset_t pending;
    was_pending_ = sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1;
    pthread_sigmask(SIG_BLOCK, &pipe_, &old_);
  }
  ~SigpipeBlocked() {
    sigset_t pending;
    if (!was_pending_ && sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE) == 1) {
      const timespec now{};
      sigtimedwait(&pipe_, nullptr, &now);
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeBlocked(const SigpipeBlocked&) = delete;
  SigpipeBlocked& operator=(const SigpipeBlocked&) = delete;

 private:
  sigset_t pipe_{}, old_{};
  bool was_pending_ = false;
};

// Opens a device or FIFO that exists under the name, to write it in place. A FIFO is opened
// without blocking first: with no reader that fails with ENXIO at once, where a blocking open
// would wait for one without end; the writes that follow block as usual.
int open_in_place(const std::string& asked, bool fifo) {
  const int fd = ::open(asked.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | (fifo ? O_NONBLOCK : 0));
  if (fd < 0 && fifo && errno == ENXIO)
    throw SceneError("no process is reading FIFO " + asked +
                     ": start its reader first (nothing was written)");
  if (fd < 0) fail_errno(asked, errno);
  if (fifo) {
    const int flags = ::fcntl(fd, F_GETFL);
    if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0) {
      const int err = errno;
      ::close(fd);
      fail_errno(asked, err);
    }
  }
  return fd;
}

// Closes fd, an error naming the file (a close can report what an earlier write deferred).
void close_checked(int fd, const std::string& asked) {
  if (::close(fd) != 0 && errno != EINTR) fail_errno(asked, errno);
}

// Writes through a sink on fd and closes it; fd is closed whatever happens.
void write_and_close(int fd, const std::string& asked,
                     const std::function<void(OutputSink&)>& write) {
  try {
    OutputSink sink(fd, asked);
    write(sink);
  } catch (...) {
    ::close(fd);
    throw;
  }
  close_checked(fd, asked);
}

}  // namespace

void OutputSink::write(const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t n = ::write(fd_, p, std::min(bytes, size_t{1} << 30));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail_errno(path_, errno);
    if (n == 0) fail(path_, "the write made no progress");
    p += n;
    bytes -= static_cast<size_t>(n);
  }
}

std::string output_target(const std::string& path) {
  fs::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p.string();
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) return p.string();
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  throw SceneError("cannot write " + path + ": too many levels of symbolic links");
}

void write_output_file(const std::string& asked, const std::function<void(OutputSink&)>& write) {
  // A device or a FIFO (/dev/null, /dev/stdout, a pipe) is written in place: renaming a
  // regular file over it would replace the device itself. Opened by the name as given, which
  // the system resolves (/dev/stdout's /proc/self/fd/1 names a pipe no path reaches).
  struct stat st {};
  if (::stat(asked.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail(asked, "is a directory");
    if (!S_ISREG(st.st_mode)) {
      SigpipeBlocked quiet;
      // Opened without O_CREAT: a device removed meanwhile is an error, never a regular file
      // made in its place.
      write_and_close(open_in_place(asked, S_ISFIFO(st.st_mode)), asked, write);
      return;
    }
  }
  const std::string path = output_target(asked);
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
    // A stale temporary file of this name (a pid reused after a crash) goes first; O_EXCL
    // then never writes through a link planted under the temporary name.
    ::unlink(tmp.c_str());
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) fail_errno(asked, errno);
    write_and_close(fd, asked, write);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) fail(asked, ec.message());
  } catch (...) {
    ::unlink(tmp.c_str());
    done();
    throw;
  }
  done();
}

void write_output_file(const std::string& path, std::string_view bytes) {
  write_output_file(path, [&](OutputSink& out) { out.write(bytes); });
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
