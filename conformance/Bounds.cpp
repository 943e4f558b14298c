// The fast-mode contract: per operation and driver, the largest error (in ulps, see
// docs/accuracy.md for the measure and the domains) a conforming result may have.
//
// Exact operations have bound 0 and correctly rounded ones 0.5 on every backend. The columns
// cpu, opencl and glsl hold the drivers the suite was measured on (gcc + glibc, PoCL, Mesa
// llvmpipe): about 1.5 times the largest error seen (rill-conformance --accuracy fast, seeds
// 1 to 10, --elements 16384: see docs/accuracy.md), rounded up to a round number, so a larger
// error there is a regression. "other" is the contract for every other driver (NVIDIA's
// OpenCL and GLSL, ...), which the measurements say nothing about: twice the largest measured
// bound, or what the OpenCL relaxed-math / GLSL / Vulkan precision requirements allow where
// that is larger (sin, cos: absolute error 2^-11 on [-pi, pi]; tan: derived from them).
#include <map>

#include "Suite.h"

namespace rill::conformance {

namespace {

struct Bound {
  double cpu, opencl, glsl, other;
};

const std::map<std::string, Bound>& table() {
  static const std::map<std::string, Bound> t = {
      //                cpu   opencl  glsl   other
      // exact operations: any correct implementation is exact
      {"neg", {0, 0, 0, 0}},
      {"abs", {0, 0, 0, 0}},
      {"sign", {0, 0, 0, 0}},
      {"floor", {0, 0, 0, 0}},
      {"ceil", {0, 0, 0, 0}},
      {"trunc", {0, 0, 0, 0}},
      {"min", {0, 0, 0, 0}},
      {"max", {0, 0, 0, 0}},
      {"clamp", {0, 0, 0, 0}},
      {"select", {0, 0, 0, 0}},
      {"as_float", {0, 0, 0, 0}},
      {"unit_float", {0, 0, 0, 0}},
      {"swizzle", {0, 0, 0, 0}},
      {"write mask", {0, 0, 0, 0}},
      // correctly rounded in IEEE arithmetic (0.5 ulp)
      {"add", {0.5, 0.5, 0.5, 0.5}},
      {"sub", {0.5, 0.5, 0.5, 0.5}},
      {"mul", {0.5, 0.5, 0.5, 0.5}},
      {"to_float", {0.5, 0.5, 0.5, 0.5}},
      {"fract", {0.5, 0.5, 0.5, 1}},
      {"sqrt", {0.5, 0.5, 0.5, 3}},
      // div on cpu: -freciprocal-math lets gcc multiply by 1/b (1.46 ulp measured). It was
      // 0.5 only while gcc's SLP vectorizer turned the divisions into divps, and that
      // vectorizer is off since it miscompiled int max chains (backends/cpu/CpuBackend.cpp).
      {"div", {2.5, 4, 0.5, 4}},
      // 1 / sqrt(x): two roundings, up to 2 ulp
      {"rsqrt", {2, 3.5, 2, 4}},
      {"mod", {1, 1, 1, 2}},
      // transcendental functions (GLSL: llvmpipe's own approximations)
      {"exp", {1, 2, 128, 256}},
      {"exp2", {1, 2, 8, 16}},
      {"log", {1, 1, 4, 8}},
      {"log2", {1, 1, 4, 8}},
      {"pow", {1, 2, 1024, 2048}},
      // sin, cos: absolute error in units of 2^-23; other: 2^-11 (OpenCL relaxed, Vulkan)
      {"sin", {1, 2, 1.5, 4096}},
      {"cos", {1, 2, 1.5, 4096}},
      // tan: in ulps of 1 / cos^2(x); other: sin / cos with the above, sqrt(2) 2^-11 2^24
      {"tan", {1, 3, 3, 12288}},
      {"atan", {2, 2, 1024, 4096}},
      {"atan2", {3, 2, 1024, 4096}},
      // geometry (in ulps of the terms' magnitude where the formula cancels)
      {"dot", {3, 3, 3, 6}},
      {"length", {2, 2, 2, 4}},
      {"distance", {2.5, 2.5, 2.5, 5}},
      {"normalize", {4, 5, 4, 8}},
      {"cross", {2, 2, 2, 4}},
      {"lerp", {3, 3, 3, 6}},
      {"reflect", {4, 4, 4, 8}},
      {"refract", {12, 12, 12, 24}},
  };
  return t;
}

}  // namespace

bool measured_driver(const std::string& backend, const std::string& device) {
  if (backend == "cpu") return true;  // generated C, gcc and glibc
  if (backend == "opencl") return device.find("Portable Computing Language") != std::string::npos;
  if (backend == "glsl") return device.find("llvmpipe") != std::string::npos;
  return false;
}

double fast_bound(const std::string& op, const std::string& backend, const std::string& device) {
  auto it = table().find(op);
  if (it == table().end()) return -1;
  const Bound& b = it->second;
  if (!measured_driver(backend, device)) return b.other;
  if (backend == "cpu") return b.cpu;
  if (backend == "opencl") return b.opencl;
  return b.glsl;
}

double double_bound(const std::string& op) {
  // libm double functions (glibc, PoCL) are within a few double ulps: rounding that to float
  // can land on the other side of a rounding boundary, one float ulp away, in rare cases.
  static const char* const kTranscendental[] = {"exp", "exp2", "log", "log2", "pow",
                                                "sin", "cos",  "tan", "atan", "atan2"};
  for (const char* t : kTranscendental)
    if (op == t) return 1;
  return 0;
}

}  // namespace rill::conformance
