// rill-bench-shaders: what user surface shaders cost (issue 18 item 2, specialization).
//
// Registers 16 small user shaders, each distinct code (a toon shader with k = 2..17 bands, a
// rim term raised to a power of 1..4 and one of four tints), and builds builtin:thesis-b
// with its triangles spread over the first N of them (triangle i gets material i % N, each
// material a different shader). For every usable backend and N = 1, 4, 16 it reports the
// tracer's captured IR statement count, the generated source size, the cold compile time
// and the trace time. A further row registers only the one shader it uses: its IR, source
// and program hash must equal those of "16 registered, 1 used" (unused registered shaders
// leave no code), and the program fails otherwise.
//
// Each measurement is a new process (this program with --child) whose Rill, PoCL and Mesa
// caches point into a fresh directory, so its first render compiles cold; it then renders
// --reps more times and reports the median trace time. Rows are interleaved per run.
//
//   build/bench/rill-bench-shaders                          # 256x192, 5 renders, 3 runs
//   build/bench/rill-bench-shaders --backends cpu --size 32x24 --reps 1 --runs 1   # smoke
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "CommaList.h"
#include "Timing.h"
#include "UsableBackends.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace {

using rill::Float;
using rill::Float3;
constexpr int kShaders = 16;

std::string shader_name(int i) {
  return "bench_toon_" + std::to_string(i);
}

// Shader i: k = i + 2 light bands, a rim of power i / 4 + 1, tint i % 4. Every host
// constant and branch below changes the generated code, so no two shaders are alike.
rt::SurfaceShader make_shader(int i) {
  rt::SurfaceShader s;
  s.name = shader_name(i);
  s.doc = "benchmark toon shader " + std::to_string(i);
  s.params = {{"color", rt::ParamType::Color, rt::ParamValue::of(glm::vec3(0.8f)), ""}};
  s.emitted = [](const rt::ShadingPoint& sp) { return sp.ambient() * sp.color("color"); };
  s.reflected = [i](const rt::ShadingPoint& sp, const rt::LightSample& l) {
    const float k = static_cast<float>(i + 2);
    Float level = floor(max(dot(sp.s.nf, l.L), 0.0f) * k) / k;
    Float edge = 1.0f - max(dot(sp.s.nf, sp.s.V), 0.0f);
    Float rim = edge;
    for (int p = 0; p < i / 4; ++p) rim = rim * edge;
    Float3 c = sp.color("color");
    switch (i % 4) {
      case 0:
        break;
      case 1:
        c = c * (0.75f + 0.25f * cos(sp.s.P.y() * k));
        break;
      case 2:
        c = c * sqrt(level + 0.01f * k);
        break;
      default:
        c = c * exp(-0.1f * k * rim);
        break;
    }
    return (c * level + 0.2f * rim) * l.color;
  };
  return s;
}

// thesis-b with its triangles over shaders 0..used-1.
rt::Scene make_scene(int used) {
  rt::Scene s = rt::builtin_scene("thesis-b");
  s.materials.clear();
  for (int j = 0; j < used; ++j) {
    rt::Material m;
    m.name = "toon" + std::to_string(j);
    m.shader = shader_name(j);
    const float h = static_cast<float>(j) / kShaders;
    m.params["color"] = rt::ParamValue::of(glm::vec3(0.3f + 0.6f * h, 0.9f - 0.5f * h, 0.5f));
    s.materials.push_back(m);
  }
  for (size_t t = 0; t < s.material.size(); ++t) s.material[t] = static_cast<int32_t>(t % used);
  s.validate();
  return s;
}

struct Row {
  int registered = 0, used = 0;
};
const std::vector<Row> kRows = {{1, 1}, {16, 1}, {16, 4}, {16, 16}};

struct Figures {
  long statements = 0, source_bytes = 0;
  unsigned long long hash = 0;
  double compile_ms = 0, trace_ms = 0;
};

// ---- the child: one cold compile and `reps` renders, figures written to `out` -------------

int child(const std::string& backend, Row row, int w, int h, int reps, const std::string& out) {
  for (int i = 0; i < row.registered; ++i) rt::register_shader(make_shader(i));
  rt::Scene scene = make_scene(row.used);
  rt::Grid grid = rt::build_grid_for(scene);
  rt::Tracer tracer(scene, grid);
  if (static_cast<int>(tracer.shaders().size()) != row.used) {
    std::fprintf(stderr, "rill-bench-shaders: %d shaders in the kernel, %d used\n",
                 static_cast<int>(tracer.shaders().size()), row.used);
    return 1;
  }
  rt::RenderSettings rs;
  rs.backend = backend;
  rs.width = w;
  rs.height = h;
  rt::RenderResult first = tracer.render(rs, scene.camera);
  if (first.from_cache) {
    std::fprintf(stderr, "rill-bench-shaders: the cold compile came from a cache\n");
    return 1;
  }
  std::vector<double> traces;
  for (int r = 0; r < reps; ++r) traces.push_back(tracer.render(rs, scene.camera).trace_ms);
  std::ofstream f(out);
  const rill::Program& program =
      tracer.program(rt::megakernel_loop_for(rt::MegakernelLoop::Auto, backend));
  f << rill::ir::count_statements(program.ir().body) << ' ' << tracer.source(backend).size() << ' '
    << program.hash() << ' ' << first.compile_ms << ' ' << rill::bench::median(traces) << '\n';
  return f ? 0 : 1;
}

