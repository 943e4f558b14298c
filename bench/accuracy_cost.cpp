// What accuracy costs in time: representative kernels on every backend in every accuracy
// mode, timed side by side, each with its error against a double-precision host reference.
//
//   rill-bench-accuracy [--size WxH] [--iterations N] [--repeats R]
//                       [--backends cpu,opencl,glsl] [--kernels math,branchy,mandelbrot]
//                       [--csv FILE] [--md FILE]
//
// The kernels (docs/accuracy.md, "What accuracy costs in time"):
//   math        a chain of the DSL's transcendental functions per element (exp, log, sin,
//               cos, pow, atan2, sqrt, atan, exp2, log2, tan), over inputs spread on [0.1, 4];
//   branchy     a piecewise iteration with nested RILL_IF / RILL_WHILE whose path and trip
//               counts depend on the data (branches on fract(v), an inner halving loop);
//   mandelbrot  the escape-time kernel of rill-bench-mandelbrot (MandelbrotKernel.h).
// Every kernel is compiled for each backend and mode (strict, fast, double; a mode a backend
// lacks is reported as n/a with the reason). All variants of one kernel are run R times
// interleaved (one run of each per round, after a warm-up run), and the table shows the
// median, the ratio to strict on the same backend, and the error of the result against the
// same computation in double on the host (<cmath>): max ulp (in float ulps of the
// reference) and RMS relative error of the float output, and the number of elements whose
// integer result (Mandelbrot iteration count, branchy path signature) differs from the reference
// (the float figures of the branchy kernel leave those elements out: see measure()).
// Results stay on the device between runs (a launch includes no download).
#include <rill/rill.h>
#include <tbb/info.h>
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "CommaList.h"
#include "MandelbrotKernel.h"
#include "Timing.h"

namespace {

using namespace rill;
using namespace rill::bench;

// ---- the kernels, each written once for the DSL and for the host reference ------------------

// The math-heavy chain. R is rill::Float in the kernel and double in the reference: the
// same expression, so the reference is exactly the kernel's formula. Every term is positive,
// so the sum does not cancel and its error is the functions' error, not cancellation's.
template <class R>
R math_chain(const R& x) {
  using std::atan;
  using std::atan2;
  using std::cos;
  using std::exp;
  using std::exp2;
  using std::log;
  using std::log2;
  using std::pow;
  using std::sin;
  using std::sqrt;
  using std::tan;
  R sum = tan(0.3f * x);  // 0.3 x in [0.03, 1.2]: away from the pole
  for (int k = 0; k < 4; ++k) {
    const float s = 1.0f + 0.25f * static_cast<float>(k);
    const R t = x * s;
    sum = sum + exp(-0.5f * t) * (1.5f + sin(3.0f * t)) + log(1.0f + t * t) * (1.2f + cos(t)) +
          pow(t, 1.5f) / (1.0f + t) + sqrt(t) * atan2(t, 2.0f) + atan(t) * exp2(-0.25f * t) +
          log2(2.0f + t);
  }
  return sum;
}

// The branchy iteration, host reference in double (the kernel is below, in branchy_program).
// v shrinks at every step, so it ends after a few dozen steps; the cap is a safety net. The
// integer result is the path's signature: steps + 2^7 (times the fract branch was taken) +
// 2^14 (inner loop iterations) + 2^24 (times the first branch was taken); each fits its
// field (at most 100, 100, 500 and 100), so an element that took another path (a branch or
// a loop condition decided the other way) shows as a different signature.
constexpr int32_t kBranchyMaxSteps = 100;
void branchy_reference(double x, double& acc_out, int32_t& path_out) {
  double v = x, acc = 0;
  int32_t steps = 0, path = 0;
  while (v > 1.5f && steps < kBranchyMaxSteps) {
    if (v > 50.0f) {
      v = std::sqrt(v) * 1.1f;
      acc += 1.0f;
      path += 1 << 24;
    } else if (v - std::floor(v) < 0.5f) {
      v = v * 0.75f;
      acc += std::log(v);
      path += 1 << 7;
    } else {
      double m = v;
      while (m > 2.0f) {
        m = m * 0.5f;
        acc += 0.1f * m;
        path += 1 << 14;
      }
      v = v * 0.9f - 0.2f;
    }
    steps += 1;
  }
  acc_out = acc;
  path_out = path + steps;
}

Program branchy_program() {
  return program("branchy", [] {
    Input<Float> x("x");
    Output<Float> acc_out("acc");
    Output<Int> path_out("path");
    Float v = x, acc = 0.0f;
    Int steps = 0, path = 0;
    RILL_WHILE(v > 1.5f && steps < kBranchyMaxSteps) {
      RILL_IF(v > 50.0f) {
        v = sqrt(v) * 1.1f;
        acc += 1.0f;
        path += 1 << 24;
      }
      RILL_ELSE_IF(fract(v) < 0.5f) {
        v = v * 0.75f;
        acc += log(v);
        path += 1 << 7;
      }
      RILL_ELSE {
        Float m = v;
        RILL_WHILE(m > 2.0f) {
          m = m * 0.5f;
          acc += 0.1f * m;
          path += 1 << 14;
        }
        RILL_ENDWHILE;
        v = v * 0.9f - 0.2f;
      }
      RILL_ENDIF;
      steps += 1;
    }
    RILL_ENDWHILE;
    acc_out = acc;
    path_out = path + steps;
  });
}

Program math_program() {
  return program("math_chain", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = math_chain(Float(x));
  });
}

