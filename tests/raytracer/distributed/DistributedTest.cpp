// rill-trace under `mpirun --oversubscribe` on this host (docs/distributed.md): the image and
// AOVs bitwise those of a single-process render for 2 and 3 ranks and tile sizes that do and
// do not divide the image; a worker killed mid-render ends the job with a clear error and a
// partial image, or (mpirun --enable-recovery) the image completes without it; a rank with
// another scene, or one that fails to load, stops the job at the start with its message.
// An image sequence's frames are the single process's files too. Every command runs under a
// timeout: a hang fails the test.
#include <gtest/gtest.h>

#include <algorithm>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

#include "RunCommand.h"
#include "TestUtil.h"
#include "distributed/TileQueue.h"

namespace rt::testing {
namespace {

using Result = rt::testing::Run;  // not testing::Test::Run, in fixtures

const std::string kExe = std::string("'") + RILL_TRACE_EXE + "'";

#if RILL_HAVE_MPI
#define RT_REQUIRE_MPI() (void)0
// Under the sanitizer build (.ci/run) the ranks check no leaks: Open MPI 4.1 leaves memory
// behind at MPI_Finalize by design, allocated in components it unloads there, so LeakSanitizer
// cannot name a library to suppress. Address and undefined-behaviour checks stay on.
const std::string kMpirun = std::string("env ASAN_OPTIONS=\"$ASAN_OPTIONS:detect_leaks=0\" '") +
                            RILL_MPIEXEC + "' --oversubscribe";
#else
#define RT_REQUIRE_MPI() GTEST_SKIP() << "rill-trace was built without MPI (RILL_MPI off)"
const std::string kMpirun;
#endif

bool has(const std::string& text, const std::string& needle) {
  return text.find(needle) != std::string::npos;
}

// The options naming every output, each file name starting with `name`.
std::string outputs(const std::string& name) {
  return " --out " + name + ".png --pfm " + name + ".pfm --depth " + name + "-depth.pfm --prim " +
         name + "-prim.pfm --normal " + name + "-normal.pfm --exr " + name + ".exr";
}
const char* const kSuffixes[] = {".png", ".pfm", "-depth.pfm", "-prim.pfm", "-normal.pfm", ".exr"};

void expect_same_files(const TempDir& dir, const std::string& want, const std::string& got,
                       const char* const* suffixes, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    const std::string a = read_text(dir.path(want + suffixes[i]));
    const std::string b = read_text(dir.path(got + suffixes[i]));
    EXPECT_FALSE(a.empty()) << want << suffixes[i];
    EXPECT_TRUE(a == b) << got << suffixes[i] << " differs from " << want << suffixes[i];
  }
}

// The tiles of a job: `tile` pixels square, the last (twice as many as ranks) cut to `tail`
// (TileQueue.h, tested on its own).
int tile_count(int width, int height, int tile, int tail, int ranks, int frames) {
  std::vector<rt::distributed::Tile> tiles =
      rt::distributed::make_tiles(width, height, tile, 0, frames);
  if (tail > 0 && tail < tile)
    rt::distributed::split_tail(tiles, std::min(2 * ranks, static_cast<int>(tiles.size()) / 2),
                                tail);
  return static_cast<int>(tiles.size());
}

class Distributed : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // mpirun refuses root without these; CI runs as root. Set here only, not in the docs.
    setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 1);
    setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 1);
    // Shared-memory messages without Linux's cross-memory attach, which containers without
    // ptrace rights may refuse (large messages, the tiles, would fail there).
    setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 1);
  }
};

