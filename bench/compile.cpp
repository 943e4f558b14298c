// rill-bench-compile: what a kernel costs before and around its work (issue 17): launch
// overhead, the cost of a loop() pass, and cold and warm compiles as a new process.
//
//   rill-bench-compile [--sections launch,compile] [--backends all|cpu,simd,opencl,glsl,glsl-compute]
//                      [--launches N] [--passes N] [--reps R]
//                      [--kernels mandelbrot,raytracer,ifs400] [--scene builtin:thesis-a]
//
// Sections (a table each; every figure is a median):
//   launch   per backend, with the data resident where the backend keeps it:
//            - execute() of a near-empty kernel (y = x + 1) over 1024 and over 1 element,
//              median of N (2000) launches;
//            - its kernel time, from the slope: (launch of 2^18 elements - launch of 1024)
//              per element, times 1024; the overhead is the 1024-element launch minus that;
//            - one loop() pass: a counter kernel over 1024 elements that adds 1 until it
//              reaches P (362, the pass count a user measured) and then discards, so loop()
//              runs P + 1 passes; per pass, and per pass minus the kernel time.
//            Targets (issue 17): launch overhead <= 50 us on cpu, simd and opencl, <= 150 us
//            on glsl; a pass <= 100 us plus the kernel time.
//   compile  per kernel and backend, a child process (this program run again with a hidden
//            flag) that compiles the kernel and launches it once, first with empty caches
//            (cold: Rill's, PoCL's and Mesa's cache directories point into a fresh temporary
//            directory) and then again with those caches as the cold run left them (warm).
//            Kernels: the Mandelbrot kernel (MandelbrotKernel.h), the ray tracer's megakernel
//            for a small built-in scene, and a generated kernel of 400 RILL_IFs. Reported: the
//            child's wall time (process start to exit: what a user waits for on first use),
//            Kernel::info() (compile_ms, its stages, and where the kernel came from), and the
//            first launch after compile(). Medians of R children each.
// A backend that cannot run here is listed as skipped with its reason.
#include <rill/rill.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "CommaList.h"
#include "rill/rt/accel/Grid.h"
#include "MandelbrotKernel.h"
#include "rill/rt/scene/Scene.h"
#include "Timing.h"
#include "rill/rt/Tracer.h"
#include "UsableBackends.h"

