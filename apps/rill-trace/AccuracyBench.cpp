// `rill-trace accuracy` (see AccuracyBench.h): time against error for every accuracy knob.
#include "AccuracyBench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// A scene of the set, and which primitive ids count as what for the measures.
struct BenchScene {
  std::string name;
  Scene scene;
  std::vector<std::pair<int32_t, int32_t>> closed;  // [first, last) id ranges of closed meshes
  int32_t floor_end = 0;                            // ids [0, floor_end) are the lit floor
  float dark = 0.0f;  // a floor pixel at or below this (red channel) is in shadow
};

// A lit floor with a box standing on it, moved far away or scaled tiny.
BenchScene floor_scene(const std::string& name, float translate, float scale) {
  BenchScene b;
  b.name = name;
  Scene& s = b.scene;
  auto P = [&](float x, float y, float z) {
    return glm::vec3(translate) + scale * glm::vec3(x, y, z);
  };
  const glm::vec3 diffuse(0.8f);
  int mat = s.add_material(Material{}.set("diffuse", diffuse));
  add_quad(s, P(-4, 0, -4), P(4, 0, -4), P(4, 0, 4), P(-4, 0, 4), mat);
  b.floor_end = static_cast<int32_t>(s.triangle_count());
  Transform t;
  t.scale = glm::vec3(scale);
  t.translate = glm::vec3(translate);
  add_box(s, glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 1.0f, 0.5f), mat, t);
  s.lights.push_back(Light{P(1.7f, 3.0f, 1.1f), glm::vec3(1.0f)});
  s.camera = Camera{P(0.3f, 6.0f, 5.0f), P(0.3f, 0.0f, 0.5f), {0, 1, 0}, 50.0f};
  s.has_camera = true;
  s.background = glm::vec3(0.0f);
  s.options.max_depth = 1;
  b.dark = s.options.ambient * diffuse.x * 1.0001f + 1e-6f;
  return b;
}

// Closed meshes (a finely tessellated sphere, a box, a coarse sphere) in front of a wall:
// a camera ray that meets a closed mesh and ends anywhere else went through a hole.
BenchScene closed_scene() {
  BenchScene b;
  b.name = "closed";
  Scene& s = b.scene;
  int w = s.add_material(Material{}.set("diffuse", glm::vec3(0.2f, 0.3f, 0.8f)));
  int m = s.add_material(Material{}.set("diffuse", glm::vec3(0.9f, 0.6f, 0.2f)));
  add_quad(s, {-6, -4, -3}, {6, -4, -3}, {6, 4, -3}, {-6, 4, -3}, w);
  auto closed = [&](auto add) {
    const int32_t first = static_cast<int32_t>(s.triangle_count());
    add();
    b.closed.emplace_back(first, static_cast<int32_t>(s.triangle_count()));
  };
  closed([&] { add_sphere(s, {-1.2f, 0.1f, 0.0f}, 1.1f, 96, 48, m, false); });
  closed([&] { add_box(s, {0.6f, -0.9f, -0.7f}, {2.0f, 0.7f, 0.9f}, m); });
  closed([&] { add_sphere(s, {1.3f, 1.5f, 0.4f}, 0.45f, 7, 5, m, false); });
  s.lights.push_back(Light{{3, 5, 6}, glm::vec3(1.0f)});
  s.camera = Camera{{0.4f, 0.9f, 6.0f}, {0.1f, 0.2f, 0.0f}, {0, 1, 0}, 45.0f};
  s.has_camera = true;
  s.options.max_depth = 1;
  return b;
}

// The camera inside a closed cube, at its centre, looking along a face diagonal over a wide
// field: the image's diagonals run along the cube's edges and into its corners, where the
// two triangles of a face and the faces meet. Every pixel must hit the cube.
BenchScene inside_scene() {
  BenchScene b;
  b.name = "inside";
  Scene& s = b.scene;
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f),
          s.add_material(Material{}.set("diffuse", glm::vec3(0.7f, 0.7f, 0.6f))));
  b.closed.emplace_back(0, static_cast<int32_t>(s.triangle_count()));
  s.lights.push_back(Light{{0.3f, 0.5f, 0.2f}, glm::vec3(1.0f)});
  s.camera = Camera{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {0, 1, 0}, 120.0f};
  s.has_camera = true;
  s.background = glm::vec3(1.0f, 0.0f, 1.0f);
  s.options.max_depth = 1;
  return b;
}

