// rill-trace render's progressive path rendering (apps/rill-trace/Progressive.h): --save,
// --save-every and --resume give the image rendered at once, bit for bit; --time-limit stops
// and says how many samples it reached; a saved render of another scene, size or seed, or a
// file of another kind, is refused naming the file; the options are refused under Whitted.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/scene/ExrImage.h"
#include "rill/rt/scene/Image.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

// rill-trace render of the path-traced Cornell box, small.
testing::Run run_path(const std::string& args, const testing::TempDir& dir) {
  return testing::run_command(
      "'" RILL_TRACE_EXE "' render builtin:cornell-path --size 12x10 --quiet " + args, dir);
}

TEST(CliPath, SavedAndResumedRendersAreTheRenderAtOnce) {
  testing::TempDir dir;
  ASSERT_EQ(run_path("--spp 9 --pfm once.pfm --out once.png", dir).status, 0);
  ASSERT_EQ(run_path("--spp 4 --save four.acc --out /dev/null", dir).status, 0);
  ASSERT_EQ(run_path("--spp 9 --resume four.acc --pfm resumed.pfm --out resumed.png", dir).status,
            0);
  ASSERT_EQ(
      run_path("--spp 9 --save chunks.acc --save-every 2 --pfm chunks.pfm --out /dev/null", dir)
          .status,
      0);
  const std::string once = testing::read_text(dir.path("once.pfm"));
  ASSERT_FALSE(once.empty());
  EXPECT_EQ(testing::read_text(dir.path("resumed.pfm")), once);
  EXPECT_EQ(testing::read_text(dir.path("chunks.pfm")), once);
  EXPECT_EQ(testing::read_text(dir.path("resumed.png")), testing::read_text(dir.path("once.png")));
  // The chunks' file holds all 9 samples: resuming from it to 9 renders nothing more.
  ASSERT_EQ(run_path("--spp 9 --resume chunks.acc --pfm again.pfm --out /dev/null", dir).status, 0);
  EXPECT_EQ(testing::read_text(dir.path("again.pfm")), once);
}

// The AOVs are sample 0's however the render goes: 9 samples at once (16 per launch), resumed
// from 4 (sample 0's camera rays traced again), saved in chunks of 2 (each chunk after the
// first resumed) and under a time limit (one sample per launch): each AOV file is that of the
// render of one sample, byte for byte.
TEST(CliPath, AovsAreSampleZerosAtOnceResumedInChunksAndTimed) {
  testing::TempDir dir;
  auto aovs = [](const std::string& name) {
    return " --depth " + name + "-d.pfm --prim " + name + "-p.pfm --normal " + name +
           "-n.pfm --albedo " + name + "-a.pfm --out /dev/null";
  };
  ASSERT_EQ(run_path("--spp 1" + aovs("one"), dir).status, 0);
  ASSERT_EQ(run_path("--spp 9" + aovs("nine"), dir).status, 0);
  ASSERT_EQ(run_path("--spp 4 --save four.acc --out /dev/null", dir).status, 0);
  ASSERT_EQ(run_path("--spp 9 --resume four.acc" + aovs("resumed"), dir).status, 0);
  ASSERT_EQ(run_path("--spp 9 --save c.acc --save-every 2" + aovs("chunks"), dir).status, 0);
  ASSERT_EQ(run_path("--spp 9 --time-limit 100000" + aovs("timed"), dir).status, 0);
  for (const char* aov : {"-d.pfm", "-p.pfm", "-n.pfm", "-a.pfm"}) {
    const std::string want = testing::read_text(dir.path(std::string("one") + aov));
    ASSERT_FALSE(want.empty()) << aov;
    for (const char* name : {"nine", "resumed", "chunks", "timed"})
      EXPECT_TRUE(testing::read_text(dir.path(name + std::string(aov))) == want)
          << name << aov << " differs from one" << aov;
  }
}