TEST_F(Distributed, IdenticalToSingleProcessWhateverRanksAndTiles) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string scene =
      " render builtin:glass --size 48x36 --spp 2 --max-depth 3 --threads 1 --quiet";
  Result ref = run_command(kExe + scene + outputs("ref"), dir);
  ASSERT_EQ(ref.status, 0) << ref.err;
  // 12 divides 48x36; 7 divides neither side. The last tiles cut into tiles of 5 (which
  // divides neither 12 nor 7), or not cut.
  for (auto [ranks, tile, tail] : {std::tuple{2, 12, 0}, {3, 12, 5}, {2, 7, 5}, {3, 7, 0}}) {
    const std::string name = "np" + std::to_string(ranks) + "-tile" + std::to_string(tile) +
                             "-tail" + std::to_string(tail);
    SCOPED_TRACE(name);
    Result r = run_command(kMpirun + " -np " + std::to_string(ranks) + " " + kExe + scene +
                               outputs(name) + " --tile " + std::to_string(tile) + " --tail-tile " +
                               std::to_string(tail) + " --stats-json " + name + ".json",
                           dir, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_files(dir, "ref", name, kSuffixes, std::size(kSuffixes));
    const nlohmann::json j = nlohmann::json::parse(read_text(dir.path(name + ".json")));
    const nlohmann::json& d = j.at("distributed");
    const int tiles = tile_count(48, 36, tile, tail, ranks, 1);
    EXPECT_EQ(d.at("ranks"), ranks);
    EXPECT_EQ(d.at("tiles"), tiles);
    EXPECT_EQ(d.at("tiles_done"), tiles);
    EXPECT_TRUE(d.at("complete").get<bool>());
    int sum = 0;
    for (const nlohmann::json& rank : d.at("per_rank")) {
      sum += rank.at("tiles").get<int>();
      EXPECT_FALSE(rank.at("host").get<std::string>().empty());
      EXPECT_EQ(rank.at("lost"), "");
      EXPECT_GE(rank.at("busy_ms").get<double>(), 0.0);
    }
    EXPECT_EQ(sum, tiles);
    EXPECT_GE(d.at("imbalance").get<double>(), 0.0);
    // Every tile once, with the rank that rendered it, a time and where it is; the tiles
    // cover the image once.
    std::vector<int> seen(static_cast<size_t>(tiles), 0);
    std::vector<int> covered(48 * 36, 0);
    for (const nlohmann::json& t : d.at("per_tile")) {
      const int id = t.at(0).get<int>(), rank = t.at(1).get<int>();
      ASSERT_TRUE(id >= 0 && id < tiles) << t;
      EXPECT_TRUE(rank >= 0 && rank < ranks) << t;
      EXPECT_GE(t.at(2).get<double>(), 0.0);
      ++seen[static_cast<size_t>(id)];
      const int x = t.at(3), y = t.at(4), w = t.at(5), h = t.at(6);
      ASSERT_TRUE(x >= 0 && y >= 0 && w >= 1 && h >= 1 && x + w <= 48 && y + h <= 36) << t;
      for (int py = y; py < y + h; ++py)
        for (int px = x; px < x + w; ++px) ++covered[static_cast<size_t>(py * 48 + px)];
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), tiles);
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), 48 * 36);
    // Rank 0's part in it: every worker tile came through its queue.
    EXPECT_EQ(d.at("gather").at("tiles").get<int>() + d.at("per_rank").at(0).at("tiles").get<int>(),
              tiles);
  }
  // The multipass strategy, tiles of 5 on a 40x30 image.
  const std::string cornell = " render builtin:cornell --strategy multipass --size 40x30 --quiet";
  ASSERT_EQ(run_command(kExe + cornell + outputs("c-ref"), dir).status, 0);
  Result r =
      run_command(kMpirun + " -np 3 " + kExe + cornell + outputs("c") + " --tile 5", dir, 120);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_files(dir, "c-ref", "c", kSuffixes, std::size(kSuffixes));
  // An animated scene: its first frame, as a single process renders it.
  const std::string bounce = " render builtin:bounce --size 40x30 --quiet";
  ASSERT_EQ(run_command(kExe + bounce + outputs("b-ref"), dir).status, 0);
  r = run_command(kMpirun + " -np 3 " + kExe + bounce + outputs("b") + " --tile 9", dir, 120);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_files(dir, "b-ref", "b", kSuffixes, std::size(kSuffixes));
  // The path integrator: each pixel's random numbers are keyed by its image coordinates, so a
  // tile's pixels are the single process's (docs/path-tracing.md).
  const std::string path = " render builtin:cornell-path --size 40x30 --spp 3 --quiet";
  ASSERT_EQ(run_command(kExe + path + outputs("p-ref"), dir).status, 0);
  r = run_command(kMpirun + " -np 3 " + kExe + path + outputs("p") + " --tile 7", dir, 120);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_same_files(dir, "p-ref", "p", kSuffixes, std::size(kSuffixes));
}

// The path integrator's albedo (--albedo, and its channels in --exr) and variance (--variance:
// var.* channels in --exr) come back with each tile: the files are the single process's, byte
// for byte, so every EXR channel bit for bit. Tiles of 7 divide neither side; 3 samples, so
// the variance is not 0.
TEST_F(Distributed, AlbedoAndVarianceAreTheSingleProcesss) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --size 40x30 --spp 3 --quiet --variance";
  auto albedo = [](const std::string& name) { return " --albedo " + name + "-albedo.pfm"; };
  const char* const suffixes[] = {".png",        ".pfm", "-depth.pfm", "-prim.pfm",
                                  "-normal.pfm", ".exr", "-albedo.pfm"};
  Result ref = run_command(kExe + path + outputs("ref") + albedo("ref"), dir);
  ASSERT_EQ(ref.status, 0) << ref.err;
  // The reference has the channels asked for (else the comparison would prove little).
  const std::string exr = read_text(dir.path("ref.exr"));
  EXPECT_TRUE(has(exr, "var.R") && has(exr, "albedo.R"));
  for (int ranks : {2, 3}) {
    const std::string name = "np" + std::to_string(ranks);
    SCOPED_TRACE(name);
    Result r = run_command(kMpirun + " -np " + std::to_string(ranks) + " " + kExe + path +
                               outputs(name) + albedo(name) + " --tile 7 --tail-tile 3",
                           dir, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_files(dir, "ref", name, suffixes, std::size(suffixes));
  }
}

