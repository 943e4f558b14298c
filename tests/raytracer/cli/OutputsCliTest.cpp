// rill-trace render's output files (apps/rill-trace/Outputs.h, OutputPaths.h): every write
// error ends in a non-zero exit naming the file; no output is another output or an input by
// any spelling; an output's extension is its format; a FIFO without a reader is an error at
// once; an empty value is never an option's absence.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "RunCommand.h"
#include "TestUtil.h"
#include "rill/rt/scene/Image.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

namespace fs = std::filesystem;
using testing::TempDir;

testing::Run trace(const std::string& args, const TempDir& dir, int timeout_s = 60) {
  return testing::run_command("'" RILL_TRACE_EXE "' " + args, dir, timeout_s);
}

// One line on stderr, "rill-trace: " and the message, which holds `needle`.
void expect_error(const testing::Run& r, const std::string& needle, const std::string& args) {
  SCOPED_TRACE(args);
  EXPECT_TRUE(r.status == 1 || r.status == 2) << "status " << r.status << ": " << r.err;
  EXPECT_EQ(r.err.rfind("rill-trace: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

// Every output, written to a device that takes no bytes: exit 1, the file and the reason
// named, and the device still there (libpng removed the file it could not write: as root,
// --out /dev/full deleted /dev/full, and every later run wrote a regular file there and
// exited 0).
TEST(CliOutputs, EveryOutputReportsAWriteError) {
  TempDir dir;
  const std::string full = testing::full_device(dir);
  const char* whitted = "render builtin:thesis-a --size 8x6 --quiet --out /dev/null ";
  const char* path = "render builtin:cornell-path --size 8x6 --spp 1 --quiet --out /dev/null ";
  const std::vector<std::string> commands = {
      std::string("render builtin:thesis-a --size 8x6 --quiet --out ") + full,
      whitted + std::string("--pfm ") + full,
      whitted + std::string("--depth ") + full,
      whitted + std::string("--prim ") + full,
      whitted + std::string("--normal ") + full,
      whitted + std::string("--exr ") + full,
      whitted + std::string("--stats-json ") + full,
      whitted + std::string("--source ") + full,
      path + std::string("--albedo ") + full,
      path + std::string("--save ") + full,
  };
  for (const std::string& args : commands) {
    expect_error(trace(args, dir), "cannot write " + full + ": No space left on device", args);
    ASSERT_TRUE(fs::is_character_file(fs::status(full))) << args << " removed " << full;
  }
}

// Two outputs that are one file, however spelled: refused before rendering, naming both.
TEST(CliOutputs, OneFileByAnySpellingIsRefused) {
  TempDir dir;
  fs::create_directory(dir.path("sub"));
  dir.file("old.pfm", "an earlier file");
  fs::create_symlink("old.pfm", dir.path("link.pfm"));
  fs::create_hard_link(dir.path("old.pfm"), dir.path("hard.pfm"));
  fs::create_symlink("missing.pfm", dir.path("dangling.pfm"));
  fs::create_symlink("sub", dir.path("subdir-link"));
  const std::string base = "render builtin:thesis-a --size 8x6 --quiet --out /dev/null ";
  const std::pair<std::string, std::string> cases[] = {
      {"--pfm a.pfm --depth " + dir.path("a.pfm"), "--pfm a.pfm and --depth "},
      {"--pfm a.pfm --depth sub/../a.pfm", "--pfm and --depth both name sub/../a.pfm"},
      {"--pfm old.pfm --normal link.pfm", "--pfm old.pfm and --normal link.pfm are one file"},
      {"--pfm old.pfm --prim hard.pfm", "--pfm old.pfm and --prim hard.pfm are one file"},
      {"--depth dangling.pfm --prim missing.pfm", "are one file"},
      {"--depth sub/n.pfm --normal subdir-link/n.pfm", "are one file"},
      {"--stats-json s.txt --source ./s.txt", "--stats-json and --source both name ./s.txt"},
  };
  for (const auto& [args, needle] : cases) {
    expect_error(trace(base + args, dir), needle + "", args);
    EXPECT_EQ(testing::read_text(dir.path("old.pfm")), "an earlier file") << args;
    EXPECT_FALSE(fs::exists(dir.path("a.pfm"))) << args;
    EXPECT_FALSE(fs::exists(dir.path("missing.pfm"))) << args;
  }
  // Devices can take any number of outputs: nothing is overwritten.
  EXPECT_EQ(trace(base + "--pfm /dev/null --depth /dev/null", dir).status, 0);
}

// A scene with a mesh, an MTL file and a texture, each of which an output could name.
void write_textured_scene(const TempDir& dir) {
  dir.file("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  dir.file("m.mtl", "newmtl red\nKd 1 0 0\n");
  write_png(dir.path("t.png"), 1, 1, {glm::vec3(1.0f)});
  dir.file("scene.json", R"({"textures": {"t": {"file": "t.png"}},
    "materials": {"tex": {"shader": "phong", "diffuse": {"texture": "t"}}},
    "meshes": [{"file": "m.obj"}, {"shape": "box", "material": "tex"}],
    "camera": {"eye": [0.3, 0.3, 3], "look_at": [0.3, 0.3, 0]}})");
}

// An output that is an input (the scene file, a mesh, an MTL, a texture, the render to
// resume), by any spelling: refused before rendering; the input is as it was.
TEST(CliOutputs, AnOutputNeverOverwritesAnInput) {
  TempDir dir;
  write_textured_scene(dir);
  fs::create_symlink("m.mtl", dir.path("mtl-link"));
  fs::create_hard_link(dir.path("m.obj"), dir.path("obj-hard"));
  const std::string scene = testing::read_text(dir.path("scene.json"));
  const std::string base = "render scene.json --size 8x6 --quiet ";
  ASSERT_EQ(trace(base + "--out ok.png", dir).status, 0);
  const std::pair<std::string, std::string> cases[] = {
      {"--out scene.json", "--out scene.json: .json names JSON, but --out writes PNG"},
      {"--stats-json ./scene.json", "--stats-json ./scene.json is the scene file (scene.json)"},
      {"--out t.png", "--out t.png is a file the scene loaded"},
      {"--out " + dir.path("t.png"), "is a file the scene loaded"},
      {"--source mtl-link", "--source mtl-link is a file the scene loaded"},
      {"--source obj-hard", "--source obj-hard is a file the scene loaded"},
  };
  for (const auto& [args, needle] : cases) {
    expect_error(trace(base + args, dir), needle, args);
    EXPECT_EQ(testing::read_text(dir.path("scene.json")), scene) << args;
  }
  // The render to resume, unless it is also the one saved (below).
  const std::string path = "render builtin:cornell-path --size 8x6 --quiet --out /dev/null ";
  ASSERT_EQ(trace(path + "--spp 2 --save r.acc", dir).status, 0);
  const std::string saved = testing::read_text(dir.path("r.acc"));
  expect_error(trace(path + "--spp 3 --resume r.acc --stats-json r.acc", dir),
               "--stats-json r.acc is the --resume file", "--stats-json r.acc");
  EXPECT_EQ(testing::read_text(dir.path("r.acc")), saved);
}

// --save F --resume F goes on from F and saves over it: F is read whole before rendering and
// replaced whole after. The image is the render at once's, bit for bit.
TEST(CliOutputs, SavingOverTheResumedFileGoesOn) {
  TempDir dir;
  const std::string path = "render builtin:cornell-path --size 8x6 --quiet --out /dev/null ";
  ASSERT_EQ(trace(path + "--spp 5 --pfm once.pfm", dir).status, 0);
  ASSERT_EQ(trace(path + "--spp 2 --save f.acc", dir).status, 0);
  const testing::Run r =
      trace(path + "--spp 5 --save f.acc --resume ./f.acc --pfm resumed.pfm", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing::read_text(dir.path("resumed.pfm")), testing::read_text(dir.path("once.pfm")));
  // f.acc now holds 5 samples: resuming to 5 renders nothing more.
  ASSERT_EQ(trace(path + "--spp 5 --resume f.acc --pfm again.pfm", dir).status, 0);
  EXPECT_EQ(testing::read_text(dir.path("again.pfm")), testing::read_text(dir.path("once.pfm")));
}

// An output's extension names its format: another format's is refused, with the formats
// each option writes; one no format is known by (or none) is the user's choice.
TEST(CliOutputs, AnExtensionOfAnotherFormatIsRefused) {
  TempDir dir;
  const std::string base = "render builtin:thesis-a --size 8x6 --quiet ";
  const std::pair<std::string, std::string> refused[] = {
      {"--out x.jpg",
       "--out x.jpg: .jpg names JPEG, but --out writes PNG (the formats written: --out PNG; --pfm, "
       "--depth, --prim, --normal and --albedo PFM; --exr OpenEXR; --stats-json JSON)"},
      {"--out x.PFM", "--out x.PFM: .PFM names PFM, but --out writes PNG"},
      {"--pfm x.png", "--pfm x.png: .png names PNG, but --pfm writes PFM"},
      {"--depth x.exr", "--depth x.exr: .exr names OpenEXR, but --depth writes PFM"},
      {"--exr x.tiff", "--exr x.tiff: .tiff names TIFF, but --exr writes OpenEXR"},
      {"--stats-json x.png", "--stats-json x.png: .png names PNG, but --stats-json writes JSON"},
      {"--source x.png",
       "--source x.png: .png names PNG, but --source writes the kernel source as text"},
  };
  for (const auto& [args, needle] : refused) expect_error(trace(base + args, dir), needle, args);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.dir()), {}), 2) << "stdout and stderr only";
  ASSERT_EQ(trace(base + "--out X.PNG --pfm plain --stats-json s.txt --source k.cl", dir).status,
            0);
  for (const char* f : {"X.PNG", "plain", "s.txt", "k.cl"}) EXPECT_TRUE(fs::exists(dir.path(f)));
}

