// rill-trace on bad command lines and bad files: it exits (no crash, no hang) with a
// non-zero status and one line on stderr. And what `rill-trace info` lists.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "RunCommand.h"
#include "TestUtil.h"

namespace rt {
namespace {

#ifdef RILL_TRACE_EXE

using testing::Run;
using testing::run_command;

Run run(const std::string& args, const testing::TempDir& dir) {
  return run_command("'" RILL_TRACE_EXE "' " + args, dir);
}

void expect_clean_failure(const std::string& args, const std::string& needle = "") {
  testing::TempDir dir;
  dir.file("bad.json", "{\"camera\": {\"eye\": [0, 1,");
  dir.file("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
  dir.file("nan.json", "{\"camera\": {\"fov_y\": 0}}");
  Run r = run(args, dir);
  SCOPED_TRACE(args);
  EXPECT_TRUE(r.status == 1 || r.status == 2) << "status " << r.status << ": " << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.rfind("rill-trace: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  if (!needle.empty()) {
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
  }
}

// A backend named only by the environment: the error says where the name came from.
TEST(Cli, AnUnknownBackendFromTheEnvironmentIsNamed) {
  testing::TempDir dir;
  const testing::Run r = run_command("env RILL_TRACE_BACKEND=bogus '" RILL_TRACE_EXE
                                     "' render builtin:cornell --size 8x8 --quiet",
                                     dir);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(
      r.err.rfind("rill-trace: RILL_TRACE_BACKEND='bogus': unknown backend (this build has: ", 0),
      0u)
      << r.err;
}

// docs/cli.md: every bad command line is exit status 2 with "(see --help)", whichever command
// and option: a range error as much as a word that is not a value. `accuracy`, `noise` and
// `demo --size` were read after parsing (status 1).
TEST(Cli, EveryCommandLineErrorExitsTwo) {
  for (const std::string args :
       {"render builtin:thesis-a --spp 0", "render builtin:thesis-a --size 0x8",
        "render builtin:thesis-a --size 20000x20000", "render builtin:thesis-a --grid 0",
        "render builtin:thesis-a --grid 99999", "render builtin:thesis-a --threads 0",
        "render builtin:thesis-a --strategy quantum", "render builtin:thesis-a --no-such-option",
        "accuracy --size 0x5", "accuracy --size abc", "noise --size 0x0", "demo --size 5",
        "demo --size 99999x2"}) {
    testing::TempDir dir;
    const testing::Run r = run(args, dir);
    SCOPED_TRACE(args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err.rfind("rill-trace: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("(see --help)\n"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not one line: " << r.err;
  }
}

TEST(Cli, BadCommandLinesAndInputs) {
  expect_clean_failure("");
  expect_clean_failure("render");
  expect_clean_failure("frobnicate",
                       "unknown command 'frobnicate' (render, accuracy, noise, demo, info)");
  expect_clean_failure("render builtin:thesis-a --pfm o.pfm --depth ./o.pfm",
                       "--pfm and --depth both name ./o.pfm: one would overwrite the other");
  expect_clean_failure("render builtin:thesis-a --frobnicate");
  expect_clean_failure("render no-such-scene.json", "no such file");
  expect_clean_failure("render builtin:nope", "unknown built-in");
  expect_clean_failure("render bad.json", "invalid JSON");
  expect_clean_failure("render bad.obj", "vertex 9");
  expect_clean_failure("render nan.json", "fov_y");
  expect_clean_failure("render builtin:thesis-a --size 0x10", "--size");
  expect_clean_failure("render builtin:thesis-a --size 100000x100000", "--size");
  expect_clean_failure("render builtin:thesis-a --size banana", "--size");
  expect_clean_failure("render builtin:thesis-a --grid 0", "--grid");
  expect_clean_failure("render builtin:thesis-a --grid 99999", "--grid");
  expect_clean_failure("render builtin:thesis-a --subgrids 0", "--subgrids expects auto, off");
  expect_clean_failure("render builtin:thesis-a --subgrids some", "(got 'some')");
  expect_clean_failure("render builtin:thesis-a --grid-density 0",
                       "--grid-density expects auto or a number of voxels per triangle in "
                       "0.125..256 (got '0')");
  expect_clean_failure("render builtin:thesis-a --grid-density lots", "--grid-density");
  expect_clean_failure("render builtin:thesis-a --grid-density Auto", "(got 'Auto')");
  // An empty file name would read as the option not given; an option given twice names it.
  expect_clean_failure("render builtin:thesis-a --size 4x4 --out ''", "--out: an empty file name");
  expect_clean_failure("render builtin:thesis-a --size 4x4 --stats-json ''",
                       "--stats-json: an empty");
  // So would an empty setting.
  for (const char* opt : {"--size", "--grid", "--grid-density", "--subgrids", "--light-buffer"})
    expect_clean_failure(std::string("render builtin:thesis-a ") + opt + " ''",
                         std::string(opt) + ": an empty value");
  expect_clean_failure("render builtin:thesis-a --size 4x4 --size 8x8",
                       "--size is given 2 times: give it once");
  expect_clean_failure("render builtin:thesis-a --spp 0", "0 is out of range (1 to 1048576)");
  expect_clean_failure("render builtin:thesis-a --max-depth -3", "out of range (0 to 64)");
  expect_clean_failure("render builtin:thesis-a --max-depth x", "'x' is not an integer");
  expect_clean_failure("render builtin:thesis-a --spp 2.5", "'2.5' is not an integer");
  expect_clean_failure("render builtin:thesis-a --bench-frames lots", "'lots' is not an integer");
  expect_clean_failure("render builtin:thesis-a --accuracy sloppy --size 4x4");
  expect_clean_failure("render builtin:thesis-a --backend nope --size 4x4", "nope");
  expect_clean_failure("render builtin:thesis-a --strategy quantum --size 4x4", "strategy");
  expect_clean_failure("render builtin:glass --strategy multipass --size 4x4", "megakernel");
  expect_clean_failure("render builtin:thesis-a --loop wavefront --size 4x4",
                       "--loop expects auto, ray or segment (got 'wavefront')");
  expect_clean_failure("render builtin:thesis-a --strategy multipass --masking maybe --size 4x4",
                       "--masking");
  expect_clean_failure("render builtin:thesis-a --strategy multipass --wait-threshold 0 --size 4x4",
                       "--wait-threshold");
  expect_clean_failure("render builtin:thesis-a --size 4x4 --out /no/such/dir/x.png", "x.png");
  // Distributed rendering's options (docs/distributed.md), checked without mpirun too.
  expect_clean_failure("render builtin:thesis-a --tile 0", "0 is out of range (1 to 16384)");
  expect_clean_failure("render builtin:thesis-a --tile big", "'big' is not an integer");
  expect_clean_failure("render builtin:thesis-a --rank-timeout 0", "out of range");
  expect_clean_failure("render builtin:thesis-a --tile-timeout -1", "out of range");
  expect_clean_failure("render builtin:thesis-a --size 4x4 --distribute", "--distribute");
  expect_clean_failure("render builtin:thesis-a --size 4x4 --device 1", "--device");
}

// What rill-trace prints (stdout and stderr) with these arguments, and its exit status.
std::string output_of(const std::string& args, int& status) {
  std::string out;
  FILE* p = popen(("timeout 60 '" RILL_TRACE_EXE "' " + args + " 2>&1").c_str(), "r");
  if (p == nullptr) return out;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  const int rc = pclose(p);
  status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  return out;
}

// `info` lists the registered surface shaders, each with its parameters: name, type, default.
TEST(Cli, InfoListsShadersAndTheirParameters) {
  int status = -1;
  const std::string out = output_of("info", status);
  EXPECT_EQ(status, 0) << out;
  const size_t shaders = out.find("surface shaders");
  ASSERT_NE(shaders, std::string::npos) << out;
  for (const char* name : {"\n  glass ", "\n  mirror ", "\n  phong "})
    EXPECT_NE(out.find(name, shaders), std::string::npos) << name << " missing in:\n" << out;
  // A number and a colour parameter, with their types and defaults, and the docs.
  EXPECT_NE(out.find("ior        number  1.5 "), std::string::npos) << out;
  EXPECT_NE(out.find("diffuse    colour  [0.8, 0.8, 0.8]  diffuse colour (Kd)"), std::string::npos)
      << out;
  EXPECT_NE(out.find("reflect    number  0.9              reflectance, 0 to 1"), std::string::npos)
      << out;
}

// The grid settings left open ("subgrids": auto, the default) are chosen for the backend:
// subgrids on the CPU backends, none where asked; so is the megakernel's loop (segment on cpu
// and simd, ray where asked); and the stats JSON splits the frame time.
TEST(Cli, GridSettingsFollowTheBackendAndStatsSplitTheFrame) {
  testing::TempDir dir;
  auto stats_of = [&](const std::string& extra) {
    const auto r =
        run("render builtin:thesis-c --size 8x8 --out a.png --stats-json s.json " + extra, dir);
    EXPECT_EQ(r.status, 0) << r.err;
    std::ifstream f(dir.path("s.json"));
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  };
  auto subgrids_in = [](const std::string& json) {
    const size_t at = json.find("\"subgrids\": ");
    EXPECT_NE(at, std::string::npos) << json;
    return at == std::string::npos ? -1 : std::atoi(json.c_str() + at + 12);
  };
  for (const char* backend : {"cpu", "simd"}) {
    const std::string json = stats_of(std::string("--backend ") + backend);
    EXPECT_GT(subgrids_in(json), 0) << backend << ": " << json;
    EXPECT_NE(json.find("\"megakernel_loop\": \"segment\""), std::string::npos) << json;
    for (const char* step :
         {"\"setup\"", "\"launch\"", "\"kernel\"", "\"accumulate\"", "\"reduce\"", "\"read_back\""})
      EXPECT_NE(json.find(step, json.find("\"trace_split_ms\"")), std::string::npos) << step;
  }
  EXPECT_EQ(subgrids_in(stats_of("--subgrids off")), 0);
  EXPECT_NE(stats_of("--loop ray").find("\"megakernel_loop\": \"ray\""), std::string::npos);
  EXPECT_GT(subgrids_in(stats_of("--subgrids auto")), 0);
}

// What loading noticed (an MTL file that is not there) is a warning on stderr that names the
// file, and a line of the stats JSON's "warnings"; the render goes on.
TEST(Cli, LoadWarningsArePrintedAndInTheStats) {
  testing::TempDir dir;
  dir.file("m.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const auto r = run("render m.obj --size 8x8 --out m.png --stats-json s.json", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("rill-trace: warning: m.obj: mtllib gone.mtl: no such file"),
            std::string::npos)
      << r.err;
  std::ifstream f(dir.path("s.json"));
  std::stringstream s;
  s << f.rdbuf();
  EXPECT_NE(s.str().find("gone.mtl: no such file"), std::string::npos) << s.str();
}

// The cases a new user met (issue: reliability): random bytes as an OBJ, "v abc def" lines,
// and a grid far too fine for its triangles, each with its message; --strict-input and
// --allow-empty change what is an error.
TEST(Cli, MalformedAndEmptyInputsAreNamed) {
  testing::TempDir dir;
  std::string noise;
  uint32_t x = 7;
  for (int i = 0; i < 100000; ++i) {
    x = x * 1664525u + 1013904223u;
    noise.push_back(static_cast<char>(x >> 24));
  }
  dir.file("random.obj", noise);
  auto r = run("render random.obj --size 8x8 --out r.png", dir);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("rill-trace: random.obj: no faces in "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("is it an OBJ file? (--allow-empty loads it as no triangles)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("r.png")));
  // --allow-empty: it renders (the background), with the malformed lines as warnings.
  dir.file("empty.obj", "");
  r = run("render empty.obj --size 8x8 --out e.png --allow-empty", dir);
  EXPECT_EQ(r.status, 0) << r.err;

  dir.file("v.obj", "v 0 0 0\nv abc def\nv 1 0 0\nv 0 1 0\nf 1 3 4\n");
  r = run("render v.obj --size 8x8 --out v.png --stats-json s.json", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("rill-trace: warning: v.obj:2: 'v' expects numbers ('v abc def'); the "
                       "line is skipped"),
            std::string::npos)
      << r.err;
  std::ifstream f(dir.path("s.json"));
  std::stringstream json;
  json << f.rdbuf();
  EXPECT_NE(json.str().find("v.obj:2: 'v' expects numbers"), std::string::npos) << json.str();
  // Set-up (uploads, the warm-up launch) is its own figure, not part of "compile".
  const std::string j = json.str();
  const size_t times = j.find("\"time_ms\"");
  ASSERT_NE(times, std::string::npos);
  const std::string time_ms = j.substr(times, j.find('}', times) - times);
  EXPECT_NE(time_ms.find("\"compile\""), std::string::npos) << time_ms;
  EXPECT_NE(time_ms.find("\"setup\""), std::string::npos) << time_ms;
  r = run("render v.obj --size 8x8 --out v.png --strict-input", dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err,
            "rill-trace: v.obj:2: 'v' expects numbers ('v abc def') (an error under "
            "--strict-input)\n");

  // A grid of 134 million voxels for one triangle: refused over the memory limit, with the
  // estimate, before allocating; a finer grid than auto's within it: a warning that it is
  // mostly empty space.
  dir.file("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  setenv("RILL_MAX_GRID_MB", "100", 1);  // the child inherits it
  r = run("render t.obj --size 8x8 --out t.png --grid 512", dir);
  unsetenv("RILL_MAX_GRID_MB");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("needs about 3072.0 MiB, over the limit of 100.0 MiB (RILL_MAX_GRID_MB)"),
            std::string::npos)
      << r.err;
  r = run("render t.obj --size 8x8 --out t.png --grid 128", dir);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: the grid 128x128x128 has 2097152 voxels for 1 triangles"),
            std::string::npos)
      << r.err;
}

// A buffer over the OpenCL device's largest allocation (lowered here with
// RILL_OPENCL_MAX_ALLOC_MB) is an error naming both sizes and the device, and a bad
// RILL_THREADS an error naming it; neither leaves an image behind.
TEST(Cli, BackendLimitsAreNamed) {
  testing::TempDir dir;
  std::string why;
  if (testing::backend_available("opencl", why)) {
    auto r = run_command("env RILL_OPENCL_MAX_ALLOC_MB=1 '" RILL_TRACE_EXE
                         "' render builtin:thesis-a --backend opencl --size 1024x1024 --out o.png",
                         dir);
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_NE(r.err.find("OpenCL backend: a buffer of "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("(RILL_OPENCL_MAX_ALLOC_MB, 1 MiB)"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path("o.png")));
  } else {
    std::printf("[  SKIPPED ] the OpenCL part: %s\n", why.c_str());
  }
  auto r = run_command("env RILL_THREADS=zero '" RILL_TRACE_EXE
                       "' render builtin:thesis-a --size 8x8 --out t.png",
                       dir);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("RILL_THREADS='zero' is not a thread count (1..4096)"), std::string::npos)
      << r.err;
}

// Memory that runs out anyway (here under a 1 GiB address-space limit, while the grid's own
// estimate is within half the machine's memory) ends with a message naming the step.
TEST(Cli, RunningOutOfMemoryNamesTheStep) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: ulimit -v cannot apply";
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: ulimit -v cannot apply";
#endif
#endif
  testing::TempDir dir;
  // 400^3 voxels: about 1.5 GB by the estimate, over the 1 GiB limit when allocated.
  auto r = run_command("sh -c \"ulimit -v 1048576; exec '" RILL_TRACE_EXE
                       "' render builtin:thesis-a --size 8x8 --grid 400 --out m.png\"",
                       dir);
  EXPECT_EQ(r.status, 1) << r.err;
  // Building or uploading the grid, as the allocator decides; the error is the last line.
  const std::string last = r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
  EXPECT_TRUE(last == "rill-trace: out of memory while building the grid of 36 triangles\n" ||
              last ==
                  "rill-trace: out of memory while uploading the scene and grid (64000000 "
                  "voxels) and building the light buffer\n")
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("m.png")));
}

std::string file_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Determinism: the image and every AOV are the same bytes for 1, 2 and all threads (Rill's and
// the CPU drivers'), for repeated runs, for OpenCL work-group sizes and for the GPU backends'
// launch orders (tiles on and off), as the cpu backend's on one thread. Each variant is a process
// of its own: the group size and tile settings are read once per process.
TEST(Cli, OutputsDoNotDependOnThreadsGroupSizesOrRuns) {
  testing::TempDir dir;
  const std::string outs =
      " --size 32x24 --spp 2 --out o.png --pfm o.pfm --depth d.pfm --prim "
      "p.pfm --normal n.pfm";
  auto render = [&](const std::string& env, const std::string& args) {
    const std::string cmd = env + " '" RILL_TRACE_EXE "' render builtin:glass" + outs + " " + args;
    auto r = run_command(cmd, dir);
    EXPECT_EQ(r.status, 0) << cmd << ": " << r.err;
    std::string all;
    for (const char* f : {"o.png", "o.pfm", "d.pfm", "p.pfm", "n.pfm"}) {
      all += file_bytes(dir.path(f));
      std::filesystem::remove(dir.path(f));
    }
    return all;
  };
  const std::string want = render("env", "--backend cpu --threads 1");
  ASSERT_GT(want.size(), 32u * 24 * 4);
  struct Variant {
    std::string backend, env, args;
  };
  const std::vector<Variant> variants = {
      {"cpu", "", "--backend cpu --threads 2"},
      {"cpu", "", "--backend cpu"},
      {"cpu", "", "--backend cpu"},  // a repeated run
      {"simd", "", "--backend simd --threads 1"},
      {"simd", "", "--backend simd"},
      {"opencl", "RILL_OPENCL_GROUP=1", "--backend opencl"},
      {"opencl", "RILL_OPENCL_GROUP=256 RILL_OPENCL_TILES=off", "--backend opencl"},
      {"opencl", "", "--backend opencl"},
      {"glsl-compute", "RILL_GLSL_TILES=off", "--backend glsl-compute"},
      {"glsl-compute", "", "--backend glsl-compute"},
      // The drivers' own threads where they run on the CPU (PoCL's worker threads, llvmpipe's
      // rasterizer threads); other drivers ignore these variables.
      {"opencl", "POCL_MAX_PTHREAD_COUNT=1", "--backend opencl"},
      {"glsl-compute", "LP_NUM_THREADS=1", "--backend glsl-compute"},
      {"glsl", "LP_NUM_THREADS=1", "--backend glsl"},
      {"glsl", "", "--backend glsl"},
  };
  for (const Variant& v : variants) {
    std::string why;
    if (!testing::backend_available(v.backend, why)) {
      std::printf("[  SKIPPED ] %s: %s\n", v.args.c_str(), why.c_str());
      continue;
    }
    EXPECT_TRUE(render("env " + v.env, v.args) == want)
        << v.env << " " << v.args << ": the outputs differ from cpu --threads 1";
  }
}

// --frames: one image per frame, named by its number, each the same bits as that frame
// rendered alone; refits give the rebuilds' images; the stats show no recompile after the
// first frame; bad sequences are one-line errors.
TEST(Cli, FramesWriteNumberedImagesOfADynamicScene) {
  testing::TempDir dir;
  dir.file("anim.json", R"({"builtin": "thesis-a", "animation": {"end": 1, "fps": 4},
    "meshes": [{"shape": "box", "min": [-0.3, 0, -0.3], "max": [0.3, 0.6, 0.3],
      "animate": {"keys": [{"time": 0, "translate": [0, 2.8, 1.2]},
                           {"time": 1, "translate": [1, 0.2, 1.2], "rotate": {"axis": [0, 1, 0], "degrees": 60}}]}}],
    "camera": {"keys": [{"time": 0}, {"time": 1, "eye": [2, 3.5, 7]}]}})");
  auto bytes = [&](const std::string& name) {
    std::ifstream f(dir.path(name), std::ios::binary);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  };
  auto r =
      run("render anim.json --size 16x12 --frames 1:3 --out f-%03d.png --stats-json s.json", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("f-000.png")));
  for (const char* f : {"f-001.png", "f-002.png", "f-003.png"})
    EXPECT_TRUE(std::filesystem::exists(dir.path(f))) << f;
  EXPECT_NE(bytes("f-001.png"), bytes("f-003.png"));  // it moves
  const std::string stats = bytes("s.json");
  EXPECT_NE(stats.find("\"frames\""), std::string::npos);
  EXPECT_NE(stats.find("\"moving_triangles\": 12"), std::string::npos) << stats;
  // Frames after the first compile nothing.
  size_t compiled = 0;
  for (size_t at = stats.find("\"kernels_compiled\": 0"); at != std::string::npos;
       at = stats.find("\"kernels_compiled\": 0", at + 1))
    ++compiled;
  EXPECT_EQ(compiled, 2u) << stats;
  // Frame 2 alone, and the sequence with refits: the same bytes.
  ASSERT_EQ(run("render anim.json --size 16x12 --frames 2 --out one.png", dir).status, 0);
  EXPECT_EQ(bytes("one.png"), bytes("f-002.png"));
  ASSERT_EQ(
      run("render anim.json --size 16x12 --frames 1:3 --bvh refit --out r-%d.png", dir).status, 0);
  EXPECT_EQ(bytes("r-3.png"), bytes("f-003.png"));

  const std::pair<const char*, const char*> bad[] = {
      {"--frames 0:3 --out x.png", "--out needs a frame number, such as frame-%04d.png"},
      {"--frames 0:3 --out f-%04d.png --depth d.pfm", "--depth needs a frame number"},
      {"--frames 0:9", "the scene has 5 frames (0..4)"},
      {"--frames 3:1", "the last frame is before the first"},
      {"--frames soon", "--frames expects N or A:B"},
      {"--frames 0:1 --out f-%s.png", "the only conversion allowed is the frame number"},
      {"--frames 0:1 --out f-%d-%d.png", "has two frame numbers"},
      {"--frames 0:1 --out f-%40d.png", "a width of at most 20"},
      {"--bvh maybe", "--bvh: unknown BVH update 'maybe' (rebuild, refit)"},
      {"--video v.mp4", "--video makes a video of the frames' PNGs: give --frames and --out"},
  };
  for (const auto& [args, needle] : bad) {
    auto b = run("render anim.json --size 16x12 " + std::string(args), dir);
    // --bvh's value is typed as the command line is read (status 2, a bad command line); the
    // others depend on the scene (status 1).
    const int status = std::string(args).rfind("--bvh", 0) == 0 ? 2 : 1;
    EXPECT_EQ(b.status, status) << args << ": " << b.err;
    EXPECT_NE(b.err.find(needle), std::string::npos) << args << ": " << b.err;
  }
  // Without ffmpeg on the PATH, --video says so before rendering anything.
  auto v = run_command("env PATH=/nonexistent '" RILL_TRACE_EXE
                       "' render anim.json --size 16x12 --frames 0:1 --out v-%d.png --video v.mp4",
                       dir);
  EXPECT_EQ(v.status, 1) << v.err;
  EXPECT_NE(v.err.find("--video needs ffmpeg, which is not on the PATH (apt-get install ffmpeg)"),
            std::string::npos)
      << v.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("v-0.png")));
  // Keys that are each fine but interpolate to eye on look_at: the error names the scene, the
  // frame and the keys.
  dir.file("cam.json", R"({"builtin": "thesis-a", "animation": {"end": 2, "fps": 2},
    "camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0], "keys": [{"time": 0},
               {"time": 2, "eye": [0, 0, -5]}]}})");
  auto c = run("render cam.json --size 8x8 --frames 0:4 --out c-%d.png", dir);
  EXPECT_EQ(c.status, 1) << c.err;
  EXPECT_NE(c.err.find("cam.json: the camera at frame 2 (time 1, between camera.keys[0] and [1]): "
                       "eye and look_at are the same point"),
            std::string::npos)
      << c.err;
  // A static scene has one frame.
  auto s = run("render builtin:thesis-a --size 8x8 --frames 0:2 --out s-%d.png", dir);
  EXPECT_NE(s.err.find("the scene has 1 frame (0..0); it has no animation"), std::string::npos)
      << s.err;
  EXPECT_EQ(run("render builtin:thesis-a --size 8x8 --frames 0 --out s.png", dir).status, 0);
}

