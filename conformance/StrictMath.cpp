// The measurement behind the strict-routine table of docs/accuracy.md: Rill's own exp, exp2,
// log, log2, pow, sin, cos, tan, atan and atan2 (StrictMath.h), run as strict kernels, against
// the same functions evaluated in double precision on the host.
#include <cfloat>
#include <numbers>

#include <rill/StrictMath.h>

#include "Suite.h"

namespace rill::conformance {

namespace {

using Sample = std::function<std::pair<float, float>(Rng&)>;

struct DomainSpec {
  std::string text;
  Sample sample;
};

struct MathFunction {
  std::string name;
  std::function<Float(const Float&, const Float&)> dsl;
  std::function<double(double, double)> ref;
  std::vector<DomainSpec> domains;
};

float uniform(Rng& r, double lo, double hi) {
  return static_cast<float>(std::uniform_real_distribution<double>(lo, hi)(r));
}
// A positive float with a uniformly chosen exponent in [emin, emax] (biased) and mantissa.
float positive_bits(Rng& r, uint32_t emin, uint32_t emax) {
  uint32_t e = std::uniform_int_distribution<uint32_t>(emin, emax)(r);
  return float_of((e << 23) | (static_cast<uint32_t>(r()) & 0x007fffffu));
}
float any_finite(Rng& r) {
  float f = positive_bits(r, 0, 254);
  return (r() & 1) ? -f : f;
}

Sample x_in(double lo, double hi) {
  return [lo, hi](Rng& r) { return std::pair{uniform(r, lo, hi), 0.0f}; };
}

std::vector<MathFunction> functions() {
  constexpr double pi = std::numbers::pi;
  auto unary = [](std::string name, Float (*dsl)(const Float&), double (*ref)(double),
                  std::vector<DomainSpec> d) {
    return MathFunction{name, [dsl](const Float& x, const Float&) { return dsl(x); },
                        [ref](double x, double) { return ref(x); }, std::move(d)};
  };
  auto trig = [&](const char* name, Float (*dsl)(const Float&), double (*ref)(double)) {
    return unary(name, dsl, ref,
                 {{"[-pi, pi]", x_in(-pi, pi)},
                  {"[-100, 100]", x_in(-100, 100)},
                  {"[-6434, 6434] (exact reduction)", x_in(-6434, 6434)},
                  {"[6434, 100000] (beyond it)", x_in(6434, 100000)}});
  };
  std::vector<MathFunction> f;
  f.push_back(unary(
      "exp", [](const Float& x) { return strict::exp(x); }, [](double x) { return std::exp(x); },
      {{"[-87.3, 88.7] (normal results)", x_in(-87.33, 88.72)},
       {"[-1, 1]", x_in(-1, 1)},
       {"[-103.9, -87.4] (denormal results)", x_in(-103.9, -87.4)}}));
  f.push_back(unary(
      "exp2", [](const Float& x) { return strict::exp2(x); }, [](double x) { return std::exp2(x); },
      {{"[-126, 128) (normal results)", x_in(-126, 127.999)},
       {"[-1, 1]", x_in(-1, 1)},
       {"[-149, -126] (denormal results)", x_in(-149, -126)}}));
  auto logs = [&](const char* name, Float (*dsl)(const Float&), double (*ref)(double)) {
    return unary(name, dsl, ref,
                 {{"all positive normal floats",
                   [](Rng& r) {
                     return std::pair{positive_bits(r, 1, 254), 0.0f};
                   }},
                  {"[0.5, 2]", x_in(0.5, 2)},
                  {"positive denormals", [](Rng& r) {
                     return std::pair{positive_bits(r, 0, 0), 0.0f};
                   }}});
  };
  f.push_back(logs(
      "log", [](const Float& x) { return strict::log(x); }, [](double x) { return std::log(x); }));
  f.push_back(logs(
      "log2", [](const Float& x) { return strict::log2(x); },
      [](double x) { return std::log2(x); }));
  f.push_back(MathFunction{
      "pow",
      [](const Float& x, const Float& y) { return strict::pow(x, y); },
      [](double x, double y) { return std::pow(x, y); },
      {{"x in (0, 10], y in [-10, 10]",
        [](Rng& r) {
          return std::pair{uniform(r, 1e-6, 10), uniform(r, -10, 10)};
        }},
       {"x in [0.5, 2], y in [-200, 200]",
        [](Rng& r) {
          return std::pair{uniform(r, 0.5, 2), uniform(r, -200, 200)};
        }},
       {"x any positive normal, y in [-1, 1]",
        [](Rng& r) {
          return std::pair{positive_bits(r, 1, 254), uniform(r, -1, 1)};
        }},
       {"x in [0.5, 2], |y log2 x| in [64, 126]",
        [](Rng& r) {
          float x = uniform(r, 0.5, 2);
          double t = uniform(r, 64, 126) * ((r() & 1) ? 1 : -1);
          return std::pair{x, static_cast<float>(t / std::log2(static_cast<double>(x)))};
        }},
       {"x in [-10, 0), y integer in [-20, 20]", [](Rng& r) {
          return std::pair{uniform(r, -10, -1e-3),
                           static_cast<float>(std::uniform_int_distribution<int>(-20, 20)(r))};
        }}}});
  f.push_back(trig(
      "sin", [](const Float& x) { return strict::sin(x); }, [](double x) { return std::sin(x); }));
  f.push_back(trig(
      "cos", [](const Float& x) { return strict::cos(x); }, [](double x) { return std::cos(x); }));
  f.push_back(trig(
      "tan", [](const Float& x) { return strict::tan(x); }, [](double x) { return std::tan(x); }));
  f.push_back(unary(
      "atan", [](const Float& x) { return strict::atan(x); }, [](double x) { return std::atan(x); },
      {{"[-1, 1]", x_in(-1, 1)},
       {"[-100, 100]", x_in(-100, 100)},
       {"all finite floats", [](Rng& r) {
          return std::pair{any_finite(r), 0.0f};
        }}}));
  f.push_back(MathFunction{"atan2",
                           [](const Float& y, const Float& x) { return strict::atan2(y, x); },
                           [](double y, double x) { return std::atan2(y, x); },
                           {{"y, x in [-10, 10]",
                             [](Rng& r) {
                               return std::pair{uniform(r, -10, 10), uniform(r, -10, 10)};
                             }},
                            {"y, x any finite floats", [](Rng& r) {
                               return std::pair{any_finite(r), any_finite(r)};
                             }}}});
  return f;
}

}  // namespace

std::vector<MathMeasurement> measure_strict_math(const std::string& backend, uint64_t seed,
                                                 int64_t samples) {
  std::vector<MathMeasurement> out;
  CompileOptions o;
  o.accuracy = Accuracy::Strict;
  for (const MathFunction& fn : functions()) {
    Program p = program("measure_" + fn.name, [&] {
      Input<Float> x("x");
      Input<Float> y("y");
      Output<Float> r("r");
      r = fn.dsl(x, y);
    });
    Kernel k = compile(p, backend, o);
    for (size_t d = 0; d < fn.domains.size(); ++d) {
      Rng rng(seed + d * 7919 + std::hash<std::string>{}(fn.name));
      std::vector<float> xs, ys;
      xs.reserve(static_cast<size_t>(samples));
      ys.reserve(static_cast<size_t>(samples));
      while (static_cast<int64_t>(xs.size()) < samples) {
        auto [x, y] = fn.domains[d].sample(rng);
        double r = fn.ref(x, y);
        // Only finite results in float (pow's domains are filtered to them).
        if (!std::isfinite(r) || std::fabs(r) > static_cast<double>(FLT_MAX)) continue;
        xs.push_back(x);
        ys.push_back(y);
      }
      Stream<Float> sx(xs), sy(ys), sr(samples);
      k.inputs(sx, sy).outputs(sr);
      k.execute();
      std::vector<float> got = sr.download();
      MathMeasurement m;
      m.function = fn.name;
      m.domain = fn.domains[d].text;
      m.samples = samples;
      double sum = 0;
      for (size_t i = 0; i < got.size(); ++i) {
        double e = ulp_error(static_cast<double>(got[i]), fn.ref(xs[i], ys[i]));
        sum += e;
        if (e > m.max_ulp) {
          m.max_ulp = e;
          m.worst_x = xs[i];
          m.worst_y = ys[i];
        }
      }
      m.mean_ulp = sum / static_cast<double>(got.size());
      out.push_back(m);
    }
  }
  return out;
}

}  // namespace rill::conformance
