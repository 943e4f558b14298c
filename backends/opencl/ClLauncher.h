// The OpenCL backend's launcher role: a built kernel (ClCompiler.h) run over a launch's
// streams, arrays and uniforms. Each launch sets the kernel's arguments (buffers from
// ClMemory.h; the array shapes, uniform words and mask values as small tables), runs it in
// work-groups of RILL_OPENCL_GROUP items (2D launches in 8 x 4 tiles unless RILL_OPENCL_TILES
// is off) and reads back the device's running count of elements written and selected, the
// launch's only wait.
#pragma once

#include <string>
#include <vector>

#include "ClCompiler.h"
#include "ClMemory.h"
#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::opencl {

// Reads the launch settings (RILL_OPENCL_GROUP, RILL_OPENCL_TILES, RILL_OPENCL_WARM_UP) once,
// and throws rill::Error naming one that is not valid: compile() calls it, so that a bad
// setting fails there rather than at the first launch (compile() keeps a failed warm-up quiet).
void check_launch_settings();

class ClKernel : public CompiledKernel {
 public:
  ClKernel(Device& device, ClMemory& memory, const ir::Function& f, std::string source,
           const BuiltKernel& built)
      : device_(device),
        memory_(memory),
        fn_(f),
        source_(std::move(source)),
        program_(built.program),
        kernel_(built.kernel) {
    set_origin(built.origin);
  }
  ~ClKernel() override {
    if (counter_) clReleaseMemObject(counter_);
    clReleaseKernel(kernel_);
    clReleaseProgram(program_);
  }
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // PoCL compiles the kernel at its first enqueue for the work-group size and for the class
  // of grid: up to 65535 work-items ("smallgrid": 32-bit ids) or more. Two launches over no
  // elements, with the usual group size and a grid of each class, do both now.
  void warm_up() override;

 private:
  Device& device_;
  ClMemory& memory_;
  ir::Function fn_;
  std::string source_;
  cl_program program_;
  cl_kernel kernel_;
  size_t warm_up_grid_ = 1;  // work-items a warm-up launch spans (warm_up)
  // Launches reuse their buffers (run() is called one launch at a time: Kernel's run_mutex).
  // The counter is never reset: it keeps running totals of elements written and selected, and
  // a launch's counts are the difference from the totals after the previous one (unsigned
  // arithmetic, so the totals may wrap).
  cl_mem counter_ = nullptr;
  cl_uint totals_[2] = {0, 0};
  ClTable<cl_long> shapes_;
  ClTable<cl_uint> uniforms_;
  ClTable<cl_int> values_;
  std::vector<cl_long> shapes_now_;
  std::vector<cl_uint> uniforms_now_;
  size_t group_ = 0;  // work-group size, from the kernel and the device, asked once
};

}  // namespace rill::opencl
