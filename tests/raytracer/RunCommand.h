// Running rill-trace (or mpirun with it) as a user would, for the command-line tests: a shell
// command line in a test's folder, bounded by a timeout, with its exit status and output.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "TestUtil.h"

namespace rt::testing {

struct Run {
  int status = -1;  // exit status, or -1 if killed by a signal
  std::string err, out;
};

inline std::string read_text(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs a shell command line in dir, its stdout and stderr kept. timeout: a hang fails the
// test (exit status 124, or 137 when the command ignores SIGTERM for 5 s) instead of the
// whole suite.
inline Run run_command(const std::string& command, const TempDir& dir, int timeout_s = 60) {
  const std::string err = dir.path("stderr.txt"), out = dir.path("stdout.txt");
  std::string cmd = "cd '" + dir.dir() + "' && timeout -k 5 " + std::to_string(timeout_s) + " " +
                    command + " > '" + out + "' 2> '" + err + "'";
  int rc = std::system(cmd.c_str());
  Run r;
  if (WIFEXITED(rc)) r.status = WEXITSTATUS(rc);
  r.err = read_text(err);
  r.out = read_text(out);
  return r;
}

// A command line started in the background in dir (its stdout and stderr kept as
// run_command's), for a test that signals it while it runs. The process is the command
// itself (the shell execs it), so a signal sent to pid reaches it.
struct Started {
  pid_t pid = -1;
  std::string out, err;  // the files its stdout and stderr go to
  Started() = default;
  Started(Started&& o) noexcept
      : pid(std::exchange(o.pid, -1)), out(std::move(o.out)), err(std::move(o.err)) {}
  Started(const Started&) = delete;
  Started& operator=(const Started&) = delete;
  // Whether it has ended (its Run then in `ended`), without waiting.
  bool poll(Run& ended) {
    int rc = 0;
    if (pid < 0 || waitpid(pid, &rc, WNOHANG) != pid) return false;
    pid = -1;
    ended.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
    ended.err = read_text(err);
    ended.out = read_text(out);
    return true;
  }
  // Waits up to timeout_s for it to end; a hang is killed (SIGKILL) and gives status -2, so
  // that it fails the test instead of blocking the suite.
  Run wait(double timeout_s) {
    Run r;
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!poll(r)) {
      if (std::chrono::steady_clock::now() > until) {
        ::kill(pid, SIGKILL);
        waitpid(pid, nullptr, 0);
        pid = -1;
        r.status = -2;
        r.err = read_text(err);
        return r;
      }
      ::usleep(10000);
    }
    return r;
  }
  ~Started() {
    if (pid > 0) {  // a test that failed before its wait: no process outlives it
      ::kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  }
};

inline Started start_command(const std::string& command, const TempDir& dir) {
  Started s;
  s.out = dir.path("stdout.txt");
  s.err = dir.path("stderr.txt");
  const std::string cmd =
      "cd '" + dir.dir() + "' && exec " + command + " > '" + s.out + "' 2> '" + s.err + "'";
  s.pid = fork();
  if (s.pid == 0) {
    // As a user's shell starts it: SIGINT and SIGTERM at their defaults, whatever the test
    // runner had (a runner in the background ignores SIGINT, and exec keeps that).
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return s;
}

}  // namespace rt::testing