// --albedo writes the first hit's albedo as PFM, and with --exr the same floats as channels
// albedo.R, albedo.G, albedo.B; a miss is 0 (the camera sees the box's open front's edges).
TEST(CliPath, TheAlbedoGoesToItsPfmAndToTheExr) {
  testing::TempDir dir;
  ASSERT_EQ(run_path("--spp 2 --albedo a.pfm --exr a.exr --out /dev/null", dir).status, 0);
  int w = 0, h = 0, c = 0;
  const std::vector<float> pfm = read_pfm(dir.path("a.pfm"), w, h, c);
  ASSERT_EQ(w * h * c, 12 * 10 * 3);
  const ExrImage exr = read_exr(dir.path("a.exr"));
  for (int k = 0; k < 3; ++k) {
    const ExrImage::Channel* ch = exr.find(std::string("albedo.") + "RGB"[k]);
    ASSERT_NE(ch, nullptr) << k;
    for (int p = 0; p < w * h; ++p) ASSERT_EQ(ch->floats[p], pfm[3 * p + k]) << p;
  }
  // The white walls' colour is somewhere in it.
  bool white = false;
  for (int p = 0; p < w * h; ++p) white = white || (pfm[3 * p] == 0.75f && pfm[3 * p + 1] == 0.75f);
  EXPECT_TRUE(white);
}

// --variance: the EXR gets var.R var.G var.B (the values are PathAovs.TheVariance...'s), finite,
// >= 0 and positive somewhere; without --exr it is an error.
TEST(CliPath, VarianceChannelsGoToTheExr) {
  testing::TempDir dir;
  ASSERT_EQ(run_path("--spp 8 --variance --exr v.exr --out /dev/null", dir).status, 0);
  const ExrImage exr = read_exr(dir.path("v.exr"));
  bool positive = false;
  for (int k = 0; k < 3; ++k) {
    const ExrImage::Channel* ch = exr.find(std::string("var.") + "RGB"[k]);
    ASSERT_NE(ch, nullptr) << k;
    for (float v : ch->floats) {
      ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << v;
      positive = positive || v > 0.0f;
    }
  }
  EXPECT_TRUE(positive);
  EXPECT_NE(run_path("--spp 8 --variance --out /dev/null", dir).err.find("--variance needs --exr"),
            std::string::npos);
}

// --variance goes with --save, --save-every and --resume: the saved sums keep the squares, and
// the resumed render's variance channels are the render at once's, bit for bit. Resuming from
// sums saved without --variance is refused, naming the file and why.
TEST(CliPath, TheVarianceSurvivesSaveAndResume) {
  testing::TempDir dir;
  ASSERT_EQ(run_path("--spp 6 --variance --exr once.exr --out /dev/null", dir).status, 0);
  ASSERT_EQ(run_path("--spp 2 --variance --save two.acc --exr two.exr --out /dev/null", dir).status,
            0);
  const auto resumed =
      run_path("--spp 6 --variance --resume two.acc --exr resumed.exr --out /dev/null", dir);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  const auto chunks = run_path(
      "--spp 6 --variance --save c.acc --save-every 4 --exr chunks.exr --out /dev/null", dir);
  ASSERT_EQ(chunks.status, 0) << chunks.err;
  const ExrImage once = read_exr(dir.path("once.exr"));
  for (const char* name : {"resumed.exr", "chunks.exr"}) {
    const ExrImage other = read_exr(dir.path(name));
    for (int k = 0; k < 3; ++k) {
      const std::string channel = std::string("var.") + "RGB"[k];
      ASSERT_NE(once.find(channel), nullptr);
      ASSERT_NE(other.find(channel), nullptr) << name;
      EXPECT_EQ(other.find(channel)->floats, once.find(channel)->floats) << name << " " << channel;
    }
  }
  ASSERT_EQ(run_path("--spp 2 --save plain.acc --out /dev/null", dir).status, 0);
  const auto refused =
      run_path("--spp 6 --variance --resume plain.acc --exr r.exr --out /dev/null", dir);
  EXPECT_NE(refused.status, 0);
  EXPECT_NE(refused.err.find("plain.acc: saved without --variance"), std::string::npos)
      << refused.err;
}