// --frames' statistics cover every frame, as a distributed render's do: the stats line says
// "N frames of WxH" with all their rays and trace time, --stats-json's rays, launches and
// trace time are the frames' sums and each frame has its rays (they were frame 0's alone).
// The "wrote" lines name the first 8 files and count the rest (they stopped at 8 silently).
TEST(Cli, FramesStatisticsCoverEveryFrameAndEveryFileIsCounted) {
  testing::TempDir dir;
  dir.file("ten.json", R"({"builtin": "thesis-a", "animation": {"end": 1, "fps": 9},
    "meshes": [{"shape": "box", "min": [-0.3, 0, -0.3], "max": [0.3, 0.6, 0.3],
      "animate": {"keys": [{"time": 0, "translate": [0, 2.8, 1.2]},
                           {"time": 1, "translate": [1, 0.2, 1.2]}]}}]})");
  auto r = run("render ten.json --size 8x6 --frames 0:9 --out f-%d.png --stats-json s.json", dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(testing::read_text(dir.path("s.json")));
  ASSERT_EQ(j["frames"].size(), 10u);
  int64_t rays = 0;
  double trace_ms = 0;
  for (const nlohmann::json& f : j["frames"]) {
    EXPECT_GT(f.value("rays", int64_t{0}), 0) << f;
    rays += f.value("rays", int64_t{0});
    trace_ms += f["trace_ms"].get<double>();
  }
  EXPECT_EQ(j["rays"].get<int64_t>(), rays);
  EXPECT_GT(rays, j["frames"][0].value("rays", int64_t{0}));
  EXPECT_DOUBLE_EQ(j["time_ms"]["trace"].get<double>(), trace_ms);
  EXPECT_NE(r.out.find(" triangles, 10 frames of 8x6, cpu strict"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(" + std::to_string(rays) + " rays)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote f-7.png\n... and 2 more (the last: f-9.png)\n"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("wrote f-8.png"), std::string::npos) << r.out;
}

#else
TEST(Cli, FramesWriteNumberedImagesOfADynamicScene) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, FramesStatisticsCoverEveryFrameAndEveryFileIsCounted) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, RunningOutOfMemoryNamesTheStep) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, BackendLimitsAreNamed) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, OutputsDoNotDependOnThreadsGroupSizesOrRuns) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, MalformedAndEmptyInputsAreNamed) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, LoadWarningsArePrintedAndInTheStats) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, GridSettingsFollowTheBackendAndStatsSplitTheFrame) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, BadCommandLinesAndInputs) {
  GTEST_SKIP() << "rill-trace is not built";
}
TEST(Cli, InfoListsShadersAndTheirParameters) {
  GTEST_SKIP() << "rill-trace is not built";
}
#endif

}  // namespace
}  // namespace rt