// The samples per pixel a progressive render reports on stdout ("path: N samples per pixel"),
// or -1.
int reported_spp(const std::string& out) {
  const size_t at = out.find("path: ");
  int spp = -1;
  if (at == std::string::npos || std::sscanf(out.c_str() + at, "path: %d", &spp) != 1) return -1;
  return spp;
}

// Every output of a path-traced render, the albedo and the variance (in the EXR) included.
std::string path_outputs(const std::string& name) {
  return outputs(name) + " --albedo " + name + "-albedo.pfm";
}
const char* const kPathSuffixes[] = {".png",        ".pfm", "-depth.pfm", "-prim.pfm",
                                     "-normal.pfm", ".exr", "-albedo.pfm"};

// A progressive render under mpirun goes in rounds (docs/distributed.md, "Rounds"): each
// round a job over every tile, each tile going on from its slice of the sums rank 0 keeps.
// The image, every AOV (sample 0's), the variance and the saved sums are the single-process
// render's of the same spp, byte for byte: rounds of --save-every 2 (2, 4, 6, 7), and rounds
// doubling under a time limit that is never reached (1, 3, 7), for 2 and 3 ranks and tiles of 7,
// which divide neither side.
TEST_F(Distributed, RoundsAreTheSingleProcesssRenderAndSums) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path =
      " render builtin:cornell-path --size 40x30 --spp 7 --threads 1 --quiet --variance";
  Result ref = run_command(kExe + path + path_outputs("ref") + " --save ref.acc", dir);
  ASSERT_EQ(ref.status, 0) << ref.err;
  const std::string sums = read_text(dir.path("ref.acc"));
  ASSERT_EQ(sums.substr(0, 8), "RILLACC2");  // with the squares, for the variance
  // The AOVs (so every round's, below) are sample 0's: those of the render of one sample.
  const std::string one = " render builtin:cornell-path --size 40x30 --spp 1 --threads 1 --quiet";
  ASSERT_EQ(run_command(kExe + one + path_outputs("one"), dir).status, 0);
  const char* const kAovSuffixes[] = {"-depth.pfm", "-prim.pfm", "-normal.pfm", "-albedo.pfm"};
  expect_same_files(dir, "one", "ref", kAovSuffixes, std::size(kAovSuffixes));
  for (auto [ranks, rounds] :
       {std::pair{2, std::string("--save-every 2")}, {3, std::string("--time-limit 100000")}}) {
    const std::string name = "np" + std::to_string(ranks);
    SCOPED_TRACE(name + " " + rounds);
    Result r = run_command(kMpirun + " -np " + std::to_string(ranks) + " " + kExe + path +
                               path_outputs(name) + " --tile 7 --tail-tile 3 --save " + name +
                               ".acc --stats-json " + name + ".json " + rounds,
                           dir, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    expect_same_files(dir, "ref", name, kPathSuffixes, std::size(kPathSuffixes));
    EXPECT_TRUE(read_text(dir.path(name + ".acc")) == sums) << name << ".acc differs";
    const nlohmann::json j = nlohmann::json::parse(read_text(dir.path(name + ".json")));
    std::vector<int> reached;
    for (const nlohmann::json& round : j.at("distributed").at("rounds"))
      reached.push_back(round.at("spp").get<int>());
    EXPECT_EQ(reached, ranks == 2 ? std::vector<int>({2, 4, 6, 7}) : std::vector<int>({1, 3, 7}));
    EXPECT_EQ(j.at("spp_reached"), 7);
  }
}

// A render saved by one process goes on under mpirun, and one saved under mpirun goes on in
// one process: either way the image and the sums are those rendered at once, byte for byte.
TEST_F(Distributed, ResumeAcrossOneAndManyProcessesIsBitwise) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --size 40x30 --threads 1 --variance";
  ASSERT_EQ(run_command(kExe + path + " --spp 7 --quiet --save ref.acc" + path_outputs("ref"), dir)
                .status,
            0);
  // --variance (which needs --exr) keeps the squares in the saved sums.
  ASSERT_EQ(run_command(kExe + path + " --spp 3 --quiet --save one.acc --exr one.exr", dir).status,
            0);
  Result many =
      run_command(kMpirun + " -np 2 " + kExe + path +
                      " --spp 7 --resume one.acc --save many.acc --tile 9" + path_outputs("many"),
                  dir, 120);
  ASSERT_EQ(many.status, 0) << many.err;
  EXPECT_EQ(reported_spp(many.out), 7) << many.out;
  EXPECT_TRUE(has(many.out, "(3 resumed)")) << many.out;
  expect_same_files(dir, "ref", "many", kPathSuffixes, std::size(kPathSuffixes));
  EXPECT_TRUE(read_text(dir.path("many.acc")) == read_text(dir.path("ref.acc")));

  Result saved = run_command(kMpirun + " -np 3 " + kExe + path +
                                 " --spp 3 --quiet --save three.acc --exr three.exr --tile 9",
                             dir, 120);
  ASSERT_EQ(saved.status, 0) << saved.err;
  EXPECT_TRUE(read_text(dir.path("three.acc")) == read_text(dir.path("one.acc")));
  Result one = run_command(
      kExe + path + " --spp 7 --quiet --resume three.acc --save again.acc" + path_outputs("again"),
      dir);
  ASSERT_EQ(one.status, 0) << one.err;
  expect_same_files(dir, "ref", "again", kPathSuffixes, std::size(kPathSuffixes));
  EXPECT_TRUE(read_text(dir.path("again.acc")) == read_text(dir.path("ref.acc")));
}

