// The image files the ray tracer writes and reads back (scene/Image.h): PFM round trips, PFM
// headers that do not match their data (the image fuzzer's findings stay fixed here), and
// whole-or-nothing writes (scene/OutputFile.h).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "TestUtil.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/OutputFile.h"

namespace rt {
namespace {

using testing::TempDir;

std::string runtime_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::runtime_error";
  return {};
}

TEST(ImageTest, PfmRoundTripsBothKindsTopRowFirst) {
  TempDir dir;
  const std::vector<glm::vec3> rgb = {{1, 2, 3},         {4, 5, 6}, {7, 8, 9},
                                      {-1, 0.5f, 1e30f}, {0, 0, 0}, {1, 1, 1}};
  write_pfm(dir.path("c.pfm"), 3, 2, rgb);
  int w = 0, h = 0, c = 0;
  std::vector<float> back = read_pfm(dir.path("c.pfm"), w, h, c);
  EXPECT_EQ(w, 3);
  EXPECT_EQ(h, 2);
  EXPECT_EQ(c, 3);
  ASSERT_EQ(back.size(), 18u);
  EXPECT_EQ(std::memcmp(back.data(), rgb.data(), 18 * sizeof(float)), 0);

  const std::vector<float> grey = {0.25f, 0.5f, 0.75f, 1.0f};
  write_pfm(dir.path("g.pfm"), 1, 4, grey);
  back = read_pfm(dir.path("g.pfm"), w, h, c);
  EXPECT_EQ(w, 1);
  EXPECT_EQ(h, 4);
  EXPECT_EQ(c, 1);
  EXPECT_EQ(back, grey);
}

TEST(ImageTest, PfmHeaderLargerThanItsDataIsAnErrorBeforeAllocating) {
  // 100000 x 100000 x 3 floats would be 120 GB: refused from the header and the file size,
  // not attempted (the fuzzer ran out of memory on this before).
  const std::string huge = "PF\n100000 100000\n-1.0\n" + std::string(24, '\0');
  int w = 0, h = 0, c = 0;
  const std::string e = runtime_error_of([&] { parse_pfm(huge, "big.pfm", w, h, c); });
  EXPECT_NE(e.find("big.pfm: truncated PFM file (100000x100000 needs 120000000000 bytes of "
                   "data, the file has 24)"),
            std::string::npos)
      << e;
  // One float short.
  const std::string short_grey = "Pf\n2 1\n-1\n" + std::string(4, '\0');
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm(short_grey, "s.pfm", w, h, c);
            }).find("s.pfm: truncated PFM file"),
            std::string::npos);
  // A header and nothing after it; a size whose byte count would wrap 64 bits.
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm("Pf\n1 1\n-1", "e.pfm", w, h, c);
            }).find("e.pfm: truncated PFM file (no data after the header)"),
            std::string::npos);
  EXPECT_NE(runtime_error_of([&] {
              parse_pfm("PF\n2147483647 2147483647\n-1\n....", "w.pfm", w, h, c);
            }).find("w.pfm: truncated PFM file"),
            std::string::npos);
  // Exactly enough.
  EXPECT_EQ(parse_pfm("Pf\n2 1\n-1\n" + std::string(8, '\0'), "ok.pfm", w, h, c).size(), 2u);
}

// A PFM whose data is all there is still held to the image limits (ImageLimits.h), checked
// from its header: the message names the file, the size and the limits.
TEST(ImageTest, PfmOverTheImageLimitsIsAnError) {
  int w = 0, h = 0, c = 0;
  const std::string wide = "Pf\n16385 1\n-1\n" + std::string(16385 * 4, '\0');
  EXPECT_EQ(runtime_error_of([&] { parse_pfm(wide, "wide.pfm", w, h, c); }),
            "wide.pfm: its header declares a 16385x1 PFM image, over the limits (1..16384 per "
            "side, at most 33554432 pixels)");
  EXPECT_EQ(parse_pfm("Pf\n16384 1\n-1\n" + std::string(16384 * 4, '\0'), "ok.pfm", w, h, c).size(),
            16384u);
}

