// Mandelbrot, Rill's CPU backend against the same algorithm written by hand in C++.
//
//   rill-bench-mandelbrot [--size WxH] [--iterations N] [--repeats R] [--backends all|cpu,...]
//
// Both versions compute the escape-time iteration count of every pixel of a 1920x1080 view
// with the same float arithmetic in the same order and the same escape test, and both run
// on oneTBB in the same way: tbb::parallel_reduce over blocked_range<int64_t> of grain 1024,
// summing the number of elements written (what the CPU backend does around the generated
// code). The two are run R times each, interleaved, and the medians are compared; the
// iteration counts must be identical. It also measures how long compiling the kernel takes:
// the first compile (empty disk cache, a fresh temporary RILL_CACHE_DIR), a compile served
// from the disk cache (after clear_kernel_cache(), as a new process would see it) and an
// in-process cache hit.
//
// The other backends of this build that can run here (OpenCL, GLSL) then run the same
// kernel in strict mode, for information: their times (results stay on the device, so a
// launch includes no download) and whether their iteration counts are identical too.
// --backends cpu skips them.
#include <rill/rill.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_reduce.h>

#include <stdlib.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "MandelbrotKernel.h"
#include "Timing.h"

namespace {

using namespace rill;
using namespace rill::bench;
using View = MandelbrotView;

// The hand-written version. Statement for statement what the kernel compiles to.
int64_t mandelbrot_by_hand(const View& v, int32_t* out) {
  const int64_t count = v.width * v.height;
  return tbb::parallel_reduce(
      tbb::blocked_range<int64_t>(0, count, 1024), int64_t{0},
      [&](const tbb::blocked_range<int64_t>& r, int64_t written) {
        for (int64_t e = r.begin(); e < r.end(); ++e) {
          const float cx = pixel_centre<float>(v.x0, static_cast<int32_t>(e % v.width), v.step);
          const float cy = pixel_centre<float>(v.y0, static_cast<int32_t>(e / v.width), v.step);
          out[e] = escape_iterations(cx, cy, v.iterations);
          ++written;
        }
        return written;
      },
      [](int64_t a, int64_t b) { return a + b; });
}

}  // namespace