// ---- the parent ---------------------------------------------------------------------------

// Runs one child with every cache (Rill's, PoCL's, Mesa's) in a fresh directory; false on
// failure (its output went to our stderr).
bool measure(const std::string& backend, Row row, const std::string& size, int reps, Figures& fig) {
  char tmpl[] = "/tmp/rill-bench-shaders-XXXXXX";
  if (!mkdtemp(tmpl)) return false;
  const std::filesystem::path dir = tmpl;
  for (const auto& [var, sub] :
       std::map<std::string, std::string>{{"RILL_CACHE_DIR", "rill"},
                                          {"POCL_CACHE_DIR", "pocl"},
                                          {"MESA_SHADER_CACHE_DIR", "mesa"},
                                          {"XDG_CACHE_HOME", "xdg"}})
    setenv(var.c_str(), (dir / sub).c_str(), 1);
  const std::string out = (dir / "figures").string();
  const std::string cmd = std::filesystem::read_symlink("/proc/self/exe").string() + " --child " +
                          backend + " " + std::to_string(row.registered) + " " +
                          std::to_string(row.used) + " " + size + " " + std::to_string(reps) + " " +
                          out;
  const bool ok = std::system(cmd.c_str()) == 0;
  std::ifstream f(out);
  const bool read =
      ok && (f >> fig.statements >> fig.source_bytes >> fig.hash >> fig.compile_ms >> fig.trace_ms);
  std::filesystem::remove_all(dir);
  if (!read) std::fprintf(stderr, "rill-bench-shaders: child failed: %s\n", cmd.c_str());
  return read;
}

int parent(const std::vector<std::string>& wanted, const std::string& size, int reps, int runs) {
  std::printf(
      "rill-bench-shaders: builtin:thesis-b at %s, triangle i -> material i %% N, one "
      "shader per material\n",
      size.c_str());
  const std::vector<std::string> bes = rill::bench::usable_backends(wanted);
  // runs[backend][row]: interleaved, so slow spells of a shared machine hit every row.
  std::map<std::string, std::vector<std::vector<Figures>>> all;
  for (const auto& be : bes) all[be].resize(kRows.size());
  for (int r = 0; r < runs; ++r)
    for (const auto& be : bes)
      for (size_t i = 0; i < kRows.size(); ++i) {
        Figures fig;
        if (!measure(be, kRows[i], size, reps, fig)) return 1;
        all[be][i].push_back(fig);
      }

  std::printf(
      "\ncold compile: median of %d processes with empty caches; trace: median over "
      "them of the median of %d renders (ms)\n\n",
      runs, reps);
  std::printf(
      "| backend | shaders registered | shaders used | IR statements | source bytes "
      "| cold compile ms | trace ms |\n|---|---|---|---|---|---|---|\n");
  bool same = true;
  for (const auto& be : bes) {
    for (size_t i = 0; i < kRows.size(); ++i) {
      std::vector<double> c, t;
      for (const Figures& f : all[be][i]) {
        c.push_back(f.compile_ms);
        t.push_back(f.trace_ms);
      }
      const Figures& f = all[be][i].front();
      std::printf("| %s | %d | %d | %ld | %ld | %.0f | %.1f |\n", be.c_str(), kRows[i].registered,
                  kRows[i].used, f.statements, f.source_bytes, rill::bench::median(c),
                  rill::bench::median(t));
    }
    const Figures& one = all[be][0].front();
    const Figures& sixteen = all[be][1].front();
    if (one.statements != sixteen.statements || one.source_bytes != sixteen.source_bytes ||
        one.hash != sixteen.hash) {
      std::printf("%s: FAIL: 16 registered, 1 used differs from 1 registered, 1 used\n",
                  be.c_str());
      same = false;
    }
  }
  if (same)
    std::printf(
        "\n16 registered, 1 used: the same program (IR hash), IR and source as 1 "
        "registered, 1 used on every backend\n");
  return same ? 0 : 1;
}

int usage() {
  std::fprintf(stderr,
               "usage: rill-bench-shaders [--backends cpu,simd,opencl,glsl,glsl-compute] [--size WxH] "
               "[--reps 5] [--runs 3]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) try {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.size() == 7 && args[0] == "--child") {
    int w = 0, h = 0;
    if (std::sscanf(args[4].c_str(), "%dx%d", &w, &h) != 2) return usage();
    return child(args[1], Row{std::stoi(args[2]), std::stoi(args[3])}, w, h, std::stoi(args[5]),
                 args[6]);
  }
  std::vector<std::string> backends = {"cpu", "simd", "opencl", "glsl"};
  std::string size = "256x192";
  int reps = 5, runs = 3;
  for (size_t i = 0; i + 1 < args.size(); i += 2) {
    if (args[i] == "--backends")
      backends = rill::bench::split_list(args[i + 1]);
    else if (args[i] == "--size")
      size = args[i + 1];
    else if (args[i] == "--reps")
      reps = std::stoi(args[i + 1]);
    else if (args[i] == "--runs")
      runs = std::stoi(args[i + 1]);
    else
      return usage();
  }
  int w = 0, h = 0;
  if (args.size() % 2 || std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || reps < 1 || runs < 1)
    return usage();
  return parent(backends, size, reps, runs);
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-bench-shaders: %s\n", e.what());
  return 1;
}
