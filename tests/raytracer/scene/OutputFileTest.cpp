// How the ray tracer writes its output files (scene/OutputFile.h): whole or not at all, every
// write and the close checked, links followed, devices and FIFOs written in place, a FIFO
// without a reader an error at once, and every writer of an image or a render's sums going
// through it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "TestUtil.h"
#include "rill/rt/film/AccumulationFile.h"
#include "rill/rt/scene/ExrImage.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/OutputFile.h"

namespace rt {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string error_message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return {};
}

std::string read(const std::string& p) {
  std::ifstream f(p);
  return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

size_t entries(const TempDir& dir) {
  return static_cast<size_t>(std::distance(fs::directory_iterator(dir.dir()), {}));
}

TEST(OutputFile, AFailedWriteLeavesTheEarlierFileAndNoPartialOne) {
  TempDir dir;
  const std::string path = dir.file("o.png", "the earlier image");
  EXPECT_THROW(write_output_file(path,
                                 [&](OutputSink& out) {
                                   out.write("half an ima");
                                   throw std::runtime_error("the backend failed");
                                 }),
               std::runtime_error);
  EXPECT_EQ(read(path), "the earlier image");
  EXPECT_EQ(entries(dir), 1u);
  // A write that completes replaces it; until the rename the old one is there.
  write_output_file(path, [&](OutputSink& out) {
    out.write("new");
    EXPECT_EQ(read(path), "the earlier image");
  });
  EXPECT_EQ(read(path), "new");
  EXPECT_EQ(entries(dir), 1u);
  // Writing into a folder that does not exist: an error naming the file, nothing left.
  EXPECT_EQ(error_message_of(
                [&] { write_pfm(dir.path("no/such/x.pfm"), 1, 1, std::vector<float>{1.0f}); }),
            "cannot write " + dir.path("no/such/x.pfm") + ": No such file or directory");
  EXPECT_EQ(error_message_of([&] { write_output_file(dir.dir(), "x"); }),
            "cannot write " + dir.dir() + ": is a directory");
}

// A symbolic link stays a link (its target is replaced); a FIFO or a device under the name
// is written in place, never replaced by a regular file.
TEST(OutputFile, LinksAreFollowedAndDevicesWrittenInPlace) {
  TempDir dir;
  const std::string target = dir.file("target.png", "old");
  const std::string link = dir.path("link.png");
  fs::create_symlink("target.png", link);
  write_output_file(link, "new");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(read(target), "new");
  EXPECT_EQ(output_target(link), dir.path("target.png"));

  // A FIFO with a reader (this test, its end opened first): written in place.
  const std::string fifo = dir.path("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(reader, 0);
  write_output_file(fifo, "image");
  char got[16] = {};
  EXPECT_EQ(::read(reader, got, sizeof got), 5);
  EXPECT_STREQ(got, "image");
  ::close(reader);
  EXPECT_TRUE(fs::is_fifo(fs::status(fifo))) << "the FIFO was replaced";

  write_output_file("/dev/null", "x");
  EXPECT_TRUE(fs::is_character_file(fs::status("/dev/null")));
}

// Runs `check` in a child process, where a signal cannot end the test program and a wait
// cannot hang it: empty when it returned true within 20 s, else what happened.
std::string in_child(const std::function<bool()>& check) {
  const pid_t child = fork();
  if (child < 0) return "fork failed";
  if (child == 0) _exit(check() ? 0 : 1);
  int status = 0;
  const auto start = std::chrono::steady_clock::now();
  while (waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() - start > std::chrono::seconds(20)) {
      kill(child, SIGKILL);
      waitpid(child, &status, 0);
      return "it waited 20 s";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (WIFSIGNALED(status)) return "it ended by signal " + std::to_string(WTERMSIG(status));
  return WEXITSTATUS(status) == 0 ? "" : "its check failed";
}

// A FIFO that no process reads: an error at once naming it, where opening it to write would
// wait for a reader without end.
TEST(OutputFile, AFifoWithoutAReaderIsAnErrorAtOnce) {
  TempDir dir;
  const std::string fifo = dir.path("nobody-reads");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(in_child([&] {
              return error_message_of([&] { write_output_file(fifo, "image"); }) ==
                     "no process is reading FIFO " + fifo +
                         ": start its reader first (nothing was written)";
            }),
            "");
  EXPECT_TRUE(fs::is_fifo(fs::status(fifo)));
  EXPECT_EQ(entries(dir), 1u);
}

// A reader that goes away mid-file: the write fails with EPIPE, naming the file, instead of
// SIGPIPE ending the process without a word; no SIGPIPE is left pending to end it later.
TEST(OutputFile, AReaderThatLeavesIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string fifo = dir.path("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(in_child([&] {
              const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
              const std::string e = error_message_of([&] {
                write_output_file(fifo, [&](OutputSink& out) {
                  out.write("the first bytes");
                  ::close(reader);  // the reader leaves
                  out.write(std::string(1 << 20, 'x'));
                });
              });
              sigset_t pending;
              sigpending(&pending);
              return e == "cannot write " + fifo + ": Broken pipe" &&
                     !sigismember(&pending, SIGPIPE);
            }),
            "");
}

// Every writer of the library checks every write and the close: a device that takes no bytes
// is an error naming it and the reason, and the device is still there afterwards (libpng's
// own file writer removed what it could not write: the device itself, as root).
TEST(OutputFile, EveryWriterReportsAFullDeviceAndLeavesIt) {
  TempDir dir;
  const std::string full = full_device(dir);
  const std::string no_space = "cannot write " + full + ": No space left on device";
  const std::vector<glm::vec3> rgb(4 * 3, glm::vec3(0.5f));
  const std::vector<float> grey(4 * 3, 1.0f);
  Accumulation a;
  a.width = 4;
  a.height = 3;
  a.samples = 1;
  a.sum = a.carry = rgb;
  const std::vector<std::pair<const char*, std::function<void()>>> writers = {
      {"png", [&] { write_png(full, 4, 3, rgb); }},
      {"pfm rgb", [&] { write_pfm(full, 4, 3, rgb); }},
      {"pfm grey", [&] { write_pfm(full, 4, 3, grey); }},
      {"exr", [&] { write_exr(full, 4, 3, {ExrChannel::of_floats("Z", grey.data())}); }},
      {"accumulation", [&] { write_accumulation(full, a, AccumulationKey{}); }},
      {"bytes", [&] { write_output_file(full, "{}\n"); }},
  };
  for (const auto& [name, write] : writers) {
    EXPECT_EQ(error_message_of(write), no_space) << name;
    ASSERT_TRUE(fs::is_character_file(fs::status(full))) << name << " removed " << full;
  }
}

// A PFM of other dimensions than its data: an error, not a read past the data.
TEST(OutputFile, APfmOfTheWrongSizeIsRefused) {
  TempDir dir;
  EXPECT_EQ(error_message_of([&] { write_pfm(dir.path("x.pfm"), 4, 3, std::vector<float>(5)); }),
            "cannot write " + dir.path("x.pfm") + ": 5 values for a 4x3 image of 1 channel(s)");
  EXPECT_EQ(entries(dir), 0u);
}

TEST(OutputFile, AnInterruptRemovesThePartialFile) {
  TempDir dir;
  const std::string path = dir.path("o.pfm");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_partial_output_on_interrupt();
    write_output_file(path, [&](OutputSink& out) {
      out.write("PF\n8 8\n-1\n");  // then Ctrl-C
      std::raise(SIGINT);
    });
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(entries(dir), 0u) << "a partial file was left";
}

}  // namespace
}  // namespace rt