std::vector<BenchScene> scene_set() {
  std::vector<BenchScene> v;
  v.push_back(closed_scene());
  v.push_back(inside_scene());
  v.push_back(floor_scene("floor-far", 1e4f, 1.0f));
  v.push_back(floor_scene("floor-tiny", 0.0f, 1e-4f));
  for (const char* n : {"cornell", "glass"}) {
    BenchScene b;
    b.name = n;
    b.scene = builtin_scene(n);
    v.push_back(std::move(b));
  }
  return v;
}

struct Config {
  std::string backend;
  rill::Accuracy accuracy = rill::Accuracy::Strict;
  TracerOptions knobs;
  int depth = -1;  // -1: the scene's
  int spp = 1;
  std::string label() const {
    std::string s = backend + " " + rill::accuracy_name(accuracy) + " " + knobs.str();
    if (depth >= 0) s += " depth=" + std::to_string(depth);
    if (spp > 1) s += " spp=" + std::to_string(spp);
    return s;
  }
  int knob_index() const {
    return (knobs.triangle == TriangleTest::Watertight ? 4 : 0) +
           (knobs.offset == SelfIntersection::Scaled ? 2 : 0) +
           (knobs.traversal == Traversal::Recompute ? 1 : 0);
  }
};

struct Measure {
  std::vector<double> times;  // trace ms per repeat
  double rmse = 0, psnr = 0;
  int holes = 0, acne = 0;
  bool against_supersampled = false;
  double median() const {
    std::vector<double> t = times;
    std::sort(t.begin(), t.end());
    return t.empty() ? 0.0 : t[t.size() / 2];
  }
};

double rmse(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
  double sum = 0;
  for (size_t p = 0; p < a.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      double d = static_cast<double>(a[p][c]) - static_cast<double>(b[p][c]);
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * static_cast<double>(a.size())));
}