// --time-limit: rank 0 stops after the round that crosses it, says how many samples per
// pixel the image has (fewer than the target, which no machine reaches in the limit), and the
// image and its variance are the single-process render of that many, byte for byte.
TEST_F(Distributed, TimeLimitStopsAfterARoundAtTheSingleProcesssImage) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --size 40x30 --threads 1 --variance";
  for (int ranks : {2, 3}) {
    const std::string name = "np" + std::to_string(ranks);
    SCOPED_TRACE(name);
    Result r = run_command(kMpirun + " -np " + std::to_string(ranks) + " " + kExe + path +
                               " --spp 1048576 --time-limit 1 --tile 11 --save " + name +
                               ".acc --stats-json " + name + ".json" + path_outputs(name),
                           dir, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(has(r.out, "stopped by --time-limit")) << r.out;
    const int spp = reported_spp(r.out);
    ASSERT_GE(spp, 1) << r.out;
    ASSERT_LT(spp, 1048576) << r.out;
    const nlohmann::json j = nlohmann::json::parse(read_text(dir.path(name + ".json")));
    EXPECT_EQ(j.at("spp_reached"), spp);
    EXPECT_EQ(j.at("distributed").at("rounds").back().at("spp"), spp);
    Result ref = run_command(kExe + path + " --quiet --spp " + std::to_string(spp) + " --save ref" +
                                 name + ".acc" + path_outputs("ref" + name),
                             dir, 120);
    ASSERT_EQ(ref.status, 0) << ref.err;
    expect_same_files(dir, "ref" + name, name, kPathSuffixes, std::size(kPathSuffixes));
    EXPECT_TRUE(read_text(dir.path(name + ".acc")) == read_text(dir.path("ref" + name + ".acc")));
  }
}

// A worker killed with kill -9 in the middle of the rounds, under mpirun --enable-recovery:
// rank 0 finds it silent, its tiles of the round in flight go to the other ranks, the rounds
// after go on without it, and the image and the sums are still the single process's. It is
// killed once the first round's sums are on disk (--save-every), so in a later round (of
// 12, which take a second or more).
TEST_F(Distributed, AWorkerKilledInARoundIsLostAndTheRoundsComplete) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --size 120x90 --spp 96 --threads 1";
  ASSERT_EQ(
      run_command(kExe + path + " --quiet --save ref.acc --out ref.png --pfm ref.pfm", dir, 120)
          .status,
      0);
  const std::string job = path +
                          " --save-every 8 --save g.acc --tile 8 --rank-timeout 2"
                          " --out g.png --pfm g.pfm --stats-json g.json --quiet";
  dir.file("kill.sh",
           "(n=0; while [ ! -e g.acc ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n + 1)); done; "
           "kill -KILL $$) &\nexec " +
               kExe + " \"$@\"\n");
  Result r = run_command(kMpirun + " --enable-recovery -np 2 " + kExe + job + " : -np 1 sh " +
                             dir.path("kill.sh") + job,
                         dir, 180);
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  EXPECT_TRUE(has(r.err, "rill-trace: warning: rank 2 on ")) << r.err;
  EXPECT_TRUE(has(r.err, "is lost (sent nothing for 2 s")) << r.err;
  expect_same_files(dir, "ref", "g", kSuffixes, 2);
  EXPECT_TRUE(read_text(dir.path("g.acc")) == read_text(dir.path("ref.acc")));
  const nlohmann::json j = nlohmann::json::parse(read_text(dir.path("g.json")));
  EXPECT_EQ(j.at("distributed").at("rounds").size(), 12u);
  EXPECT_NE(j.at("distributed").at("per_rank").at(2).at("lost"), "");
}

// SIGINT to rank 0 in a round: the job stops as any interrupted render does (exit 130,
// partial outputs), and --save keeps the sums of the rounds complete, from which one process
// goes on to the image rendered at once, bitwise. The signal comes once the first round's sums
// are on disk (--save-every), so in a later round.
TEST_F(Distributed, SigintInARoundSavesTheRoundsComplete) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --size 120x90 --spp 96 --threads 1";
  ASSERT_EQ(run_command(kExe + path + " --quiet --out ref.png --pfm ref.pfm", dir, 120).status, 0);
  const std::string job =
      path + " --save-every 8 --save s.acc --tile 8 --out g.png --pfm g.pfm --quiet";
  dir.file("rank0.sh", "echo $$ > rank0.pid\nexec " + kExe + " \"$@\"\n");
  dir.file("interrupt.sh",
           kMpirun + " -np 1 sh rank0.sh" + job + " : -np 1 " + kExe + job +
               " &\nm=$!\nn=0\nwhile [ ! -e s.acc ] && [ $n -lt 1200 ]; "
               "do sleep 0.05; n=$((n + 1)); done\nkill -INT $(cat rank0.pid)\nwait $m\n");
  Result r = run_command("sh interrupt.sh", dir, 180);
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  ASSERT_FALSE(std::filesystem::exists(dir.path("g.png"))) << "ended before the signal";
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_TRUE(has(r.err, "interrupted by SIGINT sent to rank 0")) << r.err;
  EXPECT_TRUE(has(r.err, "rounds complete to s.acc")) << r.err;
  Result resumed =
      run_command(kExe + path + " --quiet --resume s.acc --out g.png --pfm g.pfm", dir, 120);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  expect_same_files(dir, "ref", "g", kSuffixes, 2);
}

