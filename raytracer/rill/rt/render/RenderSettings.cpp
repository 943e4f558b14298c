#include "rill/rt/render/RenderSettings.h"

#include <stdexcept>

namespace rt {

MegakernelLoop parse_megakernel_loop(const std::string& s) {
  if (s == "auto") return MegakernelLoop::Auto;
  if (s == "ray") return MegakernelLoop::Ray;
  if (s == "segment") return MegakernelLoop::Segment;
  throw std::invalid_argument("--loop expects auto, ray or segment (got '" + s + "')");
}

const char* megakernel_loop_name(MegakernelLoop loop) {
  switch (loop) {
    case MegakernelLoop::Auto:
      return "auto";
    case MegakernelLoop::Ray:
      return "ray";
    case MegakernelLoop::Segment:
      return "segment";
  }
  return "?";
}

MegakernelLoop megakernel_loop_for(MegakernelLoop loop, const std::string& backend) {
  if (loop != MegakernelLoop::Auto) return loop;
  // Measured (docs/benchmarks/2026-11-25-gpu-frame.md, "Session 23"): Segment takes 3-8%
  // fewer instructions on cpu and simd; on the H200, NVIDIA's OpenCL ran Ray 3-8% faster.
  // Every other backend keeps Ray on every device, PoCL and llvmpipe included: then CI, which
  // has no GPU, runs the GPUs' program and checks its images against cpu's.
  return backend == "cpu" || backend == "simd" ? MegakernelLoop::Segment : MegakernelLoop::Ray;
}

}  // namespace rt