int main(int argc, char** argv) try {
  View view;
  int repeats = 7;
  std::string backend_list = "all";
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i], val = argv[i + 1];
    if (a == "--size") {
      long long w = 0, h = 0;
      if (std::sscanf(val.c_str(), "%lldx%lld", &w, &h) != 2 || w < 1 || h < 1)
        throw Error("--size expects WxH");
      view.width = w;
      view.height = h;
    } else if (a == "--iterations") {
      view.iterations = std::atoi(val.c_str());
    } else if (a == "--repeats") {
      repeats = std::max(1, std::atoi(val.c_str()));
    } else if (a == "--backends") {
      backend_list = "," + val + ",";
    } else {
      throw Error("unknown option " + a +
                  " (options: --size WxH, --iterations N, --repeats R, --backends all|cpu,...)");
    }
  }
  view.frame();

  // A fresh, empty disk cache, so the first compile really compiles.
  std::string dir_template =
      (std::filesystem::temp_directory_path() / "rill-bench-cache-XXXXXX").string();
  if (!mkdtemp(dir_template.data())) throw Error("cannot create a directory " + dir_template);
  const std::string cache_dir = dir_template;
  setenv("RILL_CACHE_DIR", cache_dir.c_str(), 1);

  Uniform<Float> x0(view.x0, "x0"), y0(view.y0, "y0"), step(view.step, "step");
  Uniform<Int> max_iter(view.iterations, "max_iter");
  auto define = [&] { return mandelbrot_program(x0, y0, step, max_iter); };

  // Compile latency: first compile, disk-cache hit, in-process hit.
  auto t = Clock::now();
  Kernel kernel = compile(define(), "cpu");
  const double first_ms = ms_since(t);
  const bool first_from_disk = kernel.info().from_disk_cache;
  clear_kernel_cache();
  t = Clock::now();
  kernel = compile(define(), "cpu");
  const double disk_ms = ms_since(t);
  const bool disk_from_disk = kernel.info().from_disk_cache;
  t = Clock::now();
  kernel = compile(define(), "cpu");
  const double hit_ms = ms_since(t);
  const bool hit = kernel.info().cache_hit;
  std::filesystem::remove_all(cache_dir);

  const int64_t n = view.width * view.height;
  Stream<Int> rill_out(view.width, view.height);
  kernel.outputs(rill_out);
  std::vector<int32_t> hand_out(static_cast<size_t>(n));

  // Warm up both (thread pool, page faults), then interleave the timed runs.
  kernel.execute();
  mandelbrot_by_hand(view, hand_out.data());
  std::vector<double> rill_ms, hand_ms;
  int64_t written_rill = 0, written_hand = 0;
  for (int r = 0; r < repeats; ++r) {
    t = Clock::now();
    written_rill = kernel.execute();
    rill_ms.push_back(ms_since(t));
    t = Clock::now();
    written_hand = mandelbrot_by_hand(view, hand_out.data());
    hand_ms.push_back(ms_since(t));
  }

  std::vector<int32_t> rill_iters = rill_out.download();
  int64_t mismatches = 0, total_iters = 0;
  for (int64_t e = 0; e < n; ++e) {
    mismatches += rill_iters[static_cast<size_t>(e)] != hand_out[static_cast<size_t>(e)];
    total_iters += hand_out[static_cast<size_t>(e)];
  }

  const double rill_med = median(rill_ms), hand_med = median(hand_ms);
  const double mpix = static_cast<double>(n) * 1e-6;
  std::printf(
      "Mandelbrot %lldx%lld, %d iterations, %lld inner iterations in all, %d threads, "
      "%d repeats (medians)\n",
      (long long)view.width, (long long)view.height, view.iterations, (long long)total_iters,
      tbb::info::default_concurrency(), repeats);
  std::printf("  %-26s %10s %12s %14s\n", "", "ms", "Mpixel/s", "Giter/s");
  std::printf("  %-26s %10.2f %12.2f %14.3f\n", "rill cpu (strict)", rill_med,
              mpix / (rill_med * 1e-3),
              static_cast<double>(total_iters) * 1e-9 / (rill_med * 1e-3));
  std::printf("  %-26s %10.2f %12.2f %14.3f\n", "hand-written C++ + TBB", hand_med,
              mpix / (hand_med * 1e-3),
              static_cast<double>(total_iters) * 1e-9 / (hand_med * 1e-3));
  const double ratio = hand_med / rill_med;
  std::printf("  rill / hand-written throughput: %.3fx (goal >= 0.9x)\n", ratio);
  std::printf("  identical iteration counts: %s (%lld of %lld pixels differ)\n",
              mismatches == 0 ? "yes" : "NO", (long long)mismatches, (long long)n);
  std::printf("Kernel compile latency\n");
  std::printf("  first compile (empty disk cache)        %8.1f ms%s\n", first_ms,
              first_from_disk ? "  (unexpected: served from disk)" : "");
  std::printf("  after clear_kernel_cache() (disk hit)   %8.1f ms%s\n", disk_ms,
              disk_from_disk ? "" : "  (unexpected: compiled again)");
  std::printf("  in-process cache hit                    %8.3f ms%s\n", hit_ms,
              hit ? "" : "  (unexpected: not a cache hit)");

  bool others_ok = true;
  bool header = false;
  for (Backend* b : backends()) {
    const std::string name = b->name();
    if (name == "cpu") continue;
    if (backend_list != "all" && backend_list.find("," + name + ",") == std::string::npos) continue;
    if (!header) {
      std::printf("Other backends, same kernel (strict), %d repeats (medians)\n", repeats);
      std::printf("  %-10s %12s %10s %12s  %s\n", "backend", "compile ms", "run ms", "Mpixel/s",
                  "iteration counts");
      header = true;
    }
    if (std::string why = b->unavailable_reason(); !why.empty()) {
      std::printf("  %-10s not available here: %s\n", name.c_str(), why.c_str());
      continue;
    }
    t = Clock::now();
    Kernel other = compile(define(), name);
    const double compile_ms = ms_since(t);
    Stream<Int> out(view.width, view.height);
    other.outputs(out);
    other.execute();  // warm-up
    std::vector<double> times;
    for (int r = 0; r < repeats; ++r) {
      t = Clock::now();
      other.execute();
      times.push_back(ms_since(t));
    }
    std::vector<int32_t> iters = out.download();
    int64_t differ = 0;
    for (int64_t e = 0; e < n; ++e)
      differ += iters[static_cast<size_t>(e)] != hand_out[static_cast<size_t>(e)];
    others_ok = others_ok && differ == 0;
    const double med = median(times);
    std::printf("  %-10s %12.1f %10.2f %12.2f  %s (%lld differ)\n", name.c_str(), compile_ms, med,
                mpix / (med * 1e-3), differ == 0 ? "identical" : "DIFFERENT", (long long)differ);
  }

  const bool ok = mismatches == 0 && written_rill == n && written_hand == n && !first_from_disk &&
                  disk_from_disk && hit && others_ok;
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-bench-mandelbrot: %s\n", e.what());
  return 1;
}
