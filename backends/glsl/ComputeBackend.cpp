// The GLSL compute backend (`glsl-compute`): kernels as GL 4.3 compute shaders.
//
// The fragment stage (`glsl`, GLSLBackend.cpp) is the thesis's model and stays as it is. Its
// cost on some GPUs is physical: on NVIDIA Hopper only a few SMs run pixel shaders, while
// compute shaders run on all of them. This backend runs the same generated body
// (GLSLEmitter.cpp, Stage::Compute) as a compute shader:
//   - every stream and array lives in one GL buffer object holding the host's words as
//     they are, so uploads and read-backs are plain copies (no padding to texels);
//   - a launch binds inputs and outputs as shader storage buffers (bindings from
//     compute_bindings()) and arrays, including streams gathered from, as buffer textures on
//     units 0, 1, ... (read-only data through the texture cache);
//   - one invocation per element, in work groups of 64 (RILL_GLSL_LOCAL_SIZE changes it),
//     over a 2D grid of groups so that large streams stay within the group-count limit; a 2D
//     launch runs its elements in 8 x 4 tiles, 32 neighbours per subgroup (RILL_GLSL_TILES=off:
//     along rows);
//   - discarded elements return before storing, so outputs keep their previous values; the
//     counts of elements written and selected come back through a small storage buffer
//     (reading it is the launch's only wait);
//   - a masked launch passes the state stream and the selected values to the same program,
//     which returns early for elements not selected;
//   - lane groups (rill/Group.h) are the driver's subgroups where it has GL_KHR_shader_subgroup's
//     operations in compute shaders (Subgroups.h; RILL_GLSL_SUBGROUPS=off: a group of one).
// Strict kernels follow the same rules as on the fragment stage: `precise`, constants in a
// uniform, and corrected division and square root where the driver needs it (DivSqrt.h).
//
// The roles, each in its own file: the device memory (ComputeBuffers.h), the launcher
// (ComputeLauncher.h: a kernel's dispatches, and the ComputeDevice they run on); this file is
// the compiler (emit_glsl_compute, then link_program_cached), the context's set-up and the
// Backend interface over them.
#include "ComputeBackend.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <memory>
#include <vector>

#include "../codegen/SourceMap.h"
#include "ComputeBuffers.h"
#include "ComputeLauncher.h"
#include "DriverProbes.h"
#include "GLBackend.h"
#include "GLContext.h"
#include "GLSLEmitter.h"
#include "GLSession.h"
#include "Subgroups.h"
#include "rill/StateMask.h"
#include "rill/Stopwatch.h"

namespace rill::glsl {

namespace {

constexpr const char* kName = kComputeName;
constexpr const char* kWho = kComputeWho;

static_assert(kMaskValues == static_cast<int>(StateMask::kMaxValues));

class ComputeBackend : public GLBackend {
 public:
  ComputeBackend() : GLBackend(kWho), buffers_(*this, session_) {}
  ~ComputeBackend() override {
    forget_at_exit(this);
    shutdown();
  }

