// The thesis's multipass stream ray tracer against the single kernel, per backend.
//
//   rill-bench-multipass [--full] [--repeats R] [--backends cpu,opencl,glsl] [--only abc]
//                        [--sizes 256,1024] [--depths 1,2,3] [--smoke]
//
// Three tables, each measured side by side in one run (the configurations compared are
// interleaved within every repeat, and medians of the trace time are reported):
//   (a) strategy   megakernel vs multipass (masked, 20% threshold) on builtin:thesis-a,
//                  thesis-b, thesis-c over image sizes and reflection depths;
//   (b) masking    multipass with masked launches on vs off: time, and the elements the
//                  passes ran on (processed) in each case;
//   (c) threshold  the intersector's rerun threshold from 5% to 100%: launches and time,
//                  relative to the thesis's 20%.
// The default (quick) keeps it affordable on a 2-core machine with llvmpipe: 128x128,
// depths 1, 4 and 8, 3 repeats (tables b and c at depth 4). --full: 256x256 and 1024x1024,
// depths 1..8, 5 repeats. Every multipass image is compared with the megakernel's (strict: they
// must be bitwise identical); a mismatch is reported and makes the exit status 1. --smoke: a tiny
// run for the CTest smoke test.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "CommaList.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"
#include "Timing.h"
#include "rill/rt/Tracer.h"