// Inputs spread over [lo, hi] in a scrambled order (golden-ratio sequence), so neighbouring
// elements (one SIMD lane or GPU warp) take different paths in the branchy kernel.
std::vector<float> spread_inputs(int64_t n, double lo, double hi) {
  std::vector<float> x(static_cast<size_t>(n));
  const double golden = 0.6180339887498949;
  for (int64_t i = 0; i < n; ++i) {
    const double u = std::fmod(static_cast<double>(i) * golden, 1.0);
    x[static_cast<size_t>(i)] = static_cast<float>(lo + (hi - lo) * u);
  }
  return x;
}

// ---- one kernel of the benchmark: program, inputs, outputs and reference ---------------------

// The outputs one compiled variant writes (a float result, an integer result, or both).
struct Outputs {
  std::optional<Stream<Float>> f;
  std::optional<Stream<Int>> i;
};

struct BenchKernel {
  std::string name;
  std::function<Program()> build;
  std::optional<Stream<Float>> input;
  bool float_output = false, int_output = false;
  int64_t width = 0, height = 1;  // output stream shape
  std::vector<double> ref_f;      // double reference of the float output
  std::vector<int32_t> ref_i;     // reference of the integer output

  Outputs bind(Kernel& k) const {
    Outputs o;
    if (input) k.inputs(*input);
    if (float_output) o.f.emplace(width, height);
    if (int_output) o.i.emplace(width, height);
    if (o.f && o.i)
      k.outputs(*o.f, *o.i);
    else if (o.f)
      k.outputs(*o.f);
    else
      k.outputs(*o.i);
    return o;
  }
};

BenchKernel math_kernel(int64_t n) {
  BenchKernel b;
  b.name = "math";
  b.build = math_program;
  std::vector<float> x = spread_inputs(n, 0.1, 4.0);
  b.input.emplace(x);
  b.float_output = true;
  b.width = n;
  b.ref_f.resize(x.size());
  for (size_t e = 0; e < x.size(); ++e) b.ref_f[e] = math_chain(static_cast<double>(x[e]));
  return b;
}

BenchKernel branchy_kernel(int64_t n) {
  BenchKernel b;
  b.name = "branchy";
  b.build = branchy_program;
  std::vector<float> x = spread_inputs(n, 2.0, 10000.0);
  b.input.emplace(x);
  b.float_output = b.int_output = true;
  b.width = n;
  b.ref_f.resize(x.size());
  b.ref_i.resize(x.size());
  for (size_t e = 0; e < x.size(); ++e)
    branchy_reference(static_cast<double>(x[e]), b.ref_f[e], b.ref_i[e]);
  return b;
}