// The limits themselves (docs/robustness.md): 16384 a side and 2^25 pixels, both included.
TEST(ImageLimits, SidesAndPixelsAreBoundedBothIncluded) {
  EXPECT_TRUE(image_size_fits(1, 1));
  EXPECT_TRUE(image_size_fits(16384, 2048));  // 2^25 pixels
  EXPECT_FALSE(image_size_fits(16384, 2049));
  EXPECT_FALSE(image_size_fits(16385, 1));
  EXPECT_FALSE(image_size_fits(1, 16385));
  EXPECT_FALSE(image_size_fits(0, 1));
  EXPECT_FALSE(image_size_fits(1, -1));
  EXPECT_FALSE(image_size_fits(INT64_MAX, INT64_MAX));
  EXPECT_EQ(image_size_limits(), "1..16384 per side, at most 33554432 pixels");
}

TEST(ImageTest, NotAPfmNamesTheFile) {
  int w = 0, h = 0, c = 0;
  for (const std::string& bad : {std::string(""), std::string("P6\n1 1\n255\n..."),
                                 std::string("PF\n0 1\n-1\n"), std::string("PF\n1 1\n1.0\n    "),
                                 std::string("PF\n-3 1\n-1\n"), std::string("PF\n1 1\nnan\n    ")})
    EXPECT_EQ(runtime_error_of([&] { parse_pfm(bad, "x.pfm", w, h, c); }),
              "x.pfm: not a little-endian PFM file")
        << bad;
}

// Outputs are written whole or not at all (OutputFile.h).
TEST(OutputFile, AFailedWriteLeavesTheEarlierFileAndNoPartialOne) {
  TempDir dir;
  const std::string path = dir.file("o.png", "the earlier image");
  EXPECT_THROW(write_output_file(path,
                                 [&](const std::string& tmp) {
                                   std::ofstream(tmp) << "half an ima";
                                   EXPECT_NE(tmp, path);
                                   throw std::runtime_error("the backend failed");
                                 }),
               std::runtime_error);
  std::ifstream f(path);
  std::string content((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_EQ(content, "the earlier image");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.dir()), {}), 1);
  // A write that completes replaces it.
  write_output_file(path, [&](const std::string& tmp) {
    std::ofstream(tmp) << "new";
    EXPECT_TRUE(std::filesystem::exists(path));  // the old one, until the rename
  });
  std::ifstream g(path);
  std::string now((std::istreambuf_iterator<char>(g)), std::istreambuf_iterator<char>());
  EXPECT_EQ(now, "new");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.dir()), {}), 1);
  // Writing into a folder that does not exist: an error naming the file, nothing left.
  EXPECT_THROW(write_pfm(dir.path("no/such/x.pfm"), 1, 1, std::vector<float>{1.0f}),
               std::runtime_error);
}

// A symbolic link stays a link (its target is replaced); a FIFO or a device under the name
// is written in place, never replaced by a regular file.
TEST(OutputFile, LinksAreFollowedAndDevicesWrittenInPlace) {
  namespace fs = std::filesystem;
  TempDir dir;
  auto read = [](const std::string& p) {
    std::ifstream f(p);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  };
  const std::string target = dir.file("target.png", "old");
  const std::string link = dir.path("link.png");
  fs::create_symlink("target.png", link);
  write_output_file(link, [&](const std::string& tmp) { std::ofstream(tmp) << "new"; });
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(read(target), "new");

  const std::string fifo = dir.path("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const pid_t reader = fork();
  ASSERT_GE(reader, 0);
  if (reader == 0) {  // drains the pipe, exits 0 when it read what was written
    std::ifstream f(fifo);
    std::string got((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    _exit(got == "image" ? 0 : 1);
  }
  write_output_file(fifo, [&](const std::string& to) {
    EXPECT_EQ(to, fifo);
    std::ofstream(to) << "image";
  });
  int status = 0;
  ASSERT_EQ(waitpid(reader, &status, 0), reader);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_TRUE(fs::is_fifo(fs::status(fifo))) << "the FIFO was replaced";

  write_output_file("/dev/null", [&](const std::string& to) { std::ofstream(to) << "x"; });
  EXPECT_TRUE(fs::is_character_file(fs::status("/dev/null")));
}

TEST(OutputFile, AnInterruptRemovesThePartialFile) {
  TempDir dir;
  const std::string path = dir.path("o.pfm");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_partial_output_on_interrupt();
    write_output_file(path, [&](const std::string& tmp) {
      std::ofstream(tmp) << "PF\n8 8\n-1\n";  // then Ctrl-C
      std::raise(SIGINT);
    });
    _exit(0);  // not reached
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.dir()), {}), 0)
      << "a partial file was left";
}

}  // namespace
}  // namespace rt