  std::string name() const override { return kName; }

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return std::string(kName) + ": unavailable: " + why;
    auto* self = const_cast<ComputeBackend*>(this);
    const GLContext& c = self->context();
    return std::string(kName) + ": compute shaders; " + c.kind() + ", " + c.renderer +
           "; strict / and sqrt: " +
           divsqrt_description(driver_.rules.divsqrt, driver_.rules.fused_fma, driver_.rules.lean) +
           ", comparisons: " + compare_name(driver_.rules.native_compare) +
           "; denormals: " + (device_.flushes_denormals ? "flushed" : "kept") +
           "; lane groups: " + lane_groups_text(subgroups_, driver_.rules.subgroups) + "; " +
           std::to_string(device_.limits.storage_blocks) + " storage buffers, " +
           std::to_string(device_.limits.texture_units) + " array units; disk cache: " +
           (driver_.binary_formats > 0 ? "program binaries"
                                       : "none (the driver offers no program binary format)");
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    const GL& gl = current();
    if (o.accuracy == Accuracy::Double)
      throw Error(std::string(kWho) +
                  ": accuracy mode 'double' is not supported (GLSL kernels compute in binary32)");
    // Storage buffers left for outputs after the inputs, the counters and the mask; more
    // outputs than that run in several passes.
    const int group = device_.limits.storage_blocks - static_cast<int>(f.inputs.size()) - 2;
    if (group < 1)
      throw Error(std::string(kWho) + ": kernel '" + f.name + "' reads " +
                  std::to_string(f.inputs.size()) + " input streams, but the driver (" +
                  driver_.renderer + ") allows " + std::to_string(device_.limits.storage_blocks) +
                  " shader storage buffers in a compute shader "
                  "(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS), two of "
                  "which Rill needs for counts and masks");
    if (static_cast<GLint>(f.arrays.size()) > device_.limits.texture_units)
      throw Error(std::string(kWho) + ": kernel '" + f.name + "' reads " +
                  std::to_string(f.arrays.size()) + " arrays but the driver (" + driver_.renderer +
                  ") allows " + std::to_string(device_.limits.texture_units) +
                  " textures in a compute shader (GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS)");
    Stopwatch stage;
    double codegen_ms = 0, link_ms = 0;
    bool all_cached = true;
    std::vector<ComputeKernel::Pass> passes;
    std::string source;
    for (size_t first = 0; first < std::max<size_t>(1, f.outputs.size());
         first += static_cast<size_t>(group)) {
      ComputeKernel::Pass p;
      for (size_t o = first; o < std::min(f.outputs.size(), first + static_cast<size_t>(group));
           ++o)
        p.outputs.push_back(static_cast<int>(o));
      GLSLShader shader =
          emit_glsl_compute(f, o.accuracy, p.outputs, passes.empty(), driver_.rules,
                            device_.flushes_denormals, device_.local_size, nullptr, o.source_map);
      codegen_ms += stage.lap();
      bool cached = false;
      p.program = codegen::reporting_user_lines(
          shader.source,
          [&] {
            return emit_glsl_compute(f, o.accuracy, p.outputs, passes.empty(), driver_.rules,
                                     device_.flushes_denormals, device_.local_size, nullptr, true)
                .source;
          },
          [&] {
            return link_program_cached(gl, driver_, kName, kWho, f.name,
                                       {{GL_COMPUTE_SHADER, shader.source}}, cached);
          });
      link_ms += stage.lap();
      all_cached = all_cached && cached;
      p.constants = std::move(shader.constants);
      source += shader.source;
      passes.push_back(std::move(p));
    }
    auto kernel =
        std::make_unique<ComputeKernel>(*this, buffers_, device_, session_, f, std::move(passes),
                                        std::move(source), device_.local_size);
    kernel->set_origin(all_cached ? KernelOrigin::DiskCache : KernelOrigin::Built);
    kernel->set_build_times(codegen_ms, link_ms);
    return kernel;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    buffers_.read_back(current(), s, host);
  }
  std::unique_ptr<PendingReadBack> read_back_async(const detail::Storage& s,
                                                   uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    return buffers_.read_back_async(current(), s, host);
  }

  // Deletes the backend's GL objects and destroys the context (see GLSession.h).
  void shutdown() noexcept override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    if (const GL* gl = session_->current_if_alive()) {
      if (device_.counter) gl->glDeleteBuffers(1, &device_.counter);
      timer_.destroy(*gl);
    }
    device_.counter = 0;
    session_->context.reset();
  }

 private:
  void set_up(const GL& gl, GLContext& c) override {
    device_.times_dispatches = !is_software_renderer(c.renderer);
    if (driver_.major < 4 || (driver_.major == 4 && driver_.minor < 3))
      throw Error(std::string(kWho) + ": compute shaders need OpenGL 4.3; the context (" +
                  c.kind() + ", " + driver_.renderer + ") has OpenGL " + driver_.version_text());
    gl.glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &device_.limits.storage_blocks);
    gl.glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &device_.limits.texture_units);
    gl.glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &device_.limits.groups_x);
    gl.glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &device_.limits.block_bytes);
    GLint texels = 0;
    gl.glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    device_.limits.texels = texels;
    GLint invocations = 128;
    gl.glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
    if (const char* size = std::getenv("RILL_GLSL_LOCAL_SIZE"))  // for measuring
      device_.local_size = std::clamp(std::atoi(size), 1, invocations);
    if (const char* t = std::getenv("RILL_GLSL_TILES"); t && *t) {
      const std::string v = t;
      if (v != "on" && v != "off") throw Error("RILL_GLSL_TILES='" + v + "' is not one of on, off");
      device_.tiles = v == "on";
    }
    gl.glGenBuffers(1, &device_.counter);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, device_.counter);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, 16, nullptr, GL_DYNAMIC_READ);
    device_.flushes_denormals = probe_flushes_denormals(gl, driver_, kWho);
    const bool wanted = subgroups_wanted();  // a bad value is an error on every driver
    subgroups_ = query_subgroups(gl);
    driver_.rules.subgroups = subgroups_.usable && wanted;
  }

  ComputeDevice device_;
  GLSubgroups subgroups_;  // what the driver has; driver_.rules.subgroups: whether it is used
  ComputeBuffers buffers_;
};

}  // namespace

std::unique_ptr<Backend> make_compute_backend() {
  return std::make_unique<ComputeBackend>();
}

}  // namespace rill::glsl