// The Mandelbrot uniforms live as long as the kernel definition that reads them.
struct MandelbrotUniforms {
  Uniform<Float> x0, y0, step;
  Uniform<Int> max_iter;
  explicit MandelbrotUniforms(const MandelbrotView& v)
      : x0(v.x0, "x0"), y0(v.y0, "y0"), step(v.step, "step"), max_iter(v.iterations, "max_iter") {}
};

BenchKernel mandelbrot_kernel(const MandelbrotView& view,
                              std::shared_ptr<MandelbrotUniforms>& uniforms) {
  uniforms = std::make_shared<MandelbrotUniforms>(view);
  MandelbrotUniforms* u = uniforms.get();
  BenchKernel b;
  b.name = "mandelbrot";
  b.build = [u] { return mandelbrot_program(u->x0, u->y0, u->step, u->max_iter); };
  b.int_output = true;
  b.width = view.width;
  b.height = view.height;
  b.ref_i.resize(static_cast<size_t>(view.width * view.height));
  for (int64_t e = 0; e < view.width * view.height; ++e) {
    const double cx =
        pixel_centre<double>(view.x0, static_cast<int32_t>(e % view.width), view.step);
    const double cy =
        pixel_centre<double>(view.y0, static_cast<int32_t>(e / view.width), view.step);
    b.ref_i[static_cast<size_t>(e)] = escape_iterations(cx, cy, view.iterations);
  }
  return b;
}

// ---- error measures ----------------------------------------------------------------------------

// The spacing of binary32 numbers in the binade of |r| (2^-149 below FLT_MIN).
double float_ulp(double r) {
  const double a = std::fabs(r);
  if (a < 0x1p-126) return 0x1p-149;
  int e = 0;
  std::frexp(a, &e);  // a = m 2^e, m in [0.5, 1)
  return std::ldexp(1.0, e - 24);
}

struct ErrorStats {
  double max_ulp = -1;  // -1: no float output
  double rms_rel = -1;
  int64_t differing = -1;  // -1: no integer output
};

// Where the kernel also has an integer result (the branchy path signature), the float error is
// taken over the elements whose integer result matches the reference: those that took the
// reference's path. An element that took another path (one branch decided the other way)
// has an error of another kind, counted in `differing` instead of swamping the float figures.
ErrorStats measure(const BenchKernel& b, const Outputs& o) {
  ErrorStats s;
  std::vector<int32_t> got_i;
  if (o.i) {
    got_i = o.i->download();
    s.differing = 0;
    for (size_t e = 0; e < got_i.size(); ++e) s.differing += got_i[e] != b.ref_i[e];
  }
  if (o.f) {
    const std::vector<float> got = o.f->download();
    double max_ulp = 0, sum_sq = 0;
    int64_t counted = 0;
    for (size_t e = 0; e < got.size(); ++e) {
      if (!got_i.empty() && got_i[e] != b.ref_i[e]) continue;
      const double g = static_cast<double>(got[e]), r = b.ref_f[e];
      const double d = std::isfinite(g) ? std::fabs(g - r) : INFINITY;
      max_ulp = std::max(max_ulp, d / float_ulp(r));
      const double rel = r != 0 ? d / std::fabs(r) : d;
      sum_sq += rel * rel;
      ++counted;
    }
    s.max_ulp = max_ulp;
    s.rms_rel = counted ? std::sqrt(sum_sq / static_cast<double>(counted)) : 0;
  }
  return s;
}

// ---- running and reporting ---------------------------------------------------------------------

struct Row {
  std::string kernel, backend, mode;
  std::string unavailable;  // why this variant did not run (empty: it ran)
  double median_ms = 0, ratio = 0;
  ErrorStats error;
  int64_t elements = 0;
};

struct Variant {
  Row row;
  Kernel kernel;
  Outputs outputs;
  std::vector<double> times;
};

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string ulp_text(double u) {
  if (u < 0) return "-";
  if (std::isinf(u)) return "inf";
  return u < 1e6 ? fmt("%.2f", u) : fmt("%.3g", u);
}

