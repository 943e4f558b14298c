// Composition on the device: kernels that read what an earlier launch wrote, reductions, and
// connected programs, each against the way it would be done without them.
//
//   rill-bench-compose [--sections blur,reduce,connect] [--backends all|cpu,simd,...]
//                      [--reps R] [--size WxH] [--reduce-n N] [--connect-n N]
//
// Three sections, each measured side by side (the variants compared are interleaved within
// every repeat; medians are reported):
//   blur     a WxH (1920x1080) two-pass separable 5-tap blur of Float4 pixels: the vertical pass
//            gathers from the stream the horizontal pass wrote (device chain), against the
//            vertical pass gathering from an Array uploaded from tmp.download() (host round
//            trip). Both must give identical bits, and every backend the cpu's bits.
//   reduce   the sum of N (2^24) floats: rill::sum on cpu and simd against a hand-written
//            oneTBB parallel_reduce (a sequential float sum per chunk, partial sums added);
//            on opencl and glsl, rill::sum of a stream a kernel wrote there against
//            download() + the same TBB sum. The orders differ, so only closeness is checked.
//   connect  two Float4 kernels a and b fused with connect(a, b), against two launches with
//            an intermediate stream: time, bytes of stream traffic per element, identical bits.
// A backend that cannot run here is skipped with its reason. Exit status 1 if any check fails.
#include <rill/rill.h>
#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <random>
#include <string>
#include <vector>

#include "CommaList.h"
#include "Timing.h"
#include "UsableBackends.h"