void measure_errors(const BenchScene& bs, const RenderResult& ref, const RenderResult& r,
                    Measure& m) {
  m.rmse = rmse(ref.color, r.color);
  m.psnr = m.rmse > 0 ? 20.0 * std::log10(1.0 / m.rmse) : INFINITY;
  m.holes = m.acne = 0;
  if (r.color.size() != ref.color.size()) return;
  for (size_t p = 0; p < ref.prim.size(); ++p) {
    for (const auto& [a, b] : bs.closed)
      if (ref.prim[p] >= a && ref.prim[p] < b && !(r.prim[p] >= a && r.prim[p] < b)) ++m.holes;
    if (bs.floor_end > 0 && ref.prim[p] >= 0 && ref.prim[p] < bs.floor_end && r.prim[p] >= 0 &&
        r.prim[p] < bs.floor_end && ref.color[p].x > bs.dark * 1.05f && r.color[p].x <= bs.dark)
      ++m.acne;
  }
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

int accuracy_bench(const AccuracyBenchOptions& o) {
  std::vector<std::string> backends = o.backends;
  if (backends.empty())
    for (rill::Backend* b : rill::backends())
      if (b->unavailable_reason().empty()) backends.push_back(b->name());
  for (const std::string& b : backends) {
    rill::Backend& be = rill::backend(b);  // throws for an unknown name
    if (std::string why = be.unavailable_reason(); !why.empty())
      throw std::runtime_error("accuracy: backend " + b + " cannot run here: " + why);
  }
  std::vector<BenchScene> scenes;
  for (BenchScene& s : scene_set())
    if (o.scenes.empty() || std::count(o.scenes.begin(), o.scenes.end(), s.name))
      scenes.push_back(std::move(s));
  if (scenes.empty()) throw std::runtime_error("accuracy: no scene of the set matches --scenes");

  // The configurations: every knob combination in each math mode on each backend (or one
  // knob at a time from the default), then depth and samples per pixel at the defaults.
  std::vector<TracerOptions> knob_sets;
  const int def = Config{"", rill::Accuracy::Strict, TracerOptions{}}.knob_index();
  for (int k = 0; k < 8; ++k) {
    TracerOptions t;
    t.triangle = (k & 4) ? TriangleTest::Watertight : TriangleTest::MollerTrumbore;
    t.offset = (k & 2) ? SelfIntersection::Scaled : SelfIntersection::Epsilon;
    t.traversal = (k & 1) ? Traversal::Recompute : Traversal::Incremental;
    const int changed = k ^ def;  // the knobs that differ from the default (bits)
    if (o.factorial || changed == 0 || changed == 1 || changed == 2 || changed == 4)
      knob_sets.push_back(t);
  }
  std::vector<Config> configs;
  for (const std::string& b : backends) {
    for (rill::Accuracy a :
         {rill::Accuracy::Strict, rill::Accuracy::Fast, rill::Accuracy::Double}) {
      if (!rill::backend(b).supports(a)) continue;
      for (const TracerOptions& t : knob_sets) configs.push_back({b, a, t, -1, 1});
    }
    for (int depth : {0, 2}) configs.push_back({b, rill::Accuracy::Strict, {}, depth, 1});
    configs.push_back({b, rill::Accuracy::Strict, {}, -1, 4});
  }

  // results[scene][config]
  std::vector<std::vector<Measure>> results(scenes.size(), std::vector<Measure>(configs.size()));
  for (size_t si = 0; si < scenes.size(); ++si) {
    BenchScene& bs = scenes[si];
    Scene& s = bs.scene;
    Grid grid = build_grid(s, 0);
    std::map<int, std::unique_ptr<Tracer>> tracers;  // per knob set
    auto tracer = [&](const TracerOptions& t) -> Tracer& {
      Config c{"", rill::Accuracy::Strict, t};
      auto& p = tracers[c.knob_index()];
      if (!p) p = std::make_unique<Tracer>(s, grid, t);
      return *p;
    };
    auto render = [&](const Config& c) {
      RenderSettings rs;
      rs.backend = c.backend;
      rs.accuracy = c.accuracy;
      rs.width = o.width;
      rs.height = o.height;
      rs.max_depth = c.depth;
      rs.spp = c.spp;
      // The first-hit AOVs too: the holes and dark-floor counts compare primitive ids.
      rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
      return tracer(c.knobs).render(rs, s.camera);
    };
    // The deep references: cpu, double, watertight, scaled offset, depth 8; one sample
    // (the knob rows take the same sample positions) and 16 (for the spp rows).
    Config ref_cfg{"cpu", rill::Accuracy::Double, {}, 8, 1};
    ref_cfg.knobs.triangle = TriangleTest::Watertight;
    ref_cfg.knobs.offset = SelfIntersection::Scaled;
    const RenderResult ref = render(ref_cfg);
    ref_cfg.spp = 16;
    const RenderResult ref16 = render(ref_cfg);
    std::fprintf(stderr, "accuracy: %s (%zu triangles): %zu configurations x %d repeats\n",
                 bs.name.c_str(), s.triangle_count(), configs.size(), o.repeats);
    std::vector<RenderResult> last(configs.size());
    for (size_t ci = 0; ci < configs.size(); ++ci) (void)render(configs[ci]);  // compile, warm
    for (int rep = 0; rep < o.repeats; ++rep)  // interleaved: drift hits every config alike
      for (size_t ci = 0; ci < configs.size(); ++ci) {
        RenderResult r = render(configs[ci]);
        results[si][ci].times.push_back(r.trace_ms);
        if (rep == 0) last[ci] = std::move(r);
      }
    for (size_t ci = 0; ci < configs.size(); ++ci) {
      const bool ss = configs[ci].spp > 1;
      measure_errors(bs, ss ? ref16 : ref, last[ci], results[si][ci]);
      if (ss) results[si][ci].holes = results[si][ci].acne = -1;  // the colour is a mean
      results[si][ci].against_supersampled = ss;
    }
  }

  // ---- the table: Markdown (stdout and file) and CSV --------------------------------------
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  std::ostringstream md, csv;
  md << "| configuration |";
  for (const BenchScene& bs : scenes) md << " " << bs.name << " |";
  md << " total ms | mean PSNR |\n|---|";
  for (size_t i = 0; i < scenes.size() + 2; ++i) md << "---|";
  md << "\n";
  csv << "backend,accuracy,triangle,offset,traversal,depth,spp,scene,time_ms,rmse,psnr,holes,"
         "acne\n";
  for (size_t ci = 0; ci < configs.size(); ++ci) {
    const Config& c = configs[ci];
    md << "| " << c.label() << " |";
    double total = 0, psnr_sum = 0;
    int finite = 0;
    for (size_t si = 0; si < scenes.size(); ++si) {
      const Measure& m = results[si][ci];
      total += m.median();
      if (std::isfinite(m.psnr)) psnr_sum += m.psnr, ++finite;
      md << " " << fmt("%.1f ms", m.median()) << ", "
         << (std::isfinite(m.psnr) ? fmt("%.1f dB", m.psnr) : std::string("exact"));
      auto count = [](int n) { return n < 0 ? std::string("-") : std::to_string(n); };
      if (!scenes[si].closed.empty()) md << ", " << count(m.holes) << " holes";
      if (scenes[si].floor_end > 0) md << ", " << count(m.acne) << " acne";
      md << " |";
      const TracerOptions& k = c.knobs;
      csv << c.backend << "," << rill::accuracy_name(c.accuracy) << ","
          << (k.triangle == TriangleTest::Watertight ? "watertight" : "moller") << ","
          << (k.offset == SelfIntersection::Scaled ? "scaled" : "epsilon") << ","
          << (k.traversal == Traversal::Recompute ? "recompute" : "incremental") << "," << c.depth
          << "," << c.spp << "," << scenes[si].name << "," << fmt("%.3f", m.median()) << ","
          << fmt("%.6g", m.rmse) << "," << fmt("%.2f", m.psnr) << "," << m.holes << "," << m.acne
          << "\n";
    }
    md << " " << fmt("%.1f", total) << " | "
       << (finite ? fmt("%.1f dB", psnr_sum / finite) : std::string("exact")) << " |\n";
  }
  md << "\nError against the deep reference (cpu, double, watertight, scaled, depth 8; rows with "
        "spp > 1 against its 16-sample image). Times: trace only, median of "
     << o.repeats << " interleaved repeats, " << o.width << "x" << o.height << " pixels.\n";
  std::printf("%s", md.str().c_str());
  write_output_file((dir / "accuracy.md").string(), md.str());
  write_output_file((dir / "accuracy.csv").string(), csv.str());

  // ---- the plot: error against time; one series per knob setting, a point per backend
  // and math mode (the backends' times differ tenfold, so they form clusters along x) ----
  std::vector<std::string> series;
  std::map<std::string, std::ostringstream> points;
  for (size_t ci = 0; ci < configs.size(); ++ci) {
    const Config& c = configs[ci];
    std::string name = c.depth >= 0 || c.spp > 1 ? std::string("depth, spp") : c.knobs.str();
    if (!points.count(name)) series.push_back(name);
    // The geometric mean of the scenes' RMSE (an exact image counts as 1e-8): the scenes'
    // errors differ by orders of magnitude, and an arithmetic mean would show only the
    // largest (glass, limited by its depth).
    double total = 0, log_err = 0;
    for (size_t si = 0; si < scenes.size(); ++si) {
      total += results[si][ci].median();
      log_err +=
          std::log(std::max(results[si][ci].rmse, 1e-8)) / static_cast<double>(scenes.size());
    }
    points[name] << fmt("%.4f", total) << " " << fmt("%.6g", std::exp(log_err)) << " \""
                 << c.backend << " " << rill::accuracy_name(c.accuracy) << "\"\n";
  }
  std::ostringstream dat;
  for (size_t i = 0; i < series.size(); ++i)
    dat << (i ? "\n\n" : "") << "# " << series[i] << "\n" << points[series[i]].str();
  write_output_file((dir / "accuracy-plot.dat").string(), dat.str());
  std::ostringstream gp;
  gp << "# gnuplot accuracy.gp -> accuracy.svg (written by rill-trace accuracy)\n"
        "set terminal svg size 1100,650 dynamic font 'sans,11'\n"
        "set output 'accuracy.svg'\n"
        "set title 'Ray tracer accuracy knobs: error against time ("
     << o.width << "x" << o.height << ", " << scenes.size()
     << " scenes)'\n"
        "set xlabel 'trace time over the scene set (ms, median)'\n"
        "set ylabel 'RMSE against the deep double reference (geometric mean over the scenes)'\n"
        "set logscale xy\nset grid\nset key outside right\n"
        "plot ";
  for (size_t i = 0; i < series.size(); ++i)
    gp << (i ? ", \\\n     " : "") << "'accuracy-plot.dat' index " << i
       << " using 1:2 with points pt " << (4 + i % 10) << " ps 1.3 title '" << series[i] << "'";
  gp << "\n";
  write_output_file((dir / "accuracy.gp").string(), gp.str());
  bool plotted = false;
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    const std::string cmd = "cd '" + dir.string() + "' && gnuplot accuracy.gp";
    plotted = std::system(cmd.c_str()) == 0;
  }
  std::printf("\nwrote %s, %s, %s%s\n", (dir / "accuracy.md").c_str(),
              (dir / "accuracy.csv").c_str(), (dir / "accuracy.gp").c_str(),
              plotted ? (", " + (dir / "accuracy.svg").string()).c_str() : " (no gnuplot: no SVG)");
  return 0;
}

}  // namespace rt
