// A launch over no elements, with stand-in data of the types a kernel declares, for
// CompiledKernel::warm_up().
//
// Drivers that compile at the first launch do so for what that launch looks like: PoCL
// builds the work-group function for the local size, Mesa's llvmpipe the shader variant for
// the texture and framebuffer formats bound. A launch with the kernel's own types and the
// backend's usual launch parameters reaches the same compile. No element runs (count 0: no
// kernel code meets zero inputs, which could loop forever) and nothing is written.
#pragma once

#include <memory>
#include <vector>

#include "rill/Backend.h"
#include "rill/Parameters.h"

namespace rill {

class WarmUpLaunch {
 public:
  explicit WarmUpLaunch(const ir::Function& f);
  // count 0, warm_up set, one stand-in element per stream and array.
  const LaunchArgs& args() const { return args_; }

 private:
  std::vector<std::unique_ptr<detail::StreamState>> streams_;
  std::vector<std::unique_ptr<detail::ArrayState>> arrays_;
  std::vector<std::unique_ptr<detail::UniformState>> uniforms_;
  LaunchArgs args_;
};

}  // namespace rill