namespace {

using namespace rill;
using namespace rill::bench;

struct Options {
  std::vector<std::string> sections{"blur", "reduce", "connect"};
  std::vector<std::string> backends{"cpu", "simd", "opencl", "glsl"};
  int reps = 5;
  int64_t width = 1920, height = 1080;
  int64_t reduce_n = int64_t{1} << 24;
  int64_t connect_n = int64_t{1} << 21;
};

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

double time_ms(const auto& f) {
  auto t = Clock::now();
  f();
  return ms_since(t);
}

// ---- blur -----------------------------------------------------------------------------------

// 1 4 6 4 1 over 16, along x or y, from any source gathered as src(x, y).
template <class Src>
Program blur_pass(const char* name, const Src& src, bool vertical) {
  return program(name, [&] {
    Output<Float4> out("out");
    Int2 p = element_coord();
    const float w[5] = {1.0f / 16, 4.0f / 16, 6.0f / 16, 4.0f / 16, 1.0f / 16};
    Float4 acc(0.0f);
    for (int k = -2; k <= 2; ++k)
      acc += (vertical ? src(p.x(), p.y() + k) : src(p.x() + k, p.y())) * w[k + 2];
    out = acc;
  });
}

bool run_blur(const Options& o) {
  const int64_t W = o.width, H = o.height, n = W * H;
  std::printf("\nblur: %lldx%lld Float4, 5-tap horizontal then vertical, %d reps (medians)\n",
              (long long)W, (long long)H, o.reps);
  std::vector<glm::vec4> pixels(static_cast<size_t>(n));
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (auto& px : pixels) px = glm::vec4(u(rng), u(rng), u(rng), 1.0f);

  bool ok = true;
  std::vector<glm::vec4> cpu_bits;
  std::vector<std::string> names = usable_backends(o.backends);
  std::printf("  %-8s %12s %14s %8s  %s\n", "backend", "chain ms", "round trip ms", "ratio",
              "bits");
  for (const auto& be : names) {
    Stream<Float4> src(W, H, "src"), tmp(W, H, "tmp"), out_chain(W, H, "out_chain"),
        out_trip(W, H, "out_trip");
    src.upload(pixels);
    Array<Float4> tmp_host(W, H, "tmp_host");
    Kernel h = compile(blur_pass("blur_h", src, false), be);
    Kernel v = compile(blur_pass("blur_v", tmp, true), be);
    Kernel v_trip = compile(blur_pass("blur_v_host", tmp_host, true), be);
    h.bind("out", tmp);
    v.bind("out", out_chain);
    v_trip.bind("out", out_trip);
    auto chain = [&] {
      h.execute();
      v.execute();
    };
    auto trip = [&] {
      h.execute();
      tmp_host.upload(tmp.download());
      v_trip.execute();
    };
    chain();  // warm up: uploads, first launches
    trip();
    std::vector<double> chain_ms, trip_ms;
    for (int r = 0; r < o.reps; ++r) {
      chain_ms.push_back(time_ms(chain));
      trip_ms.push_back(time_ms(trip));
    }
    auto a = out_chain.download(), b = out_trip.download();
    const bool same = same_bits(a, b);
    if (be == names.front()) cpu_bits = a;
    const bool same_as_first = same_bits(a, cpu_bits);
    ok = ok && same && same_as_first;
    const double c = median(chain_ms), t = median(trip_ms);
    std::printf("  %-8s %12.2f %14.2f %7.2fx  %s, %s %s\n", be.c_str(), c, t, t / c,
                same ? "identical" : "DIFFERENT", same_as_first ? "same as" : "DIFFERENT from",
                names.front().c_str());
  }
  std::printf("  ratio = round trip / chain (above 1: the chain is faster)\n");
  return ok;
}

// ---- reduce ---------------------------------------------------------------------------------

// The hand-written reference: a plain sequential float sum over each chunk, chunks added.
float tbb_sum(const float* x, int64_t n) {
  return tbb::parallel_reduce(
      tbb::blocked_range<int64_t>(0, n, 4096), 0.0f,
      [&](const tbb::blocked_range<int64_t>& r, float acc) {
        for (int64_t i = r.begin(); i < r.end(); ++i) acc += x[i];
        return acc;
      },
      [](float a, float b) { return a + b; });
}

bool close(float got, double want) {
  return std::fabs(got - want) <= 1e-4 * std::fabs(want) + 1e-3;
}

bool run_reduce(const Options& o) {
  const int64_t n = o.reduce_n;
  std::printf("\nreduce: sum of %lld floats in [0, 1), %d threads, %d reps (medians)\n",
              (long long)n, tbb::info::default_concurrency(), o.reps);
  std::vector<float> data(static_cast<size_t>(n));
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  double exact = 0;
  for (auto& x : data) exact += (x = u(rng));
  const double gelem = static_cast<double>(n) * 1e-9;

  bool ok = true;
  std::vector<std::string> names = usable_backends(o.backends);
  std::printf("  %-8s %-22s %9s %9s %8s  %s %.1f)\n", "backend", "rill::sum against", "rill ms",
              "other ms", "rill/oth", "values (rill / other; double:", exact);
  Stream<Float> host_data(data);
  for (const auto& be : names) {
    const bool host_side = be == "cpu" || be == "simd";
    std::vector<double> rill_ms, other_ms;
    float rill_v = 0, other_v = 0;
    if (host_side) {
      // The data is in host memory, where both read it.
      rill_v = sum(host_data, be);  // warm up: compiles the levels
      other_v = tbb_sum(data.data(), n);
      for (int r = 0; r < o.reps; ++r) {
        rill_ms.push_back(time_ms([&] { rill_v = sum(host_data, be); }));
        other_ms.push_back(time_ms([&] { other_v = tbb_sum(data.data(), n); }));
      }
    } else {
      // A stream written on the device by a kernel (a copy), rewritten before each timing so
      // that download() really moves it.
      Stream<Float> on_device(n, "on_device");
      Kernel copy = compile(program("copy",
                                    [] {
                                      Input<Float> x("x");
                                      Output<Float> y("y");
                                      y = x;
                                    }),
                            be);
      copy.bind("x", host_data).bind("y", on_device);
      auto download_sum = [&] {
        std::vector<float> h = on_device.download();
        other_v = tbb_sum(h.data(), n);
      };
      copy.execute();
      rill_v = sum(on_device);  // warm up
      copy.execute();
      download_sum();
      for (int r = 0; r < o.reps; ++r) {
        copy.execute();
        rill_ms.push_back(time_ms([&] { rill_v = sum(on_device); }));
        copy.execute();
        other_ms.push_back(time_ms(download_sum));
      }
    }
    const double rm = median(rill_ms), om = median(other_ms);
    const bool good = close(rill_v, exact) && close(other_v, exact);
    ok = ok && good;
    std::printf("  %-8s %-22s %9.2f %9.2f %7.2fx  %.1f / %.1f%s\n", be.c_str(),
                host_side ? "TBB parallel_reduce" : "download() + TBB", rm, om, om / rm, rill_v,
                other_v, good ? "" : "  NOT CLOSE");
    std::printf("  %-8s %-22s %9.3f %9.3f  Gelem/s\n", "", "", gelem / (rm * 1e-3),
                gelem / (om * 1e-3));
  }
  std::printf("  rill/oth = throughput of rill::sum over the other's (goal on cpu: >= 0.8x)\n");
  return ok;
}

// ---- connect --------------------------------------------------------------------------------

Program connect_a() {
  return program("a", [] {
    Input<Float4> x("x");
    Output<Float4> t("t");
    Float4 v = x * 1.25f + 0.5f;
    v = v * v - x;
    v = sqrt(abs(v)) + min(x, Float4(0.75f));
    t = v / (v + 1.0f);
  });
}

Program connect_b() {
  return program("b", [] {
    Input<Float4> t("t");
    Output<Float4> y("y");
    Float4 v = t * t * 3.0f - t * 2.0f;
    v = max(v, Float4(0.0f)) + fract(t * 7.0f);
    y = Float4(v.xyz() / (dot(v, v) + 1.0f), length(v));
  });
}

bool run_connect(const Options& o) {
  const int64_t n = o.connect_n;
  std::printf("\nconnect: a >> b on %lld Float4 elements, %d reps (medians)\n", (long long)n,
              o.reps);
  std::vector<glm::vec4> data(static_cast<size_t>(n));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-2.0f, 2.0f);
  for (auto& v : data) v = glm::vec4(u(rng), u(rng), u(rng), u(rng));
  Program a = connect_a(), b = connect_b(), ab = connect(a, b);
  // Stream traffic per element: fused reads x, writes y; two launches also write and read t.
  const int fused_bytes = 2 * 16, two_bytes = 4 * 16;