namespace {

using rill::bench::median;
using rill::bench::split_list;

struct Setup {
  std::string name;
  rt::Scene scene;
  std::unique_ptr<rt::Grid> grid;
  std::unique_ptr<rt::Tracer> tracer;
};

struct Config {
  rt::Strategy strategy = rt::Strategy::Multipass;
  bool masking = true;
  double threshold = 0.2;
};

struct Run {
  double ms = 0;
  int64_t launches = 0, processed = 0;
  std::vector<glm::vec3> color;
};

Run render(Setup& s, const std::string& backend, int size, int depth, const Config& c) {
  rt::RenderSettings rs;
  rs.backend = backend;
  rs.strategy = c.strategy;
  rs.width = rs.height = size;
  rs.max_depth = depth;
  rs.spp = 1;
  rs.masking = c.masking;
  rs.wait_threshold = c.threshold;
  rt::RenderResult r = s.tracer->render(rs, s.scene.camera);
  Run out;
  out.ms = r.trace_ms;
  out.launches = r.launches;
  for (const rt::PassStats& p : r.passes) out.processed += p.processed;
  out.color = std::move(r.color);
  return out;
}

bool same_bits(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0;
}

// Renders every config `repeats` times, interleaved; returns per config the median run
// (time: median; counts and image: from the last repeat, they do not vary).
std::vector<Run> measure(Setup& s, const std::string& backend, int size, int depth,
                         const std::vector<Config>& configs, int repeats) {
  std::vector<std::vector<double>> times(configs.size());
  std::vector<Run> last(configs.size());
  for (size_t i = 0; i < configs.size(); ++i)
    render(s, backend, size, depth, configs[i]);  // compile, warm up
  for (int rep = 0; rep < repeats; ++rep)
    for (size_t i = 0; i < configs.size(); ++i) {
      last[i] = render(s, backend, size, depth, configs[i]);
      times[i].push_back(last[i].ms);
    }
  for (size_t i = 0; i < configs.size(); ++i) last[i].ms = median(times[i]);
  return last;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rill-bench-multipass: multipass vs single-kernel ray tracing, masking, threshold"};
  bool full = false, smoke = false;
  int repeats = 0;
  std::string backends_opt = "all", only = "abc", sizes_opt, depths_opt;
  app.add_flag("--full", full, "256x256 and 1024x1024, depths 1..8, 5 repeats (hours on llvmpipe)");
  app.add_flag("--smoke", smoke, "a tiny run (for CTest)");
  app.add_option("--repeats", repeats, "timed repeats per configuration (default 3, --full 5)");
  app.add_option("--backends", backends_opt, "all, or a list such as cpu,glsl");
  app.add_option("--only", only, "which tables: any of a, b, c (default abc)");
  app.add_option("--sizes", sizes_opt,
                 "image sizes (square), e.g. 256,1024; the first is used for b and c");
  app.add_option("--depths", depths_opt, "reflection depths for table a, e.g. 1,2,4");
  CLI11_PARSE(app, argc, argv);

  try {
    std::vector<int> sizes = {128};
    std::vector<int> depths = {1, 4, 8};
    std::vector<std::string> scenes = {"thesis-a", "thesis-b", "thesis-c"};
    int rep = 3;
    int fixed_depth = 4;  // for (b) and (c)
    if (full) {
      sizes = {256, 1024};
      depths = {1, 2, 3, 4, 5, 6, 7, 8};
      rep = 5;
    }
    if (smoke) {
      sizes = {24};
      depths = {1};
      scenes = {"thesis-a"};
      rep = 1;
      fixed_depth = 1;
    }
    if (repeats > 0) rep = repeats;
    if (!sizes_opt.empty()) {
      sizes.clear();
      for (const std::string& v : split_list(sizes_opt)) sizes.push_back(std::stoi(v));
    }
    if (!depths_opt.empty()) {
      depths.clear();
      for (const std::string& v : split_list(depths_opt)) depths.push_back(std::stoi(v));
    }

    std::vector<std::string> backends;
    for (rill::Backend* b : rill::backends()) {
      if (backends_opt != "all") {
        auto wanted = split_list(backends_opt);
        if (std::find(wanted.begin(), wanted.end(), b->name()) == wanted.end()) continue;
      }
      if (std::string why = b->unavailable_reason(); !why.empty()) {
        std::printf("%s: unavailable (%s), skipped\n", b->name().c_str(), why.c_str());
        continue;
      }
      backends.push_back(b->name());
    }
    std::printf("rill-bench-multipass: %s, %d repeats (median trace ms), strict\n",
                full    ? "--full"
                : smoke ? "--smoke"
                        : "quick",
                rep);

    std::vector<Setup> setups;
    for (const std::string& name : scenes) {
      Setup s;
      s.name = name;
      s.scene = rt::load_scene("builtin:" + name);
      s.grid = std::make_unique<rt::Grid>(rt::build_grid_for(s.scene));
      s.tracer = std::make_unique<rt::Tracer>(s.scene, *s.grid);
      setups.push_back(std::move(s));
    }

    bool mismatch = false;
    const Config mega{rt::Strategy::Megakernel, true, 0.2}, multi{};
    const bool table_a = only.find('a') != std::string::npos;
    const bool table_b = only.find('b') != std::string::npos;
    const bool table_c = only.find('c') != std::string::npos;
    if (table_a) std::printf("\n(a) single kernel vs multipass (masking on, threshold 20%%)\n");
    if (table_a)
      std::printf("%-8s %-9s %5s %5s %11s %11s %8s %9s %s\n", "backend", "scene", "size", "depth",
                  "single ms", "multi ms", "multi/1", "launches", "image");
    if (table_a)
      for (const std::string& be : backends)
        for (Setup& s : setups)
          for (int size : sizes)
            for (int depth : depths) {
              std::vector<Run> r = measure(s, be, size, depth, {mega, multi}, rep);
              const bool same = same_bits(r[0].color, r[1].color);
              mismatch |= !same;
              std::printf("%-8s %-9s %5d %5d %11.2f %11.2f %8.2f %9lld %s\n", be.c_str(),
                          s.name.c_str(), size, depth, r[0].ms, r[1].ms, r[1].ms / r[0].ms,
                          static_cast<long long>(r[1].launches), same ? "identical" : "DIFFERENT");
              std::fflush(stdout);
            }

    const int size_bc = sizes.front();
    if (table_b)
      std::printf("\n(b) multipass masking on vs off (%dx%d, depth %d, threshold 20%%)\n", size_bc,
                  size_bc, fixed_depth);
    if (table_b)
      std::printf("%-8s %-9s %9s %9s %7s %14s %14s %s\n", "backend", "scene", "on ms", "off ms",
                  "on/off", "processed on", "processed off", "image");
    const Config off{rt::Strategy::Multipass, false, 0.2};
    if (table_b)
      for (const std::string& be : backends)
        for (Setup& s : setups) {
          std::vector<Run> r = measure(s, be, size_bc, fixed_depth, {multi, off}, rep);
          const bool same = same_bits(r[0].color, r[1].color);
          mismatch |= !same;
          std::printf("%-8s %-9s %9.2f %9.2f %7.2f %14lld %14lld %s\n", be.c_str(), s.name.c_str(),
                      r[0].ms, r[1].ms, r[0].ms / r[1].ms, static_cast<long long>(r[0].processed),
                      static_cast<long long>(r[1].processed), same ? "identical" : "DIFFERENT");
          std::fflush(stdout);
        }

    if (table_c)
      std::printf(
          "\n(c) intersector rerun threshold (%dx%d, depth %d, masking on): launches, ms, "
          "time relative to 20%%\n",
          size_bc, size_bc, fixed_depth);
    const std::vector<double> thresholds = {0.05, 0.10, 0.20, 0.30, 0.50, 0.75, 1.00};
    if (table_c) {
      std::printf("%-8s %-9s", "backend", "scene");
      for (double t : thresholds) std::printf(" %17.0f%%", t * 100);
      std::printf("\n");
    }
    if (table_c)
      for (const std::string& be : backends)
        for (Setup& s : setups) {
          std::vector<Config> configs;
          for (double t : thresholds) configs.push_back({rt::Strategy::Multipass, true, t});
          std::vector<Run> r = measure(s, be, size_bc, fixed_depth, configs, rep);
          std::printf("%-8s %-9s", be.c_str(), s.name.c_str());
          for (size_t i = 0; i < r.size(); ++i) {
            mismatch |= !same_bits(r[i].color, r[2].color);
            std::printf(" %5lld %7.1f %4.2f", static_cast<long long>(r[i].launches), r[i].ms,
                        r[i].ms / r[2].ms);
          }
          std::printf("\n");
          std::fflush(stdout);
        }
    if (mismatch) {
      std::printf("\nERROR: some multipass image differs from the single kernel's\n");
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rill-bench-multipass: %s\n", e.what());
    return 1;
  }
}
