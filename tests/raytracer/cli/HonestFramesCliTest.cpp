// What rill-trace render reports about a frame's first use, and what overlapping a sequence's
// writes with its renders leaves on disk (issue 52, items 4 and 5):
// - a single render's stats line and --stats-json give the first launches (the drivers' work
//   at a first launch) apart from the trace, and its Mrays/s is labelled cold;
// - with warm frames (--bench-frames, or the frames of --frames after the first) Mrays/s is
//   theirs: the rays over their trace time, not labelled;
// - --overlap on (frames written while the next renders) writes the bytes --overlap off does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "RunCommand.h"
#include "TestUtil.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

testing::Run run(const std::string& args, const testing::TempDir& dir) {
  return testing::run_command("'" RILL_TRACE_EXE "' " + args, dir);
}

nlohmann::json stats(const testing::TempDir& dir) {
  return nlohmann::json::parse(testing::read_text(dir.path("s.json")));
}

// The stats line: the last line of stdout.
std::string stats_line(const std::string& out) {
  const size_t end = out.find_last_not_of('\n');
  const size_t begin = out.rfind('\n', end);
  return out.substr(begin == std::string::npos ? 0 : begin + 1, end + 1);
}

TEST(CliHonest, ASingleRenderIsColdAndItsFirstLaunchIsApart) {
  testing::TempDir dir;
  const auto r =
      run("render builtin:thesis-b --size 24x16 --out /dev/null --stats-json s.json", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = stats(dir);
  const nlohmann::json& t = j["time_ms"];
  EXPECT_TRUE(j["trace_cold"].get<bool>()) << j;
  EXPECT_TRUE(j["rays_per_second_cold"].get<bool>()) << j;
  EXPECT_EQ(j["rays_per_second_from"], "cold first frame");
  // The megakernel's launch that traces nothing took some time, and it is not in the trace.
  EXPECT_GT(t["first_launch"].get<double>(), 0.0) << t;
  EXPECT_GT(t["trace"].get<double>(), 0.0) << t;
  EXPECT_GE(t["setup"].get<double>(), 0.0) << t;
  // The parts add up to the total, and the speed is the rays over the (cold) trace.
  const double parts = t["load"].get<double>() + t["grid_build"].get<double>() +
                       t["compile"].get<double>() + t["setup"].get<double>() +
                       t["first_launch"].get<double>() + t["trace"].get<double>();
  EXPECT_NEAR(parts, t["total"].get<double>(), 1e-9 * t["total"].get<double>()) << t;
  const double rays = static_cast<double>(j["rays"].get<int64_t>());
  EXPECT_GT(rays, 0.0);
  EXPECT_DOUBLE_EQ(j["rays_per_second"].get<double>(), rays / (t["trace"].get<double>() * 1e-3));
  const std::string line = stats_line(r.out);
  EXPECT_NE(line.find(" Mrays/s cold ("), std::string::npos) << line;
  EXPECT_NE(line.find(", first launch "), std::string::npos) << line;
  EXPECT_NE(line.find(" ms (cold)"), std::string::npos) << line;
}

void bench_frames_give_the_warm_speed(const std::string& backend);

// On cpu, and on opencl, whose repeats' read-backs are in flight while the next one traces
// (--overlap on, the default): each repeat's trace is counted once.
TEST(CliHonest, BenchFramesGiveTheWarmSpeed) {
  std::vector<std::string> backends = {"cpu"};
  if (rill::backend("opencl").unavailable_reason().empty()) backends.push_back("opencl");
  for (const std::string& backend : backends) {
    SCOPED_TRACE(backend);
    bench_frames_give_the_warm_speed(backend);
  }
}

void bench_frames_give_the_warm_speed(const std::string& backend) {
  testing::TempDir dir;
  const auto r =
      run("render builtin:thesis-b --size 24x16 --out /dev/null --bench-frames 3 "
          "--stats-json s.json --backend " +
              backend,
          dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = stats(dir);
  EXPECT_TRUE(j["trace_cold"].get<bool>()) << j;  // the first frame still is
  EXPECT_FALSE(j["rays_per_second_cold"].get<bool>()) << j;
  EXPECT_EQ(j["rays_per_second_from"], "bench frames");
  const nlohmann::json& b = j["bench_frames"];
  std::vector<double> trace = b["trace_ms"].get<std::vector<double>>();
  ASSERT_EQ(trace.size(), 3u) << b;
  std::sort(trace.begin(), trace.end());
  // Every frame traces the same rays: the first's count is each repeat's.
  EXPECT_EQ(b["rays"].get<int64_t>(), j["rays"].get<int64_t>()) << j;
  EXPECT_DOUBLE_EQ(j["rays_per_second"].get<double>(),
                   static_cast<double>(b["rays"].get<int64_t>()) / (trace[1] * 1e-3));
  const std::string line = stats_line(r.out);
  // The speed is warm; the first frame's trace, which the line gives, is still cold.
  EXPECT_EQ(line.find("Mrays/s cold"), std::string::npos) << line;
  EXPECT_NE(line.find(" Mrays/s ("), std::string::npos) << line;
  EXPECT_NE(line.find(" ms (cold)"), std::string::npos) << line;
  EXPECT_NE(line.find(", first launch "), std::string::npos) << line;
}

// A dynamic scene's sequence: frame 0 is cold, the others warm, and Mrays/s is theirs alone;
// its images are the same bytes with the writes overlapped or not, and on opencl with frame
// n's read-back overlapping frame n + 1's trace or not (under RILL_OPENCL_READBACK=late, which
// holds each transfer until frame n + 1 has traced: a frame that read outputs the next one
// overwrote would show; the frames all differ).
TEST(CliHonest, FramesAfterTheFirstAreWarmAndOverlapChangesNoByte) {
  testing::TempDir dir;
  dir.file("anim.json", R"({"builtin": "thesis-a", "animation": {"end": 1, "fps": 4},
    "meshes": [{"shape": "box", "min": [-0.3, 0, -0.3], "max": [0.3, 0.6, 0.3],
      "animate": {"keys": [{"time": 0, "translate": [0, 2.8, 1.2]},
                           {"time": 1, "translate": [1, 0.2, 1.2]}]}}]})");
  std::vector<std::string> backends = {"cpu", "simd"};
  if (rill::backend("opencl").unavailable_reason().empty()) backends.push_back("opencl");
  for (const std::string& backend : backends) {
    const std::string common = "render anim.json --size 16x12 --frames 0:4 --backend " + backend;
    setenv("RILL_OPENCL_READBACK", "late", 1);  // the child inherits it
    const auto on = run(common +
                            " --out on-%d.png --pfm on-%d.pfm --depth on-d%d.pfm "
                            "--stats-json s.json",
                        dir);
    unsetenv("RILL_OPENCL_READBACK");
    ASSERT_EQ(on.status, 0) << on.err;
    const nlohmann::json j = stats(dir);
    const auto off = run(common +
                             " --overlap off --out off-%d.png --pfm off-%d.pfm "
                             "--depth off-d%d.pfm",
                         dir);
    ASSERT_EQ(off.status, 0) << off.err;
    for (int f = 0; f <= 4; ++f)
      for (const char* kind : {"%d.png", "%d.pfm", "d%d.pfm"}) {
        std::string name = kind;
        name.replace(name.find("%d"), 2, std::to_string(f));
        const std::string want = testing::read_text(dir.path("off-" + name));
        ASSERT_FALSE(want.empty()) << name;
        EXPECT_EQ(testing::read_text(dir.path("on-" + name)), want) << backend << " " << name;
        if (f > 0 && name.ends_with(".png")) {
          const std::string before = "off-" + std::to_string(f - 1) + ".png";
          EXPECT_NE(testing::read_text(dir.path(before)), want) << name << " is " << before;
        }
      }
    ASSERT_EQ(j["frames"].size(), 5u) << j;
    int64_t rays = 0;
    double trace_ms = 0;
    for (size_t f = 0; f < 5; ++f) {
      EXPECT_EQ(j["frames"][f]["cold"].get<bool>(), f == 0) << j["frames"][f];
      EXPECT_EQ(j["frames"][f]["first_launch_ms"].get<double>() > 0, f == 0) << j["frames"][f];
      if (f == 0) continue;
      rays += j["frames"][f]["rays"].get<int64_t>();
      trace_ms += j["frames"][f]["trace_ms"].get<double>();
    }
    EXPECT_EQ(j["rays_per_second_from"], "warm frames");
    EXPECT_DOUBLE_EQ(j["rays_per_second"].get<double>(),
                     static_cast<double>(rays) / (trace_ms * 1e-3));
    EXPECT_EQ(stats_line(on.out).find("Mrays/s cold"), std::string::npos) << on.out;
  }
  // A bad value is named.
  const auto bad = run("render anim.json --size 16x12 --frames 0:1 --overlap maybe", dir);
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_NE(bad.err.find("--overlap expects on or off (got 'maybe')"), std::string::npos)
      << bad.err;
}

#else
TEST(CliHonest, ASingleRenderIsColdAndItsFirstLaunchIsApart) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(CliHonest, BenchFramesGiveTheWarmSpeed) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(CliHonest, FramesAfterTheFirstAreWarmAndOverlapChangesNoByte) {
  GTEST_SKIP() << "rill-trace is not built";
}
#endif

}  // namespace
}  // namespace rt