  bool ok = true;
  std::vector<glm::vec4> first_bits;
  std::vector<std::string> names = usable_backends(o.backends);
  std::printf("  %-8s %10s %10s %8s %14s  %s\n", "backend", "fused ms", "2 launch", "ratio",
              "bytes/elem", "bits");
  for (const auto& be : names) {
    Stream<Float4> x(n, "x"), t(n, "t"), y_fused(n, "y_fused"), y_two(n, "y_two");
    x.upload(data);
    Kernel kf = compile(ab, be), ka = compile(a, be), kb = compile(b, be);
    kf.bind("x", x).bind("y", y_fused);
    ka.bind("x", x).bind("t", t);
    kb.bind("t", t).bind("y", y_two);
    auto fused = [&] { kf.execute(); };
    auto two = [&] {
      ka.execute();
      kb.execute();
    };
    fused();
    two();
    std::vector<double> f_ms, t_ms;
    for (int r = 0; r < o.reps; ++r) {
      f_ms.push_back(time_ms(fused));
      t_ms.push_back(time_ms(two));
    }
    auto p = y_fused.download(), q = y_two.download();
    const bool same = same_bits(p, q);
    if (be == names.front()) first_bits = p;
    const bool same_as_first = same_bits(p, first_bits);
    ok = ok && same && same_as_first;
    const double fm = median(f_ms), tm = median(t_ms);
    std::printf("  %-8s %10.2f %10.2f %7.2fx %6d vs %-5d  %s, %s %s\n", be.c_str(), fm, tm, tm / fm,
                fused_bytes, two_bytes, same ? "identical" : "DIFFERENT",
                same_as_first ? "same as" : "DIFFERENT from", names.front().c_str());
  }
  std::printf("  ratio = two launches / fused (above 1: fusing is faster)\n");
  return ok;
}

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr,
               "rill-bench-compose: %s\n"
               "options: --sections blur,reduce,connect  --backends all|cpu,simd,opencl,glsl,glsl-compute\n"
               "         --reps R  --size WxH  --reduce-n N  --connect-n N\n",
               msg.c_str());
  std::exit(2);
}

}  // namespace

int main(int argc, char** argv) try {
  Options o;
  for (int i = 1; i < argc; i += 2) {
    std::string a = argv[i];
    if (i + 1 >= argc) usage_error("option " + a + " needs a value");
    std::string val = argv[i + 1];
    if (a == "--sections") {
      o.sections = split_list(val);
    } else if (a == "--backends") {
      if (val != "all") o.backends = split_list(val);
    } else if (a == "--reps") {
      o.reps = std::max(1, std::atoi(val.c_str()));
    } else if (a == "--size") {
      long long w = 0, h = 0;
      if (std::sscanf(val.c_str(), "%lldx%lld", &w, &h) != 2 || w < 1 || h < 1)
        usage_error("--size expects WxH");
      o.width = w;
      o.height = h;
    } else if (a == "--reduce-n") {
      o.reduce_n = std::max(1LL, std::atoll(val.c_str()));
    } else if (a == "--connect-n") {
      o.connect_n = std::max(1LL, std::atoll(val.c_str()));
    } else {
      usage_error("unknown option " + a);
    }
  }
  bool ok = true;
  if (has(o.sections, "blur")) ok = run_blur(o) && ok;
  if (has(o.sections, "reduce")) ok = run_reduce(o) && ok;
  if (has(o.sections, "connect")) ok = run_connect(o) && ok;
  std::printf("\n%s\n", ok ? "all checks passed" : "SOME CHECKS FAILED");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-bench-compose: %s\n", e.what());
  return 1;
}
