// rill-trace demo: renders a scene (the flagship, builtin:glass, by default) on every backend
// that runs here, writes a PNG of each and checks that the images are bitwise identical.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <utility>
#include <vector>

#include "CliChecks.h"
#include "Commands.h"
#include "rill/Stopwatch.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

using Clock = std::chrono::steady_clock;
using rill::ms_since;

CLI::App* add_demo_command(CLI::App& app, DemoOptions& o) {
  CLI::App* d =
      app.add_subcommand("demo", "render the flagship scene on every backend and compare");
  d->add_option("--scene", o.scene, "scene to render")->default_str("builtin:glass");
  add_parsed_option(d, "--size", o.size, checked_size, "image size WxH");
  d->add_option("--out-dir", o.out_dir, "where the PNGs go");
  return d;
}

int demo(const DemoOptions& o) {
  const std::string& scene_spec = o.scene;
  const std::string& size = o.size;
  const std::string& out_dir = o.out_dir;
  rt::Scene scene = rt::load_scene(scene_spec);
  if (!size.empty()) parse_size(size, scene.width, scene.height);
  scene.validate();
  rt::Grid grid = rt::build_grid_for(scene);
  rt::Tracer tracer(scene, grid);
  std::printf("rill-trace demo: %s, %zu triangles, %dx%d, grid %dx%dx%d, kernel features: %s\n",
              scene.name.c_str(), scene.triangle_count(), scene.width, scene.height, grid.res.x,
              grid.res.y, grid.res.z, tracer.features().str().c_str());
  std::filesystem::create_directories(out_dir.empty() ? "." : out_dir);
  std::vector<std::pair<std::string, rt::RenderResult>> results;
  for (rill::Backend* b : rill::backends()) {
    if (std::string why = b->unavailable_reason(); !why.empty()) {
      std::printf("  %-7s unavailable: %s\n", b->name().c_str(), why.c_str());
      continue;
    }
    rt::RenderSettings rs;
    rs.backend = b->name();
    rs.width = scene.width;
    rs.height = scene.height;
    // The first-hit AOVs too: the backends' images are compared by primitive id below.
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
    const auto t = Clock::now();
    rt::RenderResult r = tracer.render(rs, scene.camera);
    const double total = ms_since(t);
    std::string png = (std::filesystem::path(out_dir.empty() ? "." : out_dir) /
                       ("demo-" + scene.name + "-" + b->name() + ".png"))
                          .string();
    rt::write_png(png, r.width, r.height, r.color);
    // One render per backend: its trace is cold (RenderResult::cold), and its speed says so.
    std::printf("  %-7s compile %8.1f ms%s  trace %8.1f ms  %7.3f Mrays/s%s  -> %s\n",
                b->name().c_str(), total - r.trace_ms, r.from_cache ? " (cached)" : "         ",
                r.trace_ms, r.trace_ms > 0 ? static_cast<double>(r.rays) / (r.trace_ms * 1e3) : 0.0,
                r.cold ? " cold" : "", png.c_str());
    results.emplace_back(b->name(), std::move(r));
  }
  if (results.empty()) throw rt::SceneError("no backend can run here");
  bool all_same = true;
  for (size_t i = 1; i < results.size(); ++i) {
    const auto& a = results[0].second;
    const auto& b = results[i].second;
    size_t diff = 0;
    for (size_t p = 0; p < a.color.size(); ++p)
      if (std::memcmp(&a.color[p], &b.color[p], sizeof(glm::vec3)) != 0 || a.prim[p] != b.prim[p])
        ++diff;
    std::printf(
        "  %s vs %s: %s\n", results[0].first.c_str(), results[i].first.c_str(),
        diff == 0 ? "bitwise identical" : (std::to_string(diff) + " pixels differ").c_str());
    all_same = all_same && diff == 0;
  }
  if (results.size() > 1)
    std::printf("rill-trace demo: the images are %s\n",
                all_same ? "identical on every backend" : "NOT identical");
  if (!all_same)
    throw rt::SceneError(
        "demo: the backends' images differ (strict mode should make them identical)");
  return 0;
}

}  // namespace trace_cli