// A --resume file that does not fit the render is refused by rank 0 before any tile, with the
// single process's message naming the file (no rank prefix: rank 0 read it); so are rounds
// of an image sequence or of an animated scene (one still frame only, as in one process).
TEST_F(Distributed, AResumeFileThatDoesNotFitIsRefusedByRankZero) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string path = " render builtin:cornell-path --threads 1 --quiet";
  ASSERT_EQ(run_command(kExe + path + " --size 16x12 --spp 2 --save s.acc", dir).status, 0);
  for (auto [options, message] :
       {std::pair{std::string(" --size 20x12 --spp 4"),
                  std::string("s.acc: saved at 16x12, the render is 20x12")},
        {" --size 16x12 --spp 4 --seed 9", "s.acc: saved with seed "},
        {" --size 16x12 --spp 4 --max-depth 2", "s.acc: saved from another scene"},
        {" --size 16x12 --spp 1", "s.acc: holds 2 samples per pixel, more than the 1"},
        {" --size 16x12 --spp 4 --variance --exr v.exr", "s.acc: saved without --variance"}}) {
    SCOPED_TRACE(options);
    Result r = run_command(
        kMpirun + " -np 2 " + kExe + path + options + " --resume s.acc --out o.png", dir, 60);
    ASSERT_NE(r.status, 124) << "hung: " << r.err;
    EXPECT_NE(r.status, 0);
    EXPECT_TRUE(has(r.err, "rill-trace: " + message)) << r.err;  // rank 0's, unprefixed
    EXPECT_FALSE(has(r.err, "rank 1 on")) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("o.png")));
  }
  // builtin:bounce is animated: a still of it too renders one frame of many.
  for (const std::string& frames :
       {std::string(" --frames 0:1 --out f-%04d.png"), std::string(" --out f.png")}) {
    Result r = run_command(kMpirun + " -np 2 " + kExe +
                               " render builtin:bounce --size 16x12 --integrator path --quiet "
                               "--save f.acc" +
                               frames,
                           dir, 60);
    EXPECT_NE(r.status, 0);
    EXPECT_TRUE(has(r.err, "render one still frame")) << r.err;
  }
}

// An image sequence (--frames) over the ranks: every frame's files are the single process's,
// named as it names them, rebuilding or refitting the BVH, however the frames' tiles fall on
// the ranks; the stats list each frame once.
TEST_F(Distributed, FramesAreTheSingleProcesssFiles) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string bounce = " render builtin:bounce --size 40x30 --frames 6:9 --quiet";
  auto named = [](const std::string& name) {
    return " --out " + name + "-%04d.png --depth " + name + "-depth-%02d.pfm --prim " + name +
           "-prim-%02d.pfm";
  };
  Result ref = run_command(kExe + bounce + named("ref"), dir);
  ASSERT_EQ(ref.status, 0) << ref.err;
  for (auto [ranks, tile, bvh] : {std::tuple{3, 9, "rebuild"}, {2, 40, "refit"}}) {
    const std::string name = "np" + std::to_string(ranks) + "-" + bvh;
    SCOPED_TRACE(name);
    Result r = run_command(kMpirun + " -np " + std::to_string(ranks) + " " + kExe + bounce +
                               named(name) + " --tile " + std::to_string(tile) + " --bvh " + bvh +
                               " --stats-json " + name + ".json",
                           dir, 120);
    ASSERT_EQ(r.status, 0) << r.err;
    for (int f = 6; f <= 9; ++f) {
      char png[16], pfm[16];
      std::snprintf(png, sizeof png, "-%04d.png", f);
      std::snprintf(pfm, sizeof pfm, "-%02d.pfm", f);
      const std::string suffixes[] = {png, std::string("-depth") + pfm, std::string("-prim") + pfm};
      for (const std::string& suffix : suffixes) {
        const std::string a = read_text(dir.path("ref" + suffix));
        EXPECT_FALSE(a.empty()) << "ref" << suffix;
        EXPECT_TRUE(a == read_text(dir.path(name + suffix))) << name << suffix << " differs";
      }
    }
    EXPECT_FALSE(std::filesystem::exists(dir.path(name + "-0010.png")));
    const nlohmann::json j = nlohmann::json::parse(read_text(dir.path(name + ".json")));
    EXPECT_EQ(j.at("distributed").at("tiles"),
              tile_count(40, 30, tile, tile >= 16 ? tile / 2 : 0, ranks, 4));
    EXPECT_TRUE(j.at("distributed").at("complete").get<bool>());
    std::vector<int> frames;
    for (const nlohmann::json& f : j.at("frames")) frames.push_back(f.at("frame").get<int>());
    std::sort(frames.begin(), frames.end());
    EXPECT_EQ(frames, (std::vector<int>{6, 7, 8, 9}));
  }
  // A sequence without frame numbers in its names is refused at the start, by every rank.
  Result bad = run_command(kMpirun + " -np 2 " + kExe + bounce + " --out same.png", dir, 120);
  ASSERT_NE(bad.status, 124) << "hung: " << bad.err;
  EXPECT_NE(bad.status, 0);
  EXPECT_TRUE(has(bad.err, "--out needs a frame number")) << bad.err;
}