TEST(CliPath, ATimeLimitStopsAndSaysHowFarItGot) {
  testing::TempDir dir;
  const auto r = testing::run_command("'" RILL_TRACE_EXE
                                      "' render builtin:cornell-path --size 12x10 --spp 1000000 "
                                      "--time-limit 0.3 --out t.png",
                                      dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("stopped by --time-limit"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("samples per pixel"), std::string::npos) << r.out;
}

TEST(CliPath, AResumeFromAnotherRenderIsRefusedNamingTheFile) {
  testing::TempDir dir;
  ASSERT_EQ(run_path("--spp 3 --save s.acc --out /dev/null", dir).status, 0);
  ASSERT_EQ(testing::run_command("'" RILL_TRACE_EXE "' render builtin:cornell-path --size 10x10 "
                                 "--spp 3 --save s10.acc --out /dev/null",
                                 dir)
                .status,
            0);
  dir.file("junk.acc", "not a saved render");
  struct Case {
    std::string args, needle;
  };
  for (const Case& c : std::vector<Case>{
           {"--spp 8 --seed 5 --resume s.acc", "s.acc: saved with seed 0, the scene's is 5"},
           {"--spp 8 --resume s10.acc", "s10.acc: saved at 10x10, the render is 12x10"},
           {"--spp 8 --max-depth 2 --resume s.acc", "s.acc: saved from another scene"},
           {"--spp 2 --resume s.acc", "s.acc: holds 3 samples per pixel, more than the 2"},
           {"--spp 8 --resume junk.acc", "junk.acc: not a render saved by rill-trace --save"},
           {"--spp 8 --resume gone.acc", "gone.acc: cannot open"},
           {"--integrator whitted --spp 8 --resume s.acc", "--resume is for the path integrator"},
           {"--save-every 2", "--save-every needs --save FILE"},
           {"--integrator whitted --albedo a.pfm", "--albedo is the path integrator's AOV"},
       }) {
    const auto r = run_path(c.args + " --out /dev/null", dir);
    SCOPED_TRACE(c.args);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  }
}

// The wavefront's stages in --stats-json and --stats: the camera stage runs once a sample on
// every pixel; the masked stages process only the paths not done, at most every pixel a launch,
// and the shade stage runs on the paths the intersect stage had (the same mask, between them
// nothing changes it); the ray count is the image's.
TEST(CliPath, TheWavefrontsStagesAreCounted) {
  testing::TempDir dir;
  const auto r =
      run_path("--spp 3 --strategy wavefront --stats --stats-json s.json --out /dev/null", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(testing::read_text(dir.path("s.json")));
  const int64_t pixels = 12 * 10;
  std::map<std::string, nlohmann::json> stage;
  for (const nlohmann::json& p : j["passes"]) stage[p["name"].get<std::string>()] = p;
  ASSERT_EQ(stage.count("camera"), 1u) << j["passes"];
  EXPECT_EQ(stage["camera"]["calls"].get<int64_t>(), 3);
  EXPECT_EQ(stage["camera"]["processed"].get<int64_t>(), 3 * pixels);
  for (const char* name : {"intersect", "shade", "shadow"}) {
    const nlohmann::json& p = stage[name];
    EXPECT_GT(p["calls"].get<int64_t>(), 0) << name;
    EXPECT_GT(p["processed"].get<int64_t>(), 0) << name;
    EXPECT_LE(p["processed"].get<int64_t>(), p["calls"].get<int64_t>() * pixels) << name;
  }
  EXPECT_EQ(stage["shade"]["processed"], stage["intersect"]["processed"]);
  EXPECT_NE(r.out.find("(120 pixels a launch)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\nintersect "), std::string::npos) << r.out;
}

#endif

}  // namespace
}  // namespace rt