std::vector<Row> run_kernel(const BenchKernel& b, const std::vector<std::string>& backend_names,
                            int repeats) {
  std::vector<Variant> variants;
  for (const std::string& name : backend_names) {
    Backend& be = backend(name);
    const std::string why_not_here = be.unavailable_reason();
    for (Accuracy a : {Accuracy::Strict, Accuracy::Fast, Accuracy::Double}) {
      Variant v;
      v.row.kernel = b.name;
      v.row.backend = name;
      v.row.mode = accuracy_name(a);
      v.row.elements = b.width * b.height;
      if (!why_not_here.empty()) {
        v.row.unavailable = "backend not available here: " + why_not_here;
      } else if (!be.supports(a)) {
        v.row.unavailable = name.rfind("glsl", 0) == 0 ? "GLSL kernels compute in binary32 (no double mode)"
                                           : "the device has no double precision";
      } else {
        CompileOptions opt;
        opt.accuracy = a;
        v.kernel = compile(b.build(), name, opt);
        v.outputs = b.bind(v.kernel);
        v.kernel.execute();  // warm-up: uploads, first-launch costs
      }
      variants.push_back(std::move(v));
    }
  }
  for (int r = 0; r < repeats; ++r)
    for (Variant& v : variants) {
      if (!v.row.unavailable.empty()) continue;
      const auto t = Clock::now();
      v.kernel.execute();
      v.times.push_back(ms_since(t));
    }
  std::vector<Row> rows;
  for (Variant& v : variants) {
    if (v.row.unavailable.empty()) {
      v.row.median_ms = median(v.times);
      v.row.error = measure(b, v.outputs);
    }
    rows.push_back(v.row);
  }
  for (Row& r : rows)  // strict runs on every backend that runs at all
    for (const Row& s : rows)
      if (s.backend == r.backend && s.mode == "strict" && s.median_ms > 0)
        r.ratio = r.median_ms / s.median_ms;
  return rows;
}

std::string markdown(const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "| kernel | backend | mode | median ms | vs strict | max ulp | RMS rel. error | "
       "differing elements |\n"
    << "| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |\n";
  for (const Row& r : rows) {
    s << "| " << r.kernel << " | " << r.backend << " | " << r.mode << " | ";
    if (!r.unavailable.empty()) {
      s << "n/a | n/a | n/a | n/a | n/a: " << r.unavailable << " |\n";
      continue;
    }
    s << fmt("%.2f", r.median_ms) << " | " << fmt("%.2fx", r.ratio) << " | "
      << ulp_text(r.error.max_ulp) << " | "
      << (r.error.rms_rel < 0 ? "-" : fmt("%.2e", r.error.rms_rel)) << " | "
      << (r.error.differing < 0
              ? std::string("-")
              : std::to_string(r.error.differing) + " of " + std::to_string(r.elements))
      << " |\n";
  }
  return s.str();
}

std::string csv(const std::vector<Row>& rows) {
  std::ostringstream s;
  s << "kernel,backend,mode,median_ms,ratio_to_strict,max_ulp,rms_rel_error,differing,elements,"
       "note\n";
  for (const Row& r : rows) {
    s << r.kernel << "," << r.backend << "," << r.mode << ",";
    if (!r.unavailable.empty()) {
      s << "n/a,n/a,n/a,n/a,n/a," << r.elements << ",\"" << r.unavailable << "\"\n";
      continue;
    }
    s << fmt("%.4f", r.median_ms) << "," << fmt("%.4f", r.ratio) << ","
      << (r.error.max_ulp < 0 ? "n/a" : fmt("%.6g", r.error.max_ulp)) << ","
      << (r.error.rms_rel < 0 ? "n/a" : fmt("%.6g", r.error.rms_rel)) << ","
      << (r.error.differing < 0 ? "n/a" : std::to_string(r.error.differing)) << "," << r.elements
      << ",\n";
  }
  return s.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  if (!f) throw Error("cannot write " + path);
  f << text;
  if (!f) throw Error("error writing " + path);
}

}  // namespace

