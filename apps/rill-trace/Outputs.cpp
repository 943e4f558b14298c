#include "Outputs.h"

#include <cstdio>
#include <cstdlib>

#include "Doing.h"
#include "rill/rt/accel/LightBuffer.h"
#include "rill/rt/megakernel/Megakernel.h"
#include "rill/rt/render/ResultFiles.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/NameList.h"
#include "rill/rt/scene/OutputFile.h"

namespace trace_cli {

namespace {

std::vector<float> to_float(const std::vector<int32_t>& v) {
  std::vector<float> f(v.size());
  for (size_t i = 0; i < v.size(); ++i) f[i] = static_cast<float>(v[i]);
  return f;
}

// --exr: the linear colour (R G B) and the AOVs (Z, N.X N.Y N.Z, prim) as 32-bit channels,
// always (docs/cli.md), and var.* and albedo.* where --variance and --albedo read them back.
// prim is UINT, the id's 32 bits as they are: exact for every id (a scene may have 2^26
// triangles, more than a float holds exactly), a miss (-1) 4294967295.
void write_exr_output(const std::string& path, const rt::RenderResult& r) {
  const size_t n = static_cast<size_t>(r.width) * static_cast<size_t>(r.height);
  if (r.color.size() != n || r.depth.size() != n || r.normal.size() != n || r.prim.size() != n)
    throw rt::SceneError("cannot write " + path + ": the render did not read back every AOV");
  rt::write_exr(path, r);
}

}  // namespace

std::vector<std::string> write_outputs(const RenderOptions& o, const Prepared& p,
                                       const rt::RenderResult& r, const NameOf& name) {
  g_doing = "writing the outputs";
  std::vector<std::string> written;
  auto pfm = [&](const std::string& path, const auto& data) {
    if (path.empty()) return;
    rt::write_pfm(name(path), r.width, r.height, data);
    written.push_back(name(path));
  };
  if (!p.out.empty()) {
    rt::write_png_rgb8(name(p.out), r.width, r.height, r.rgb8);
    written.push_back(name(p.out));
  }
  pfm(o.pfm, r.color);
  pfm(o.depth, r.depth);
  if (!o.prim.empty()) pfm(o.prim, to_float(r.prim));
  pfm(o.normal, r.normal);
  pfm(o.albedo, r.albedo);
  if (!o.exr.empty()) {
    write_exr_output(name(o.exr), r);
    written.push_back(name(o.exr));
  }
  return written;
}

PathLaunches path_launches(const RenderOptions& o, const Prepared& p) {
  if (p.scene.options.integrator != rt::Integrator::Path ||
      !(o.strategy == rt::Strategy::Megakernel))
    return {};
  // As Progressive.cpp and the megakernel decide, in that order.
  if (o.time_limit > 0) return {1, "--time-limit"};
  if (p.rs.outputs.variance) return {1, "--variance"};
  const char* env = std::getenv("RILL_PATH_REGENERATE");
  const int n = rt::path_samples_per_launch(p.rs.path_samples_per_launch, o.backend);
  return {n, env != nullptr ? "RILL_PATH_REGENERATE=" + std::string(env)
                            : "the " + o.backend + " backend's default"};
}

nlohmann::json stats_json(const RenderOptions& o, const Prepared& p, int width, int height,
                          int64_t rays) {
  const rt::Scene& scene = p.scene;
  const rt::Grid& grid = p.grid;
  nlohmann::json j;
  j["scene"] = o.scene;
  j["triangles"] = scene.triangle_count();
  j["width"] = width;
  j["height"] = height;
  j["backend"] = o.backend;
  j["accuracy"] = rill::accuracy_name(o.accuracy);
  j["strategy"] = o.strategy.name;
  if (o.strategy == rt::Strategy::Megakernel)
    j["megakernel_loop"] = rt::megakernel_loop_name(rt::megakernel_loop_for(p.rs.loop, o.backend));
  if (const PathLaunches pl = path_launches(o, p); pl.per_launch > 0)
    j["path_samples_per_launch"] = {{"samples", pl.per_launch}, {"why", pl.why}};
  j["knobs"] = o.knobs.str();
  j["spp"] = scene.options.spp;
  j["max_depth"] = scene.options.max_depth;
  j["features"] = p.tracer->features().str();
  j["grid"] = {{"resolution", {grid.res.x, grid.res.y, grid.res.z}},
               {"density", rt::grid_density_for(scene.options.grid_density, o.backend,
                                                scene.triangle_count(), scene.options.integrator)},
               {"subgrids", grid.subgrids},
               {"references", grid.elements.size()},
               {"triangles", grid.usable},
               {"degenerate", grid.degenerate},
               {"non_finite", grid.non_finite}};
  const rt::LightBufferStats& lb = p.tracer->light_buffer();
  j["light_buffer"] = {{"resolution", lb.res},
                       {"entries", lb.entries},
                       {"fallback_cells", lb.fallback_cells},
                       {"build_ms", lb.build_ms},
                       {"skipped", lb.skipped}};
  j["warnings"] = scene.warnings;
  j["rays"] = rays;
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  rt::write_output_file(path, j.dump(2) + "\n");
}

void write_source(const RenderOptions& o, const Prepared& p) {
  if (o.source.empty()) return;
  rt::write_output_file(o.source, p.tracer->source(o.backend, o.accuracy, p.rs.loop, p.rs.outputs,
                                                   p.scene.options.spp));
}

void print_notes(const RenderOptions& o, const Prepared& p,
                 const std::vector<std::string>& written) {
  if (o.quiet) return;
  // A long sequence's files: the first few, then how many more and the last (a video's, when
  // there is one), never dropped without a word.
  for (size_t i = 0; i < written.size() && i < kWroteShown; ++i)
    std::printf("wrote %s\n", written[i].c_str());
  if (written.size() > kWroteShown)
    std::printf("... and %s more (the last: %s)\n",
                rt::grouped(written.size() - kWroteShown).c_str(), written.back().c_str());
  glm::vec3 lo, hi;
  if (rt::scene_bounds(p.scene, lo, hi)) {
    // In double: the float length of a 1e20-unit box overflows.
    const double size = glm::length(glm::dvec3(hi) - glm::dvec3(lo));
    if (size < 1e-10f || size > 1e10f)
      std::printf(
          "note: the scene is %g units across; the intersection test's cubic terms underflow "
          "(GLSL flushes them) or overflow outside about 1e-10..1e10\n",
          static_cast<double>(size));
  }
  if (p.grid.degenerate + p.grid.non_finite > 0)
    std::printf("note: %zu degenerate and %zu non-finite triangles are never hit\n",
                p.grid.degenerate, p.grid.non_finite);
}

}  // namespace trace_cli