// A render long enough to kill a worker in the middle of it: the single-process reference
// (ref.png, ref.pfm), and how long it took.
class KilledWorker : public Distributed {
 protected:
  static constexpr const char* kScene =
      " render builtin:glass --size 160x120 --spp 32 --threads 1 --tile 16 --rank-timeout 2"
      " --out g.png --pfm g.pfm --stats-json g.json --checkpoint 0.2";

  void SetUp() override {
    RT_REQUIRE_MPI();
    const auto t0 = std::chrono::steady_clock::now();
    Result ref = run_command(kExe +
                                 " render builtin:glass --size 160x120 --spp 32 --threads 1 "
                                 "--out ref.png --pfm ref.pfm --quiet",
                             dir_);
    ASSERT_EQ(ref.status, 0) << ref.err;
    reference_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // Rank 2 is killed (kill -9, from outside the program) once rank 0 has written its first
    // checkpoint: the render is under way, with tiles done, and far from done (the
    // checkpoints come every 0.2 s of a render of several seconds). A fixed delay could land
    // before the first tile on a loaded machine, where start-up (MPI, the scene, kernels
    // from the cache) takes longer than a share of the single process's time. (The wait
    // ends after 30 s, or when the whole image is there: the test then says the render
    // ended first.)
    // The same with SIGSTOP: a rank that hangs.
    for (const char* signal : {"KILL", "STOP"})
      dir_.file(
          std::string(signal) + ".sh",
          std::string("echo $$ > rank2.pid\n(n=0; while [ ! -e g.partial.png ] && [ ! -e "
                      "g.png ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n + 1)); done; kill -") +
              signal + " $$) &\nexec " + kExe + " \"$@\"\n");
  }
  Result run_with_killed_rank(const std::string& mpirun_options, const char* signal = "KILL",
                              int timeout_s = 120) {
    return run_command(kMpirun + mpirun_options + " -np 2 " + kExe + kScene + " : -np 1 sh " +
                           dir_.path(std::string(signal) + ".sh") + kScene,
                       dir_, timeout_s);
  }

  TempDir dir_;
  double reference_s_ = 0;
};

// Plain mpirun ends the job when a rank dies: a clear error naming the rank and host, and
// the tiles done so far as a partial image with a note (the last checkpoint, or what rank 0
// wrote on SIGTERM if mpirun left it the time).
TEST_F(KilledWorker, EndsWithAClearErrorAndAPartialImage) {
  Result r = run_with_killed_rank("");
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  ASSERT_NE(r.status, 0) << "the render ended before the worker was killed (it took "
                         << reference_s_ << " s alone); stdout: " << r.out;
  EXPECT_TRUE(has(r.err, "noticed that process rank 2")) << r.err;  // mpirun or mpiexec
  EXPECT_TRUE(has(r.err, "on node ")) << r.err;
  EXPECT_TRUE(has(r.err, "signal 9")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir_.path("g.png")));
  ASSERT_TRUE(std::filesystem::exists(dir_.path("g.partial.png"))) << r.err;
  EXPECT_GT(std::filesystem::file_size(dir_.path("g.partial.png")), 0u);
  EXPECT_GT(std::filesystem::file_size(dir_.path("g.partial.pfm")), 0u);
  const std::string note = read_text(dir_.path("g.partial.txt"));
  int done = -1, total = -1;
  const size_t at = note.find("tiles in the image: ");
  ASSERT_NE(at, std::string::npos) << note;
  ASSERT_EQ(std::sscanf(note.c_str() + at, "tiles in the image: %d of %d;", &done, &total), 2);
  EXPECT_EQ(total, tile_count(160, 120, 16, 8, 3, 1));  // 80 of 16, the last 6 cut: 86
  EXPECT_GT(done, 0) << note;
  EXPECT_LT(done, total) << note;
  EXPECT_TRUE(has(note, "missing tiles (x y width height):\n")) << note;
}