int main(int argc, char** argv) try {
  std::string size = "512x512", backend_list = "all", kernel_list = "math,branchy,mandelbrot";
  std::string csv_path, md_path;
  int repeats = 5, iterations = 256;
  CLI::App app{"rill-bench-accuracy: time and error of each accuracy mode, per backend"};
  app.add_option("--size", size,
                 "elements as WxH (the Mandelbrot image; W*H elements for the "
                 "1-D kernels)")
      ->capture_default_str();
  app.add_option("--iterations", iterations, "Mandelbrot iteration limit")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.add_option("--repeats", repeats, "timed runs of each variant (interleaved)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  app.add_option("--backends", backend_list, "all, or a list of cpu,opencl,glsl")
      ->capture_default_str();
  app.add_option("--kernels", kernel_list, "a list of math,branchy,mandelbrot")
      ->capture_default_str();
  app.add_option("--csv", csv_path, "also write the table as CSV");
  app.add_option("--md", md_path, "also write the table as Markdown");
  CLI11_PARSE(app, argc, argv);

  long long w = 0, h = 0;
  char rest = 0;
  if (std::sscanf(size.c_str(), "%lldx%lld%c", &w, &h, &rest) != 2 || w < 1 || h < 1 ||
      w * h > (1ll << 28))
    throw Error("--size expects WxH with at most 2^28 elements, got '" + size + "'");

  std::vector<std::string> backend_names;
  if (backend_list == "all") {
    for (Backend* b : backends()) backend_names.push_back(b->name());
  } else {
    backend_names = split_list(backend_list);
    for (const std::string& n : backend_names) backend(n);  // throws naming an unknown backend
  }
  std::vector<std::string> kernel_names = split_list(kernel_list);
  for (const std::string& k : kernel_names)
    if (k != "math" && k != "branchy" && k != "mandelbrot")
      throw Error("unknown kernel '" + k + "' (kernels: math, branchy, mandelbrot)");
  if (kernel_names.empty()) throw Error("--kernels names no kernel");

  MandelbrotView view;
  view.width = w;
  view.height = h;
  view.iterations = iterations;
  view.frame();
  std::shared_ptr<MandelbrotUniforms> uniforms;

  std::printf("Accuracy cost: %lld elements (%lldx%lld), %d repeats (medians), %d CPU threads\n",
              w * h, w, h, repeats, tbb::info::default_concurrency());
  for (const std::string& n : backend_names) {
    Backend& be = backend(n);
    std::printf("  %-7s %s\n", n.c_str(),
                be.unavailable_reason().empty() ? be.description().c_str()
                                                : be.unavailable_reason().c_str());
  }
  std::vector<Row> rows;
  for (const std::string& k : kernel_names) {
    BenchKernel b = k == "math"      ? math_kernel(w * h)
                    : k == "branchy" ? branchy_kernel(w * h)
                                     : mandelbrot_kernel(view, uniforms);
    std::vector<Row> r = run_kernel(b, backend_names, repeats);
    rows.insert(rows.end(), r.begin(), r.end());
  }
  clear_kernel_cache();  // GL objects go while the context exists

  const std::string table = markdown(rows);
  std::printf("\n%s", table.c_str());
  if (!md_path.empty()) write_file(md_path, table);
  if (!csv_path.empty()) write_file(csv_path, csv(rows));

  // Sanity: double mode must match its own reference (the integer results exactly).
  bool ok = true;
  for (const Row& r : rows)
    if (r.unavailable.empty() && r.mode == "double" && r.error.differing > 0) {
      std::fprintf(stderr,
                   "rill-bench-accuracy: %s on %s in double mode differs from the double "
                   "reference in %lld elements\n",
                   r.kernel.c_str(), r.backend.c_str(), (long long)r.error.differing);
      ok = false;
    }
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-bench-accuracy: %s\n", e.what());
  return 1;
}
