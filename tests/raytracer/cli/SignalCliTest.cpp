// SIGINT and SIGTERM to rill-trace render (apps/rill-trace/Interrupt.h, docs/cli.md
// "Signals"): a progressive path render stops after the pass in flight, within seconds; it
// says so on stderr, naming the signal and the samples done; it exits 128 + the signal; with
// --save the sums of the passes done are on disk and --resume goes on from them, bit for bit;
// no image passes for a whole one and no temporary file (NAME.partial-PID) is left.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include "RunCommand.h"
#include "TestUtil.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

// The temporary files of the checked writer (rt/scene/OutputFile.h) left in dir.
std::vector<std::string> temporaries(const testing::TempDir& dir) {
  std::vector<std::string> found;
  for (const auto& e : std::filesystem::directory_iterator(dir.dir()))
    if (e.path().filename().string().find(".partial-") != std::string::npos)
      found.push_back(e.path().filename().string());
  return found;
}

// Starts a render of a million samples per pixel (hours), waits until it renders (its first
// --save-every file is on disk), sends sig, and checks what it did and left.
void interrupt_a_render(int sig, const char* name, int status) {
  testing::TempDir dir;
  const std::string exe = "'" RILL_TRACE_EXE "'";
  testing::Started render = testing::start_command(
      exe +
          " render builtin:cornell-path --size 64x48 --spp 1000000 --save s.acc --save-every 1 "
          "--out o.png",
      dir);
  ASSERT_GT(render.pid, 0);
  // The load and the compile come first (seconds; more on a busy machine or under ASan).
  testing::Run early;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(150);
  while (!std::filesystem::exists(dir.path("s.acc"))) {
    ASSERT_FALSE(render.poll(early))
        << "ended before rendering: " << early.status << " " << early.err;
    ASSERT_LT(std::chrono::steady_clock::now(), give_up) << "never began rendering";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // some passes in
  const auto signalled = std::chrono::steady_clock::now();
  ASSERT_EQ(::kill(render.pid, sig), 0);
  const testing::Run r = render.wait(30);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
  ASSERT_NE(r.status, -2) << "still running 30 s after " << name;
  EXPECT_EQ(r.status, status) << r.err;
  // A pass of this image takes milliseconds; the rest is the save and the exit.
  EXPECT_LT(seconds, 5.0);
  std::smatch m;
  const std::regex said(std::string("rill-trace: interrupted by ") + name +
                        " after (\\d+) of 1000000 samples per pixel; wrote the image of \\d+ "
                        "samples as o\\.partial\\.png; saved the sums to s\\.acc");
  ASSERT_TRUE(std::regex_search(r.err, m, said)) << r.err;
  const int done = std::stoi(m[1].str());
  EXPECT_GE(done, 1);
  // The image of a few samples is not written as if it were the million asked for: it is the
  // partial output, an image of the samples done.
  EXPECT_FALSE(std::filesystem::exists(dir.path("o.png")));
  EXPECT_GT(std::filesystem::file_size(dir.path("o.partial.png")), 0u);
  EXPECT_TRUE(temporaries(dir).empty()) << temporaries(dir).front();

  // The sums hold exactly the samples the message names: resumed to one more, it renders the
  // image of done + 1 samples at once, bit for bit.
  const std::string more = std::to_string(done + 1);
  const testing::Run resumed =
      testing::run_command(exe + " render builtin:cornell-path --size 64x48 --spp " + more +
                               " --resume s.acc --pfm resumed.pfm --out /dev/null",
                           dir, 120);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("path: " + more + " samples per pixel (" + m[1].str() + " resumed)"),
            std::string::npos)
      << resumed.out;
  ASSERT_EQ(testing::run_command(exe + " render builtin:cornell-path --size 64x48 --spp " + more +
                                     " --quiet --pfm once.pfm --out /dev/null",
                                 dir, 120)
                .status,
            0);
  const std::string once = testing::read_text(dir.path("once.pfm"));
  ASSERT_FALSE(once.empty());
  EXPECT_EQ(testing::read_text(dir.path("resumed.pfm")), once);
  std::printf("%s: %d samples, exit %.2f s after the signal\n", name, done, seconds);
}

TEST(CliSignals, SigintStopsAPathRenderAndSavesItsSums) {
  interrupt_a_render(SIGINT, "SIGINT", 130);
}

TEST(CliSignals, SigtermStopsAPathRenderAndSavesItsSums) {
  interrupt_a_render(SIGTERM, "SIGTERM", 143);
}

#endif

}  // namespace
}  // namespace rt