// SIGINT sent to rank 0 itself (not by mpirun): rank 0 says it was interrupted (not that a
// rank died), writes the tiles done as partial outputs, stops the other ranks, and the job
// ends with 130 (128 + SIGINT), no temporary file (NAME.partial-PID) left. On main, rank 0
// said "stopped by a signal: mpirun ends the job when a rank dies" and left the worker to
// mpirun's kill.
TEST_F(Distributed, SigintToRankZeroStopsTheJobAndSaysInterrupted) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string scene =
      " render builtin:glass --size 160x120 --spp 512 --threads 1 --tile 16 --out g.png "
      "--pfm g.pfm --checkpoint 0.2";
  // Rank 0 records its pid; the signal is sent once its first checkpoint is on disk (the
  // render under way), from this shell, which is not rank 0's parent.
  dir.file("rank0.sh", "echo $$ > rank0.pid\nexec " + kExe + " \"$@\"\n");
  dir.file("interrupt.sh",
           kMpirun + " -np 1 sh rank0.sh" + scene + " : -np 1 " + kExe + scene +
               " &\nm=$!\nn=0\nwhile [ ! -e g.partial.png ] && [ ! -e g.png ] && [ $n -lt 1200 ]; "
               "do sleep 0.05; n=$((n + 1)); done\nkill -INT $(cat rank0.pid)\nwait $m\n");
  const auto t0 = std::chrono::steady_clock::now();
  Result r = run_command("sh interrupt.sh", dir, 180);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  ASSERT_FALSE(std::filesystem::exists(dir.path("g.png"))) << "ended before the signal";
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_TRUE(has(r.err, "interrupted by SIGINT sent to rank 0; the other ranks were stopped"))
      << r.err;
  EXPECT_FALSE(has(r.err, "when a rank dies")) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("g.partial.png"))) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.path("g.partial.txt"))) << r.err;
  for (const auto& e : std::filesystem::directory_iterator(dir.dir()))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos)
        << e.path().filename();
  std::printf("interrupted job: %.1f s in all\n", s);
}

// With mpirun --enable-recovery the job goes on: rank 0 finds the rank silent, gives its
// tiles to the others, and the image is the single-process one.
TEST_F(KilledWorker, WithRecoveryTheImageCompletes) {
  Result r = run_with_killed_rank(" --enable-recovery");
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  EXPECT_TRUE(has(r.err, "rill-trace: warning: rank 2 on ")) << r.err;
  EXPECT_TRUE(has(r.err, "is lost (sent nothing for 2 s")) << r.err;
  expect_same_files(dir_, "ref", "g", kSuffixes, 2);
  const nlohmann::json j = nlohmann::json::parse(read_text(dir_.path("g.json")));
  const nlohmann::json& d = j.at("distributed");
  EXPECT_TRUE(d.at("complete").get<bool>());
  EXPECT_NE(d.at("per_rank").at(2).at("lost"), "");
  EXPECT_EQ(d.at("per_rank").at(0).at("lost"), "");
  // The checkpoints are gone with the whole image written.
  EXPECT_FALSE(std::filesystem::exists(dir_.path("g.partial.png")));
  EXPECT_FALSE(std::filesystem::exists(dir_.path("g.partial.txt")));
}

// A rank that hangs (stopped) is not dead to mpirun, so the job goes on without any option:
// rank 0 finds it silent, the others render its tiles, rank 0 writes the image and ends the
// job with MPI_Abort (MPI_Finalize would wait for the stopped rank). What mpirun does then is
// Open MPI's: 4.1.4 at times crashes (PMIx_server_finalize) or hangs while it ends a job with
// a stopped process, so its exit status is not checked, and a hang of mpirun alone ends with
// the timeout here.
TEST_F(KilledWorker, AHungWorkerIsLostAndTheImageCompletes) {
  Result r = run_with_killed_rank("", "STOP", 40);
  // The stopped rank, if mpirun left it behind.
  const std::string pid = read_text(dir_.path("rank2.pid"));
  if (!pid.empty()) std::system(("kill -9 " + pid + " 2> /dev/null").c_str());
  EXPECT_TRUE(has(r.err, "rill-trace: warning: rank 2 on ")) << r.err;
  EXPECT_TRUE(has(r.err, "is lost (sent nothing for 2 s")) << r.err;
  EXPECT_TRUE(has(r.err, "ending the job with MPI_Abort")) << r.err;
  expect_same_files(dir_, "ref", "g", kSuffixes, 2);
}

