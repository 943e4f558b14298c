// `rill-trace noise` (see NoiseBench.h): sampling error against spp and time.
#include "NoiseBench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "LogLogSvg.h"
#include "distributed/SceneHash.h"
#include "rill/Stopwatch.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/film/AccumulationFile.h"
#include "rill/rt/scene/OutputFile.h"

namespace rt {

// A namespace of its own: rill-trace is a unity build, and AccuracyBench.cpp's file-local
// helpers have the same names.
namespace noise_impl {

namespace {

struct Variant {
  std::string name;
  bool nee, mis;
};
const std::vector<Variant> kVariants = {
    {"nee+mis", true, true}, {"nee", true, false}, {"bsdf", false, false}};

// One (backend, mode, variant) series: per spp, the median time, the error and the image's hash.
struct Point {
  int spp = 0;
  std::vector<double> times;
  double rmse = 0, rel = 0;
  double vs_strict = 0;  // RMSE against the first backend's strict image (same variant, spp)
  uint64_t hash = 0;
  bool repeatable = true;  // every repeat gave the same bits
  double median() const {
    std::vector<double> t = times;
    std::sort(t.begin(), t.end());
    return t.empty() ? 0.0 : t[t.size() / 2];
  }
};
struct Series {
  std::string backend;
  rill::Accuracy mode;
  Variant variant;
  std::vector<Point> points;
  double slope = 0, intercept = 0;  // log(rel RMSE) = intercept + slope * log(spp), the tail
  double slope_all = 0;             // the slope fitted over every spp
  std::string label() const {
    return backend + " " + rill::accuracy_name(mode) + " " + variant.name;
  }
  // The fit's spp for a relative RMSE (fractional; may lie outside the measured range).
  double spp_for(double rel) const { return std::exp((std::log(rel) - intercept) / slope); }
  double rel_at(double spp) const { return std::exp(intercept + slope * std::log(spp)); }
  // The time of a render of `spp` samples: log-log interpolation between the measured points,
  // beyond the last one proportional to spp (the fixed cost is spent), below 1 spp the 1-spp
  // time.
  double time_at(double spp) const {
    const Point& last = points.back();
    if (spp >= last.spp) return last.median() * spp / last.spp;
    if (spp <= points.front().spp) return points.front().median();
    for (size_t i = 1; i < points.size(); ++i)
      if (spp <= points[i].spp) {
        const Point &a = points[i - 1], &b = points[i];
        const double f = std::log(spp / a.spp) / std::log(static_cast<double>(b.spp) / a.spp);
        return std::exp(std::log(a.median()) + f * (std::log(b.median()) - std::log(a.median())));
      }
    return last.median();
  }
  // The inverse of time_at: the samples a time buys.
  double spp_in(double ms) const {
    double lo = 1e-3, hi = 1e12;
    for (int i = 0; i < 200; ++i) {
      const double mid = std::sqrt(lo * hi);
      (time_at(mid) < ms ? lo : hi) = mid;
    }
    return lo;
  }
};

uint64_t fnv(const std::vector<glm::vec3>& v) {
  uint64_t h = 1469598103934665603ull;
  const auto* p = reinterpret_cast<const unsigned char*>(v.data());
  for (size_t i = 0; i < v.size() * sizeof(glm::vec3); ++i) h = (h ^ p[i]) * 1099511628211ull;
  return h;
}

double rmse(const std::vector<double>& ref, const std::vector<glm::vec3>& img) {
  double sum = 0;
  for (size_t p = 0; p < img.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(img[p][c]) - ref[3 * p + c];
      sum += d * d;
    }
  return std::sqrt(sum / static_cast<double>(ref.size()));
}

std::string hex16(uint64_t h) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// "12.3 ms", "4.56 s", "2.1 min", "3.4 h".
std::string duration(double ms) {
  if (ms < 1000) return fmt("%.3g ms", ms);
  if (ms < 120e3) return fmt("%.3g s", ms / 1e3);
  if (ms < 7200e3) return fmt("%.3g min", ms / 60e3);
  return fmt("%.3g h", ms / 3600e3);
}

// The reference's mean per pixel and channel, in double, from its sums.
std::vector<double> mean_of(const Accumulation& a) {
  std::vector<double> m(3 * a.sum.size());
  for (size_t p = 0; p < a.sum.size(); ++p)
    for (int c = 0; c < 3; ++c)
      m[3 * p + c] =
          (static_cast<double>(a.sum[p][c]) + static_cast<double>(a.carry[p][c])) / a.samples;
  return m;
}

}  // namespace

int run(const NoiseBenchOptions& o) {
  // ---- what to run ------------------------------------------------------------------------
  std::vector<std::string> backends = o.backends;
  if (backends.empty())
    for (rill::Backend* b : rill::backends())
      if (b->unavailable_reason().empty()) backends.push_back(b->name());
  for (const std::string& b : backends)
    if (std::string why = rill::backend(b).unavailable_reason(); !why.empty())
      throw std::runtime_error("noise: backend " + b + " cannot run here: " + why);
  std::vector<Variant> variants;
  for (const Variant& v : kVariants)
    if (o.variants.empty() || std::count(o.variants.begin(), o.variants.end(), v.name))
      variants.push_back(v);
  for (const std::string& n : o.variants)
    if (std::none_of(kVariants.begin(), kVariants.end(),
                     [&](const Variant& v) { return v.name == n; }))
      throw std::runtime_error("noise: unknown variant '" + n + "' (nee+mis, nee, bsdf)");
  std::vector<rill::Accuracy> modes = o.modes;
  if (modes.empty()) modes = {rill::Accuracy::Strict, rill::Accuracy::Fast};
  std::vector<int> spps;
  for (int s = 1; s <= o.max_spp; s *= 2) spps.push_back(s);

  Scene scene = load_scene(o.scene);
  if (scene.options.integrator != Integrator::Path)
    throw std::runtime_error("noise: " + o.scene +
                             " is not rendered by the path integrator (options.integrator)");
  scene.width = o.width;
  scene.height = o.height;
  const Grid grid = build_grid_for(scene);
  auto settings = [&](const std::string& backend, rill::Accuracy a, int spp) {
    RenderSettings rs;
    rs.backend = backend;
    rs.accuracy = a;
    rs.width = o.width;
    rs.height = o.height;
    rs.spp = spp;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = false;
    return rs;
  };

  // ---- the reference ----------------------------------------------------------------------
  std::string ref_backend = o.ref_backend;
  if (ref_backend.empty())
    ref_backend = rill::backend("simd").unavailable_reason().empty() ? "simd" : "cpu";
  Scene ref_scene = scene;
  ref_scene.options.nee = ref_scene.options.mis = true;
  ref_scene.options.seed = o.ref_seed;
  const AccumulationKey key{
      distributed::accumulation_hash(ref_scene, "noise reference strict " + TracerOptions{}.str()),
      o.ref_seed};
  std::optional<Accumulation> ref_sums;
  if (!o.reference.empty() && std::filesystem::exists(o.reference))
    ref_sums = read_accumulation(o.reference, key, o.width, o.height);
  double ref_ms = 0;
  if (!ref_sums || ref_sums->samples < o.ref_spp) {
    const int from = ref_sums ? ref_sums->samples : 0;
    std::fprintf(stderr, "noise: reference: %d spp on %s (strict, nee+mis, seed %u)%s\n", o.ref_spp,
                 ref_backend.c_str(), o.ref_seed,
                 from ? (", resumed from " + std::to_string(from)).c_str() : "");
    Tracer ref_tracer(ref_scene, grid);
    RenderSettings rs = settings(ref_backend, rill::Accuracy::Strict, o.ref_spp);
    rs.outputs.accumulation = true;
    rs.resume = ref_sums ? &*ref_sums : nullptr;
    rill::Stopwatch clock;
    rs.after_pass = [&](int done) {
      if (done % 1024 == 0)
        std::fprintf(stderr, "noise: reference %d/%d spp, %.0f s\n", done, o.ref_spp,
                     clock.ms() / 1e3);
      return true;
    };
    RenderResult r = ref_tracer.render(rs, ref_scene.camera);
    ref_ms = clock.ms();
    ref_sums = std::move(r.accumulation);
    if (!o.reference.empty()) {
      const std::filesystem::path parent = std::filesystem::path(o.reference).parent_path();
      if (!parent.empty()) std::filesystem::create_directories(parent);
      write_accumulation(o.reference, *ref_sums, key);
    }
  } else {
    std::fprintf(stderr, "noise: reference: %d spp from %s\n", ref_sums->samples,
                 o.reference.c_str());
  }
  const std::vector<double> ref = mean_of(*ref_sums);
  double ref_mean = 0;
  for (double v : ref) ref_mean += v / static_cast<double>(ref.size());

  // ---- the measured series ----------------------------------------------------------------
  std::vector<Series> all;
  std::map<std::pair<std::string, int>, std::vector<glm::vec3>> strict_images;  // variant, spp
  for (const Variant& v : variants) {
    Scene sv = scene;
    sv.options.nee = v.nee;
    sv.options.mis = v.mis;
    sv.options.seed = o.seed;
    Tracer tracer(sv, grid);
    for (const std::string& b : backends)
      for (rill::Accuracy a : modes) {
        if (!rill::backend(b).supports(a)) continue;
        Series se{b, a, v, {}, 0, 0};
        rill::Stopwatch clock;
        for (int warm : {1, 2}) (void)tracer.render(settings(b, a, warm), sv.camera);  // compile
        std::vector<std::vector<glm::vec3>> first(spps.size());
        se.points.resize(spps.size());
        for (int rep = 0; rep < o.repeats; ++rep)
          for (size_t i = 0; i < spps.size(); ++i) {
            RenderResult r = tracer.render(settings(b, a, spps[i]), sv.camera);
            Point& p = se.points[i];
            p.spp = spps[i];
            p.times.push_back(r.trace_ms);
            const uint64_t h = fnv(r.color);
            if (rep == 0) {
              p.hash = h;
              first[i] = std::move(r.color);
            } else if (h != p.hash) {
              p.repeatable = false;
            }
          }
        for (size_t i = 0; i < spps.size(); ++i) {
          Point& p = se.points[i];
          p.rmse = rmse(ref, first[i]);
          p.rel = p.rmse / ref_mean;
          auto& si = strict_images[{v.name, spps[i]}];
          if (a == rill::Accuracy::Strict && si.empty()) si = first[i];
          if (!si.empty()) {
            std::vector<double> sd(si.size() * 3);
            for (size_t q = 0; q < si.size(); ++q)
              for (int c = 0; c < 3; ++c) sd[3 * q + c] = si[q][c];
            p.vs_strict = rmse(sd, first[i]);
          }
        }
        // Least squares of log(rel) on log(spp): over every point, and over spp >= fit_from
        // (the tail, whose line the targets and comparisons use: at low spp the pixel-area
        // (edge) error, which stratified pixel samples integrate faster, still counts).
        auto fit = [&](int from, double& slope, double& intercept) {
          double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
          for (const Point& p : se.points) {
            if (p.spp < from) continue;
            const double x = std::log(p.spp), y = std::log(std::max(p.rel, 1e-30));
            sx += x, sy += y, sxx += x * x, sxy += x * y, n += 1;
          }
          const double den = n * sxx - sx * sx;
          slope = den > 0 ? (n * sxy - sx * sy) / den : 0.0;
          intercept = n > 0 ? (sy - slope * sx) / n : 0.0;
        };
        double unused = 0;
        fit(1, se.slope_all, unused);
        // The tail needs two points: with fewer, the last two.
        fit(std::min(o.fit_from, spps.size() >= 2 ? spps[spps.size() - 2] : 1), se.slope,
            se.intercept);
        std::fprintf(
            stderr,
            "noise: %-28s slope %.3f (all %.3f), rel RMSE %.4f at %d spp, %s there (%.0f s)\n",
            se.label().c_str(), se.slope, se.slope_all, se.points.back().rel, se.points.back().spp,
            duration(se.points.back().median()).c_str(), clock.ms() / 1e3);
        all.push_back(std::move(se));
      }
  }

  // ---- strict: the same bits on every backend ----------------------------------------------
  int strict_differ = 0, unrepeatable = 0, strict_checked = 0;
  std::map<std::pair<std::string, int>, uint64_t> strict_hash;
  for (const Series& se : all)
    for (const Point& p : se.points) {
      if (!p.repeatable) ++unrepeatable;
      if (se.mode != rill::Accuracy::Strict) continue;
      auto [it, fresh] = strict_hash.emplace(std::make_pair(se.variant.name, p.spp), p.hash);
      if (!fresh) {
        ++strict_checked;
        if (it->second != p.hash) {
          ++strict_differ;
          std::fprintf(stderr, "noise: strict image differs: %s at %d spp\n", se.label().c_str(),
                       p.spp);
        }
      }
    }

  // ---- tables ------------------------------------------------------------------------------
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  std::ostringstream md, csv;
  const Series* any_strict = nullptr;
  for (const Series& se : all)
    if (se.mode == rill::Accuracy::Strict) {
      any_strict = &se;
      break;
    }
  md << "Scene " << o.scene << ", " << o.width << "x" << o.height
     << "; reference: " << ref_sums->samples << " spp, nee+mis, strict, seed " << o.ref_seed
     << (ref_ms > 0 ? ", " + std::string(ref_backend) + ", " + duration(ref_ms) : std::string())
     << "; measured renders: seed " << o.seed << ", time = trace_ms, median of " << o.repeats
     << " after a warm-up. Relative RMSE = RMSE / the reference's mean (" << fmt("%.4g", ref_mean)
     << ").\n\n";
  md << "Strict images bitwise identical across backends: "
     << (strict_differ ? "NO (" + std::to_string(strict_differ) + " of " +
                             std::to_string(strict_checked) + " differ)"
         : strict_checked ? "yes (" + std::to_string(strict_checked) + " images compared)"
                          : std::string("- (one backend)"))
     << "; repeats bitwise identical: " << (unrepeatable ? "NO" : "yes") << ".\n\n";

  // Error against spp: strict, one column per variant (every backend alike), and fast's error
  // against strict's image.
  md << "| spp |";
  for (const Variant& v : variants) md << " " << v.name << " RMSE (rel.) |";
  md << "\n|---:|";
  for (size_t i = 0; i < variants.size(); ++i) md << "---:|";
  md << "\n";
  for (size_t i = 0; i < spps.size(); ++i) {
    md << "| " << spps[i] << " |";
    for (const Variant& v : variants) {
      const Series* s = nullptr;
      for (const Series& se : all)
        if (se.variant.name == v.name && (se.mode == rill::Accuracy::Strict || !any_strict)) {
          s = &se;
          break;
        }
      if (s)
        md << " " << fmt("%.4g", s->points[i].rmse) << " (" << fmt("%.2f%%", 100 * s->points[i].rel)
           << ") |";
      else
        md << " - |";
    }
    md << "\n";
  }
  md << "\n";

  // Per series: slope, time at 1 and max spp, ms per sample, and each target.
  const int tail = std::min(o.fit_from, spps.size() >= 2 ? spps[spps.size() - 2] : 1);
  md << "| backend | mode | variant | slope (all) | slope (spp >= " << tail << ") | rel. RMSE at "
     << spps.back() << " spp | fast vs strict image (RMSE) | time at 1 spp | time at "
     << spps.back() << " spp | ms per spp |";
  for (double t : o.targets) md << " " << fmt("%g%%", 100 * t) << ": spp, time |";
  md << "\n|---|---|---|---:|---:|---:|---:|---:|---:|---:|";
  for (size_t i = 0; i < o.targets.size(); ++i) md << "---:|";
  md << "\n";
  for (const Series& se : all) {
    const Point& last = se.points.back();
    md << "| " << se.backend << " | " << rill::accuracy_name(se.mode) << " | " << se.variant.name
       << " | " << fmt("%.3f", se.slope_all) << " | " << fmt("%.3f", se.slope) << " | "
       << fmt("%.3f%%", 100 * last.rel) << " | "
       << (se.mode == rill::Accuracy::Strict ? std::string("-") : fmt("%.2g", last.vs_strict))
       << " | " << duration(se.points.front().median()) << " | " << duration(last.median()) << " | "
       << fmt("%.3g", last.median() / last.spp) << " |";
    for (double t : o.targets) {
      const double n = std::max(1.0, se.spp_for(t));
      md << " " << fmt("%.0f", n) << ", " << duration(se.time_at(n)) << " |";
    }
    md << "\n";
  }
  md << "\n";

  // What NEE and MIS buy, per backend and mode: error at equal spp (the last) and at equal time
  // (nee+mis's time at the last spp), against nee+mis.
  md << "| backend | mode | variant | RMSE vs nee+mis at " << spps.back()
     << " spp | RMSE vs nee+mis at equal time | time vs nee+mis per spp |\n"
        "|---|---|---|---:|---:|---:|\n";
  for (const Series& base : all) {
    if (base.variant.name != "nee+mis") continue;
    const double T = base.points.back().median();
    for (const Series& se : all) {
      if (se.backend != base.backend || se.mode != base.mode || &se == &base) continue;
      const double at_t = se.rel_at(se.spp_in(T)) / base.rel_at(base.spp_in(T));
      md << "| " << se.backend << " | " << rill::accuracy_name(se.mode) << " | " << se.variant.name
         << " | " << fmt("%.2fx", se.points.back().rel / base.points.back().rel) << " | "
         << fmt("%.2fx", at_t) << " | "
         << fmt("%.2fx", se.points.back().median() / base.points.back().median()) << " |\n";
    }
  }

  csv << "backend,accuracy,variant,spp,time_ms,rmse,rel_rmse,vs_strict_rmse,image_hash,"
         "repeatable\n";
  for (const Series& se : all)
    for (const Point& p : se.points)
      csv << se.backend << "," << rill::accuracy_name(se.mode) << "," << se.variant.name << ","
          << p.spp << "," << fmt("%.4f", p.median()) << "," << fmt("%.6g", p.rmse) << ","
          << fmt("%.6g", p.rel) << "," << fmt("%.3g", p.vs_strict) << "," << hex16(p.hash) << ","
          << (p.repeatable ? 1 : 0) << "\n";
  std::printf("%s", md.str().c_str());
  write_output_file((dir / "noise.md").string(), md.str());
  write_output_file((dir / "noise.csv").string(), csv.str());

  // ---- the plot ----------------------------------------------------------------------------
  static const char* colors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};
  static const char* dashes[] = {"", "6,3", "2,2"};
  auto variant_index = [&](const std::string& n) {
    for (size_t i = 0; i < kVariants.size(); ++i)
      if (kVariants[i].name == n) return static_cast<int>(i);
    return 0;
  };
  trace_cli::SvgPanel by_spp, by_time;
  by_spp.title = "relative RMSE against samples per pixel";
  by_spp.xlabel = "samples per pixel";
  by_spp.ylabel = "relative RMSE vs the reference";
  by_time.title = "relative RMSE against time (strict)";
  by_time.xlabel = "trace time (ms, median)";
  by_time.ylabel = "relative RMSE vs the reference";
  // Left: strict per variant (one line: every backend's bits), fast per variant hollow.
  for (const Variant& v : variants)
    for (rill::Accuracy a : modes) {
      const Series* s = nullptr;
      for (const Series& se : all)
        if (se.variant.name == v.name && se.mode == a) {
          s = &se;
          break;
        }
      if (!s) continue;
      trace_cli::SvgSeries ss;
      const int vi = variant_index(v.name);
      ss.label = v.name + " " + rill::accuracy_name(a) +
                 (a == rill::Accuracy::Strict ? " (every backend)" : " (" + s->backend + ")");
      ss.color = colors[vi];
      ss.dash = a == rill::Accuracy::Strict ? "" : "2,2";
      ss.marker = a == rill::Accuracy::Strict ? 0 : 1;
      ss.hollow = a != rill::Accuracy::Strict;
      for (const Point& p : s->points) ss.points.emplace_back(p.spp, p.rel);
      by_spp.series.push_back(std::move(ss));
    }
  if (!by_spp.series.empty() && !by_spp.series.front().points.empty()) {
    trace_cli::SvgSeries guide;
    guide.label = "1/sqrt(spp)";
    guide.color = "#808080";
    guide.dash = "8,4";
    guide.marker = -1;
    // Through the first series' last point: the slope its tail should have.
    const auto [xn, yn] = by_spp.series.front().points.back();
    for (int s : spps) guide.points.emplace_back(s, yn * std::sqrt(xn / s));
    by_spp.series.push_back(std::move(guide));
  }
  // Right: strict, colour per backend, dash per variant; the legend names each once.
  for (size_t bi = 0; bi < backends.size(); ++bi) {
    trace_cli::SvgSeries key;
    key.label = backends[bi];
    key.color = colors[bi % 6];
    key.marker = static_cast<int>(bi % 4);
    by_time.series.push_back(key);
  }
  for (const Variant& v : variants) {
    trace_cli::SvgSeries key;
    key.label = v.name;
    key.color = "#000000";
    key.dash = dashes[variant_index(v.name)];
    key.marker = -1;
    by_time.series.push_back(key);
  }
  const rill::Accuracy time_mode = std::count(modes.begin(), modes.end(), rill::Accuracy::Strict)
                                       ? rill::Accuracy::Strict
                                       : modes.front();
  by_time.title =
      std::string("relative RMSE against time (") + rill::accuracy_name(time_mode) + ")";
  for (const Series& se : all) {
    if (se.mode != time_mode) continue;
    const size_t bi = std::find(backends.begin(), backends.end(), se.backend) - backends.begin();
    trace_cli::SvgSeries ss;
    ss.color = colors[bi % 6];
    ss.dash = dashes[variant_index(se.variant.name)];
    ss.marker = static_cast<int>(bi % 4);
    for (const Point& p : se.points) ss.points.emplace_back(std::max(p.median(), 1e-3), p.rel);
    by_time.series.push_back(std::move(ss));
  }
  for (double t : o.targets) {
    by_spp.hlines.emplace_back(t, fmt("%g%%", 100 * t));
    by_time.hlines.emplace_back(t, fmt("%g%%", 100 * t));
  }
  write_output_file(
      (dir / "noise.svg").string(),
      trace_cli::loglog_svg("Path tracing noise: " + scene.name + " " + std::to_string(o.width) +
                                "x" + std::to_string(o.height) + ", reference " +
                                std::to_string(ref_sums->samples) + " spp",
                            {by_spp, by_time}));
  std::printf("\nwrote %s, %s, %s\n", (dir / "noise.md").c_str(), (dir / "noise.csv").c_str(),
              (dir / "noise.svg").c_str());
  return strict_differ || unrepeatable ? 1 : 0;
}

}  // namespace noise_impl

int noise_bench(const NoiseBenchOptions& o) {
  return noise_impl::run(o);
}

}  // namespace rt
