// The glsl-compute backend's launcher role: a kernel's compute programs (one per group of
// outputs that fits the driver's storage buffers) dispatched over its elements. A launch binds
// inputs and outputs as shader storage buffers and arrays (streams gathered from too) as buffer
// textures, runs one invocation per element in work groups of the device's local size over a
// 2D grid of groups (2D launches in 8 x 4 tiles), and reads back the counts of elements written
// and selected, its only wait. Discarded elements return before storing; a masked launch passes
// the state stream and the selected values to the same program.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "ComputeBuffers.h"
#include "GLBackend.h"
#include "WarmUpLaunch.h"
#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::glsl {

// What the driver allows, asked once.
struct Limits {
  GLint storage_blocks = 8, texture_units = 16, groups_x = 65535;
  GLint64 block_bytes = 1 << 24, texels = 65536;
};

// What the backend learns and makes when its context is set up (ComputeBackend.cpp): the
// driver's limits, the launch layout, the buffer every launch writes its counts to, and how the
// driver treats denormals and timers.
struct ComputeDevice {
  Limits limits;
  int local_size = 64;  // invocations per work group (RILL_GLSL_LOCAL_SIZE)
  bool tiles = true;    // 2D launches in 8 x 4 tiles (RILL_GLSL_TILES)
  GLuint counter = 0;   // the launch's counts: elements written, selected
  // Whether the timer covers dispatches: Mesa's software renderers time the draw pipeline
  // only (a 25 ms dispatch on llvmpipe measured 0.02 ms), so launches there report -1.
  bool times_dispatches = false;
  bool flushes_denormals = true;
};

class ComputeKernel : public CompiledKernel {
 public:
  struct Locations {
    GLint count = -1, width = -1, u = -1, k = -1, one = -1, shapes = -1, values = -1, nvalues = -1,
          tiled = -1;
  };
  // One dispatch: every element computes the whole kernel and stores these outputs.
  struct Pass {
    std::vector<int> outputs;
    GLuint program = 0;
    std::vector<uint32_t> constants;
    Locations loc;
    bool located = false;
  };
  ComputeKernel(GLBackend& be, ComputeBuffers& buffers, const ComputeDevice& device,
                std::shared_ptr<Session> session, ir::Function f, std::vector<Pass> passes,
                std::string source, int local_size)
      : be_(be),
        buffers_(buffers),
        device_(device),
        session_(std::move(session)),
        fn_(std::move(f)),
        passes_(std::move(passes)),
        source_(std::move(source)),
        local_size_(local_size) {}
  ~ComputeKernel() override {
    std::lock_guard<std::recursive_mutex> lock(session_->mutex);
    if (const GL* gl = session_->current_if_alive())
      for (Pass& p : passes_) gl->glDeleteProgram(p.program);
  }
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // Drivers that finish compiling at the first dispatch do it now (a dispatch of one group
  // whose invocations all return at once), where that is what real launches use
  // (warm_up_pays).
  void warm_up() override {
    if (warm_up_pays(be_.driver().renderer, fn_)) run(WarmUpLaunch(fn_).args());
  }

 private:
  void check_limits(const LaunchArgs& a) const;
  // One pass: `inputs` and `mask` are the buffers to read them from (copies, see run()).
  void dispatch(const GL& gl, Pass& p, const LaunchArgs& a, const std::vector<GLuint>& inputs,
                GLuint mask);

  // run() is only called while the backend exists, and with it its buffers and device.
  GLBackend& be_;
  ComputeBuffers& buffers_;
  const ComputeDevice& device_;
  std::shared_ptr<Session> session_;  // the destructor may run after the backend's
  ir::Function fn_;
  std::vector<Pass> passes_;
  std::string source_;
  int local_size_;
  // Per launch, kept to reuse their memory.
  std::vector<uint32_t> words_;
  std::vector<GLint> shapes_;
  std::vector<GLuint> in_buf_;
};

}  // namespace rill::glsl