// A FIFO with no reader: an error at once naming it (a blocking open would wait for a reader
// without end); with a reader, the image goes through it.
TEST(CliOutputs, AFifoWithoutAReaderIsAnErrorAtOnce) {
  TempDir dir;
  ASSERT_EQ(mkfifo(dir.path("p").c_str(), 0600), 0);
  const std::string args = "render builtin:thesis-a --size 8x6 --quiet --out /dev/null --pfm p";
  expect_error(trace(args, dir, 30), "no process is reading FIFO p", args);
  EXPECT_TRUE(fs::is_fifo(fs::status(dir.path("p"))));
  // This test reads: its end is open before rill-trace writes (the 8x6 PFM fits the pipe).
  const int reader = ::open(dir.path("p").c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(reader, 0);
  ASSERT_EQ(trace(args, dir, 30).status, 0);
  std::string got(4096, '\0');
  const ssize_t n = ::read(reader, got.data(), got.size());
  ::close(reader);
  ASSERT_GT(n, 0);
  got.resize(static_cast<size_t>(n));
  ASSERT_EQ(
      trace("render builtin:thesis-a --size 8x6 --quiet --out /dev/null --pfm f.pfm", dir).status,
      0);
  EXPECT_EQ(got, testing::read_text(dir.path("f.pfm")));
  // /dev/stdout on a pipe: written in place through it (its link names no path: 'pipe:[N]').
  const testing::Run piped = trace(
      "render builtin:thesis-a --size 8x6 --quiet --out /dev/null --pfm /dev/stdout | cat", dir);
  ASSERT_EQ(piped.status, 0) << piped.err;
  EXPECT_EQ(piped.out.rfind(got, 0), 0u) << "the PFM, then the stats line";
}

// Every option that takes a value, of every subcommand (as --help lists them), refuses an
// empty one: CLI11 read `--frames ''` as --frames not given, and rendered frame 0.
TEST(CliOutputs, AnEmptyValueIsNeverTheOptionsAbsence) {
  TempDir dir;
  const std::regex option(R"(^  (?:-\w,)?(--[\w-]+) [A-Z])");
  size_t checked = 0;
  for (const char* command : {"render", "accuracy", "noise", "demo"}) {
    const testing::Run help = trace(std::string(command) + " --help", dir);
    ASSERT_EQ(help.status, 0) << help.err;
    std::istringstream lines(help.out);
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, option)) continue;
      const std::string args = std::string(command) +
                               (std::string(command) == "render" ? " builtin:thesis-a" : "") + " " +
                               m[1].str() + " ''";
      const testing::Run r = trace(args, dir);
      SCOPED_TRACE(args);
      EXPECT_EQ(r.status, 2) << r.err;
      EXPECT_EQ(r.err.rfind("rill-trace: " + m[1].str() + ": an empty ", 0), 0u) << r.err;
      ++checked;
    }
  }
  EXPECT_GT(checked, 40u) << "the help's format changed";
  expect_error(trace("render ''", dir), "scene: an empty value", "render ''");
}

#else
TEST(CliOutputs, EveryOutputReportsAWriteError) {
  GTEST_SKIP() << "rill-trace is not built";
}
#endif

}  // namespace
}  // namespace rt