// An image sequence with a worker killed part of the way: the frames complete before the
// fault are written whole (the single process's bytes) with no partial left beside them; a
// frame begun and not complete is kept as partial outputs with its own note; frames not begun
// are not written.
TEST_F(Distributed, AKilledWorkerInASequenceKeepsTheFramesDone) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string bounce =
      " render builtin:bounce --size 160x120 --spp 32 --frames 0:5 --threads 1 --quiet";
  const auto t0 = std::chrono::steady_clock::now();
  Result ref = run_command(kExe + bounce + " --out ref-%02d.png", dir);
  ASSERT_EQ(ref.status, 0) << ref.err;
  const double reference_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  dir.file("kill.sh", "(sleep " + std::to_string(std::max(0.8, reference_s / 3)) +
                          "; kill -KILL $$) &\nexec " + kExe + " \"$@\"\n");
  const std::string options = bounce + " --out s-%02d.png --tile 12 --checkpoint 0.2";
  Result r = run_command(
      kMpirun + " -np 2 " + kExe + options + " : -np 1 sh " + dir.path("kill.sh") + options, dir,
      120);
  ASSERT_NE(r.status, 124) << "hung: " << r.err;
  ASSERT_NE(r.status, 0) << "the sequence ended before the worker was killed (it took "
                         << reference_s << " s alone)";
  int whole = 0, partial = 0;
  for (int f = 0; f <= 5; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "s-%02d", f);
    const bool done = std::filesystem::exists(dir.path(std::string(name) + ".png"));
    const bool part = std::filesystem::exists(dir.path(std::string(name) + ".partial.png"));
    SCOPED_TRACE(name);
    EXPECT_FALSE(done && part);
    if (done) {
      ++whole;
      std::snprintf(name, sizeof name, "ref-%02d.png", f);
      const std::string want = read_text(dir.path(name));
      std::snprintf(name, sizeof name, "s-%02d.png", f);
      EXPECT_TRUE(want == read_text(dir.path(name))) << name << " differs from the reference";
    }
    if (part) {
      ++partial;
      std::snprintf(name, sizeof name, "s-%02d.partial.txt", f);
      const std::string note = read_text(dir.path(name));
      EXPECT_TRUE(has(note, ", frame " + std::to_string(f) + ", 160x120")) << note;
      EXPECT_TRUE(has(note, "tiles in the image: ")) << note;
    }
  }
  EXPECT_GT(whole + partial, 0) << r.err;
  EXPECT_LT(whole, 6) << r.err;
}

// Rank 2 loads another scene, other settings, or nothing: the job stops before any tile,
// with rank 2's message.
TEST_F(Distributed, AnotherSceneOrAFailedLoadStopsTheStart) {
  RT_REQUIRE_MPI();
  TempDir dir;
  const std::string a = " render builtin:thesis-a --size 30x20 --out m.png";
  struct Case {
    std::string rank2, message;
  } cases[] = {
      {" render builtin:thesis-b --size 30x20 --out m.png", "loaded another scene than rank 0"},
      {a + " --spp 2", "loaded another scene than rank 0"},
      {" render builtin:nope --size 30x20 --out m.png", "unknown built-in scene 'nope'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.rank2);
    Result r = run_command(kMpirun + " -np 2 " + kExe + a + " : -np 1 " + kExe + c.rank2, dir, 120);
    ASSERT_NE(r.status, 124) << "hung: " << r.err;
    EXPECT_NE(r.status, 0) << r.err;
    EXPECT_TRUE(has(r.err, "rill-trace: rank 2 on ")) << r.err;
    EXPECT_TRUE(has(r.err, c.message)) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("m.png")));
  }
}

// Ranks on different backends give the same bytes under strict; a rank whose backend fails
// at its first tile (an OpenCL device that is not there) is lost with its message, and the
// others complete the image without it.
TEST_F(Distributed, MixedBackendsAndARankWhoseRenderFails) {
  RT_REQUIRE_MPI();
  RT_REQUIRE_BACKEND("opencl");
  TempDir dir;
  const std::string scene =
      " render builtin:thesis-a --size 60x40 --quiet --tile 8 --rank-timeout 5";
  ASSERT_EQ(run_command(kExe + scene + outputs("ref"), dir).status, 0);
  Result mixed = run_command(kMpirun + " -np 2 " + kExe + scene + outputs("mixed") + " : -np 1 " +
                                 kExe + scene + outputs("mixed") + " --backend opencl",
                             dir, 120);
  ASSERT_EQ(mixed.status, 0) << mixed.err;
  expect_same_files(dir, "ref", "mixed", kSuffixes, std::size(kSuffixes));
  Result failed =
      run_command(kMpirun + " -np 2 " + kExe + scene + outputs("failed") + " : -np 1 " + kExe +
                      scene + outputs("failed") + " --backend opencl --device 7:7",
                  dir, 120);
  ASSERT_EQ(failed.status, 0) << failed.err;
  EXPECT_TRUE(has(failed.err, "rill-trace: warning: rank 2 on ")) << failed.err;
  EXPECT_TRUE(has(failed.err, "is lost (rendering failed: ")) << failed.err;
  EXPECT_TRUE(has(failed.err, "7:7")) << failed.err;
  expect_same_files(dir, "ref", "failed", kSuffixes, std::size(kSuffixes));
}

// Without MPI in the build, a process started by a launcher as one of several refuses to
// render the whole image beside the others.
TEST(DistributedWithoutMpi, ALaunchedProcessIsAClearError) {
#if RILL_HAVE_MPI
  GTEST_SKIP() << "rill-trace was built with MPI; this checks a build without it";
#else
  TempDir dir;
  Result r = run_command(
      "env OMPI_COMM_WORLD_SIZE=3 " + kExe + " render builtin:thesis-a --size 8x8", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_TRUE(has(r.err, "built without MPI")) << r.err;
#endif
}

}  // namespace
}  // namespace rt::testing
