// Running rill-trace (or mpirun with it) as a user would, for the command-line tests: a shell
// command line in a test's folder, bounded by a timeout, with its exit status and output.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

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

}  // namespace rt::testing