namespace {

using namespace rill;
using namespace rill::bench;

struct Options {
  std::vector<std::string> sections{"launch", "compile"};
  std::vector<std::string> backends{"cpu", "simd", "opencl", "glsl"};
  std::vector<std::string> kernels{"mandelbrot", "raytracer", "ifs400"};
  std::string scene = "builtin:thesis-a";
  int launches = 2000;
  int passes = 362;
  int reps = 1;
};

double us_since(Clock::time_point t) {
  return 1000.0 * ms_since(t);
}

// ---- launch ---------------------------------------------------------------------------------

Program near_empty() {
  return program("near_empty", [] {
    Input<Float> x("x");
    Output<Float> y("y");
    y = x + 1.0f;
  });
}

// Adds 1 until the element reaches `limit`, then discards: loop() runs limit + 1 passes.
Program counter(const Uniform<Int>& limit) {
  return program("counter", [&] {
    Input<Int> c("c");
    Output<Int> next("c");
    RILL_IF(c >= limit) {
      RILL_DISCARD;
    }
    RILL_ENDIF;
    next = c + 1;
  });
}

// Median microseconds of one execute() of k, bound to streams that stay on the backend: only
// the first, untimed, launch uploads.
double median_launch_us(Kernel& k, int launches) {
  k.execute();
  std::vector<double> us;
  us.reserve(static_cast<size_t>(launches));
  for (int i = 0; i < launches; ++i) {
    auto t = Clock::now();
    k.execute();
    us.push_back(us_since(t));
  }
  return median(us);
}

double near_empty_us(const std::string& be, int64_t n, int launches) {
  Stream<Float> x(n, "x"), y(n, "y");
  x.fill(0.5f);
  Kernel k = compile(near_empty(), be);
  k.bind("x", x).bind("y", y);
  return median_launch_us(k, launches);
}

// One launch of the counter over n elements that all write (the limit is out of reach).
double counter_us(const std::string& be, int64_t n, int launches) {
  Uniform<Int> limit(std::numeric_limits<int32_t>::max(), "limit");
  Stream<Int> c(n, "c");
  Kernel k = compile(counter(limit), be);
  k.bind("c", c);
  return median_launch_us(k, launches);
}

// The work of 1024 elements, from the slope between launches of 1024 and `big` elements.
double kernel_us_of_1024(double at_1024, double at_big, int64_t big) {
  return std::max(0.0, (at_big - at_1024) / static_cast<double>(big - 1024) * 1024);
}

bool run_launch(const Options& o) {
  std::printf(
      "\nlaunch: y = x + 1 over 1 and 1024 Float elements, median of %d launches; "
      "loop() of a counter over 1024 Int elements, %d + 1 passes, median of 3 (us)\n",
      o.launches, o.passes);
  std::vector<std::string> names = usable_backends(o.backends);
  std::printf("  %-8s %8s %8s %8s %8s | %8s %8s %8s %8s %8s  %s\n", "backend", "1 elem", "1024",
              "kernel", "overhead", "launch", "kernel", "pass", "pass-kern", "loop ms", "target");
  bool ok = true;
  const int64_t big = int64_t{1} << 18;
  const int big_launches = std::max(5, o.launches / 100);
  for (const auto& be : names) {
    const double one = near_empty_us(be, 1, o.launches);
    const double small = near_empty_us(be, 1024, o.launches);
    const double kernel = kernel_us_of_1024(small, near_empty_us(be, big, big_launches), big);
    const double c_small = counter_us(be, 1024, o.launches);
    const double c_kernel = kernel_us_of_1024(c_small, counter_us(be, big, big_launches), big);

    Uniform<Int> limit(o.passes, "limit");
    Kernel k = compile(counter(limit), be);
    Stream<Int> c(1024, "c");
    k.bind("c", c);
    std::vector<double> loop_ms;
    int64_t passes = 0;
    for (int r = 0; r < 3; ++r) {
      c.fill(0);
      k.execute();  // uploads; the first pass of the loop then finds the data in place
      c.fill(0);
      auto t = Clock::now();
      passes = k.loop();
      loop_ms.push_back(ms_since(t));
    }
    const std::vector<int32_t> final_values = c.download();
    bool counted = passes == o.passes + 1;
    for (int32_t v : final_values) counted = counted && v == o.passes;
    ok = ok && counted;
    const double pass = 1000.0 * median(loop_ms) / static_cast<double>(passes);
    const double overhead = small - kernel;
    const double target = be == "glsl" ? 150 : 50;
    const bool met = overhead <= target && pass - c_kernel <= 100;
    std::printf("  %-8s %8.1f %8.1f %8.1f %8.1f | %8.1f %8.1f %8.1f %8.1f %8.2f  %s%s\n",
                be.c_str(), one, small, kernel, overhead, c_small, c_kernel, pass, pass - c_kernel,
                median(loop_ms), met ? "met" : "MISSED", counted ? "" : "  WRONG COUNT");
  }
  std::printf(
      "  left: y = x + 1; right: the counter (launch: one execute() of 1024 elements "
      "that all write; pass: loop() time / passes)\n"
      "  kernel = (launch of 2^18 - launch of 1024) / (2^18 - 1024) * 1024: the work "
      "of 1024 elements\n"
      "  targets: overhead = 1024 - kernel <= 50 us (glsl 150 us); pass - kernel <= "
      "100 us\n");
  return ok;
}

// ---- compile (the child) --------------------------------------------------------------------

Program ifs_program(int n) {
  return program("ifs" + std::to_string(n), [n] {
    Input<Float> x("x");
    Output<Float> y("y");
    Float v = x;
    for (int i = 0; i < n; ++i) {
      const float c = static_cast<float>(i % 17) * 0.125f;
      RILL_IF(v > c) {
        v = v * 0.5f + static_cast<float>(i % 5) * 0.25f;
      }
      RILL_ENDIF;
      v = v + 0.0625f;
    }
    y = v;
  });
}

// Compiles one kernel on one backend and launches it once; prints one line the parent parses.
int child(const std::string& kernel, const std::string& be, const std::string& scene_spec) {
  Kernel k;
  double first_ms = 0;
  auto timed_compile = [&](const Program& p) { k = compile(p, be); };
  if (kernel == "mandelbrot") {
    MandelbrotView view;
    view.width = 64;
    view.height = 64;
    view.iterations = 64;
    view.frame();
    Uniform<Float> x0(view.x0, "x0"), y0(view.y0, "y0"), step(view.step, "step");
    Uniform<Int> iters(view.iterations, "max_iter");
    timed_compile(mandelbrot_program(x0, y0, step, iters));
    Stream<Int> out(view.width, view.height, "iters");
    k.bind("iters", out);
    auto t = Clock::now();
    k.execute();
    (void)out.download();
    first_ms = ms_since(t);
  } else if (kernel == "raytracer") {
    rt::Scene scene = rt::load_scene(scene_spec);
    scene.width = scene.height = 64;
    scene.options.spp = 1;
    scene.validate();
    rt::Grid grid = rt::build_grid_for(scene);
    rt::Tracer tracer(scene, grid);
    // The same kernel render() compiles, a cache hit there: the backend's loop.
    timed_compile(tracer.program(rt::megakernel_loop_for(rt::MegakernelLoop::Auto, be)));
    rt::RenderSettings s;
    s.backend = be;
    s.width = scene.width;
    s.height = scene.height;
    auto t = Clock::now();
    tracer.render(s, scene.camera);
    first_ms = ms_since(t);
  } else if (kernel.rfind("ifs", 0) == 0) {
    timed_compile(ifs_program(std::atoi(kernel.c_str() + 3)));
    Stream<Float> x(1024, "x"), y(1024, "y");
    x.fill(0.5f);
    k.bind("x", x).bind("y", y);
    auto t = Clock::now();
    k.execute();
    (void)y.download();
    first_ms = ms_since(t);
  } else {
    std::fprintf(stderr, "rill-bench-compile: unknown kernel '%s'\n", kernel.c_str());
    return 2;
  }
  const CompileInfo& i = k.info();
  std::printf("RESULT %.3f %.3f %.3f %.3f %.3f %.3f %.3f %d\n", i.compile_ms, i.capture_ms,
              i.optimize_ms, i.codegen_ms, i.backend_compile_ms, i.driver_finish_ms, first_ms,
              static_cast<int>(i.origin));
  return 0;
}

// ---- compile (the parent) -------------------------------------------------------------------

struct ChildResult {
  bool ok = false;
  double wall_ms = 0;
  double compile_ms = 0, capture_ms = 0, optimize_ms = 0, codegen_ms = 0, backend_ms = 0,
         finish_ms = 0, first_ms = 0;
  int origin = 0;
  std::string error;
};

std::string self_path() {
  std::error_code ec;
  auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("rill-bench-compile: cannot read /proc/self/exe: " + ec.message());
  return p.string();
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs the child with every cache this process could use (Rill's, PoCL's, Mesa's) under dir.
ChildResult run_child(const std::string& exe, const std::string& kernel, const std::string& be,
                      const std::string& scene, const std::filesystem::path& dir) {
  const std::string d = dir.string();
  std::string cmd =
      "RILL_CACHE_DIR=" + quoted(d + "/rill") + " XDG_CACHE_HOME=" + quoted(d + "/xdg") +
      " POCL_CACHE_DIR=" + quoted(d + "/pocl") + " MESA_SHADER_CACHE_DIR=" + quoted(d + "/mesa") +
      " " + quoted(exe) + " --child " + quoted(kernel) + " " + quoted(be) + " --scene " +
      quoted(scene) + " 2>&1";
  ChildResult r;
  auto t = Clock::now();
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    r.error = "popen failed";
    return r;
  }
  std::string out;
  char buf[4096];
  while (size_t n = std::fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  const int status = pclose(p);
  r.wall_ms = ms_since(t);
  const size_t at = out.find("RESULT ");
  if (status != 0 || at == std::string::npos) {
    r.error = out.empty() ? "exit status " + std::to_string(status) : out;
    return r;
  }
  r.ok = std::sscanf(out.c_str() + at, "RESULT %lf %lf %lf %lf %lf %lf %lf %d", &r.compile_ms,
                     &r.capture_ms, &r.optimize_ms, &r.codegen_ms, &r.backend_ms, &r.finish_ms,
                     &r.first_ms, &r.origin) == 8;
  if (!r.ok) r.error = "unreadable child output: " + out;
  return r;
}

// The median of each figure over several children (origin: the last child's).
ChildResult median_of(const std::vector<ChildResult>& rs) {
  ChildResult m = rs.back();
  auto med = [&](double ChildResult::*f) {
    std::vector<double> v;
    for (const auto& r : rs) v.push_back(r.*f);
    m.*f = median(v);
  };
  for (auto f : {&ChildResult::wall_ms, &ChildResult::compile_ms, &ChildResult::capture_ms,
                 &ChildResult::optimize_ms, &ChildResult::codegen_ms, &ChildResult::backend_ms,
                 &ChildResult::finish_ms, &ChildResult::first_ms})
    med(f);
  return m;
}

bool run_compile(const Options& o) {
  std::printf(
      "\ncompile: each a new process (compile + first launch), cold (empty Rill, PoCL "
      "and Mesa caches) then warm (as the cold run left them), median of %d (ms)\n",
      o.reps);
  std::vector<std::string> names = usable_backends(o.backends);
  const std::string exe = self_path();
  std::printf("  %-10s %-8s %-5s %9s %9s %9s %8s %8s %8s %8s %9s  %s\n", "kernel", "backend",
              "cache", "wall", "compile", "capture", "optimize", "codegen", "backend", "finish",
              "1st run", "origin");
  bool ok = true;
  for (const auto& kernel : o.kernels) {
    for (const auto& be : names) {
      // Per repeat, a fresh directory: the cold child fills it, the warm child reuses it.
      std::vector<ChildResult> cold, warm;
      for (int r = 0; r < o.reps; ++r) {
        char tmpl[] = "/tmp/rill-bench-compile-XXXXXX";
        if (!mkdtemp(tmpl)) throw Error("rill-bench-compile: mkdtemp failed");
        const std::filesystem::path dir = tmpl;
        cold.push_back(run_child(exe, kernel, be, o.scene, dir));
        const bool cold_ok = cold.back().ok;
        if (cold_ok) warm.push_back(run_child(exe, kernel, be, o.scene, dir));
        std::filesystem::remove_all(dir);
        if (!cold_ok || !warm.back().ok) break;
      }
      for (const auto* rs : {&cold, &warm}) {
        const char* mode = rs == &cold ? "cold" : "warm";
        if (rs->empty() || !rs->back().ok || rs->size() < cold.size()) {
          ok = false;
          std::printf("  %-10s %-8s %-5s FAILED: %s\n", kernel.c_str(), be.c_str(), mode,
                      rs->empty() ? "(the cold run failed)" : rs->back().error.c_str());
          continue;
        }
        const ChildResult m = median_of(*rs);
        std::printf("  %-10s %-8s %-5s %9.1f %9.1f %9.1f %8.1f %8.1f %8.1f %8.1f %9.1f  %s\n",
                    kernel.c_str(), be.c_str(), mode, m.wall_ms, m.compile_ms, m.capture_ms,
                    m.optimize_ms, m.codegen_ms, m.backend_ms, m.finish_ms, m.first_ms,
                    origin_name(static_cast<KernelOrigin>(m.origin)));
      }
      std::fflush(stdout);
    }
  }
  std::printf(
      "  wall: the child process from start to exit; compile: Kernel::info().compile_ms "
      "and its stages (0 where not yet measured); 1st run: the first launch after "
      "compile() (with a download)\n");
  return ok;
}

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr,
               "rill-bench-compile: %s\n"
               "options: --sections launch,compile  --backends all|cpu,simd,opencl,glsl,glsl-compute\n"
               "         --launches N  --passes N  --reps R  --kernels "
               "mandelbrot,raytracer,ifs400  --scene builtin:NAME\n",
               msg.c_str());
  std::exit(2);
}

int int_option(const std::string& name, const std::string& v) {
  char* end = nullptr;
  const long n = std::strtol(v.c_str(), &end, 10);
  if (v.empty() || *end || n < 1 || n > 1000000)
    usage_error(name + " expects a whole number from 1 to 1000000 (got '" + v + "')");
  return static_cast<int>(n);
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  std::string child_kernel, child_backend;
  for (int i = 1; i < argc; i += 2) {
    std::string a = argv[i];
    if (a == "--child") {  // hidden: run by the compile section
      if (i + 2 >= argc) usage_error("--child needs a kernel and a backend");
      child_kernel = argv[i + 1];
      child_backend = argv[i + 2];
      ++i;
      continue;
    }
    if (i + 1 >= argc) usage_error("option " + a + " needs a value");
    std::string val = argv[i + 1];
    if (a == "--sections") {
      o.sections = split_list(val);
    } else if (a == "--backends") {
      if (val != "all") o.backends = split_list(val);
    } else if (a == "--kernels") {
      o.kernels = split_list(val);
    } else if (a == "--scene") {
      o.scene = val;
    } else if (a == "--launches") {
      o.launches = int_option(a, val);
    } else if (a == "--passes") {
      o.passes = int_option(a, val);
    } else if (a == "--reps") {
      o.reps = int_option(a, val);
    } else {
      usage_error("unknown option " + a);
    }
  }
  if (!child_kernel.empty()) return child(child_kernel, child_backend, o.scene);
  bool ok = true;
  if (has(o.sections, "launch")) ok = run_launch(o) && ok;
  if (has(o.sections, "compile")) ok = run_compile(o) && ok;
  std::printf("\n%s\n", ok ? "all checks passed" : "SOME CHECKS FAILED");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-bench-compile: %s\n", e.what());
  return 1;
}
