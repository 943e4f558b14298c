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
//     which returns early for elements not selected.
// Strict kernels follow the same rules as on the fragment stage: `precise`, constants in a
// uniform, and corrected division and square root where the driver needs it (DivSqrt.h).
#include "ComputeBackend.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "../codegen/Tiles.h"
#include "GLBackend.h"
#include "GLContext.h"
#include "GLSLEmitter.h"
#include "GLSession.h"
#include "KernelTimer.h"
#include "WarmUpLaunch.h"
#include "rill/Parameters.h"
#include "rill/StateMask.h"
#include "rill/Stopwatch.h"

namespace rill::glsl {

namespace {

constexpr const char* kName = "glsl-compute";
constexpr const char* kWho = "glsl-compute backend";

static_assert(kMaskValues == static_cast<int>(StateMask::kMaxValues));

// The buffer texture format of an element type (3-component formats exist for buffer
// textures since GL 4.0).
GLenum texel_format(ir::Type t) {
  const bool f = t.is_float();
  switch (t.width) {
    case 1:
      return f ? GL_R32F : GL_R32I;
    case 2:
      return f ? GL_RG32F : GL_RG32I;
    case 3:
      return f ? GL_RGB32F : GL_RGB32I;
    default:
      return f ? GL_RGBA32F : GL_RGBA32I;
  }
}

// A stream's or array's device copy: a buffer object, and a buffer texture over it once the
// data is gathered from.
struct Buffer : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  GLuint buf = 0, tex = 0;
  int64_t bytes = 0;  // allocated
  ~Buffer() override {
    if (!buf && !tex) return;
    std::lock_guard<std::recursive_mutex> lock(session->mutex);
    if (const GL* gl = session->current_if_alive()) {
      if (tex) gl->glDeleteTextures(1, &tex);
      if (buf) gl->glDeleteBuffers(1, &buf);
    }
  }
};

// What the driver allows, asked once.
struct Limits {
  GLint storage_blocks = 8, texture_units = 16, groups_x = 65535;
  GLint64 block_bytes = 1 << 24, texels = 65536;
};

class ComputeBackend;

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
  ComputeKernel(ComputeBackend& be, std::shared_ptr<Session> session, ir::Function f,
                std::vector<Pass> passes, std::string source, int local_size)
      : be_(be),
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
  // whose invocations all return at once).
  void warm_up() override { run(WarmUpLaunch(fn_).args()); }

 private:
  void check_limits(const LaunchArgs& a) const;
  // One pass: `inputs` and `mask` are the buffers to read them from (copies, see run()).
  void dispatch(const GL& gl, Pass& p, const LaunchArgs& a, const std::vector<GLuint>& inputs,
                GLuint mask);

  ComputeBackend& be_;                // run() is only called while the backend exists
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

class ComputeBackend : public GLBackend {
 public:
  ComputeBackend() : GLBackend(kWho) {}
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
           "; strict / and sqrt: " + divsqrt_name(driver_.rules.divsqrt) +
           ", comparisons: " + compare_name(driver_.rules.native_compare) +
           "; denormals: " + (flushes_denormals_ ? "flushed" : "kept") + "; " +
           std::to_string(limits_.storage_blocks) + " storage buffers, " +
           std::to_string(limits_.texture_units) + " array units; disk cache: " +
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
    const int group = limits_.storage_blocks - static_cast<int>(f.inputs.size()) - 2;
    if (group < 1)
      throw Error(std::string(kWho) + ": kernel '" + f.name + "' reads " +
                  std::to_string(f.inputs.size()) + " input streams, but the driver (" +
                  driver_.renderer + ") allows " + std::to_string(limits_.storage_blocks) +
                  " shader storage buffers in a compute shader "
                  "(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS), two of "
                  "which Rill needs for counts and masks");
    if (static_cast<GLint>(f.arrays.size()) > limits_.texture_units)
      throw Error(std::string(kWho) + ": kernel '" + f.name + "' reads " +
                  std::to_string(f.arrays.size()) + " arrays but the driver (" + driver_.renderer +
                  ") allows " + std::to_string(limits_.texture_units) +
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
      GLSLShader shader = emit_glsl_compute(f, o.accuracy, p.outputs, passes.empty(), driver_.rules,
                                            flushes_denormals_, local_size_);
      codegen_ms += stage.lap();
      bool cached = false;
      p.program = link_program_cached(gl, driver_, kName, kWho, f.name,
                                      {{GL_COMPUTE_SHADER, shader.source}}, cached);
      link_ms += stage.lap();
      all_cached = all_cached && cached;
      p.constants = std::move(shader.constants);
      source += shader.source;
      passes.push_back(std::move(p));
    }
    auto kernel = std::make_unique<ComputeKernel>(*this, session_, f, std::move(passes),
                                                  std::move(source), local_size_);
    kernel->set_origin(all_cached ? KernelOrigin::DiskCache : KernelOrigin::Built);
    kernel->set_build_times(codegen_ms, link_ms);
    return kernel;
  }
  void read_back(const detail::Storage& s, uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    const GL& gl = current();
    auto* b = s.device_buffer<Buffer>(this);
    if (s.words() == 0) return;
    gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, b->buf);
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(s.words() * 4),
                          host);
    check(gl, "reading a buffer back", kWho);
  }

  // --- used by ComputeKernel::run, under the lock ----------------------------------------

  const Limits& limits() const { return limits_; }
  GLuint counter() const { return counter_; }
  // Whether the timer covers dispatches: Mesa's software renderers time the draw pipeline
  // only (a 25 ms dispatch on llvmpipe measured 0.02 ms), so launches there report -1.
  bool times_dispatches() const { return times_dispatches_; }
  bool tiles() const { return tiles_; }

  // The buffer holding s, current with the host copy.
  Buffer& to_device(const GL& gl, detail::Storage& s) {
    auto* b = s.device_buffer<Buffer>(this);
    if (b && s.is_device_current(this)) return *b;
    // The freshest copy may be another backend's, read back now: with the other GLSL
    // backend, through its own context, so this one is made current again.
    const uint32_t* host = s.words() > 0 ? s.host_data_for_read() : nullptr;
    current();
    b = s.device_buffer<Buffer>(this);
    const int64_t bytes = std::max<int64_t>(16, static_cast<int64_t>(s.words()) * 4);
    // A buffer that is stale in some words only gets just those (Storage::stale_words).
    auto [first, end] = s.stale_words();
    if (!b || b->bytes != bytes) {
      first = 0;
      end = s.words();
      auto fresh = std::make_unique<Buffer>();
      fresh->session = session_;
      fresh->bytes = bytes;
      gl.glGenBuffers(1, &fresh->buf);
      gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, fresh->buf);
      gl.glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, nullptr, GL_DYNAMIC_COPY);
      check(gl, "allocating a buffer", kWho);
      b = fresh.get();
      s.set_device_buffer(this, std::move(fresh));
      current();  // releasing another backend's copy may have made its context current
    }
    if (host != nullptr && end > first) {
      gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, b->buf);
      gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(first * 4),
                         static_cast<GLsizeiptr>((end - first) * 4), host + first);
      check(gl, "uploading a buffer", kWho);
    }
    s.mark_device_current(this);
    return *b;
  }

  // The buffer texture over s's buffer, for gathers.
  GLuint texture_of(const GL& gl, detail::Storage& s) {
    Buffer& b = to_device(gl, s);
    if (b.tex == 0) {
      gl.glGenTextures(1, &b.tex);
      gl.glBindTexture(GL_TEXTURE_BUFFER, b.tex);
      gl.glTexBuffer(GL_TEXTURE_BUFFER, texel_format(s.type()), b.buf);
      check(gl, "making a buffer texture", kWho);
    }
    return b.tex;
  }

  // Deletes the backend's GL objects and destroys the context (see GLSession.h).
  void shutdown() noexcept override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    if (const GL* gl = session_->current_if_alive()) {
      if (counter_) gl->glDeleteBuffers(1, &counter_);
      timer_.destroy(*gl);
    }
    counter_ = 0;
    session_->context.reset();
  }

 private:
  void set_up(const GL& gl, GLContext& c) override {
    times_dispatches_ = !is_software_renderer(c.renderer);
    if (driver_.major < 4 || (driver_.major == 4 && driver_.minor < 3))
      throw Error(std::string(kWho) + ": compute shaders need OpenGL 4.3; the context (" +
                  c.kind() + ", " + driver_.renderer + ") has OpenGL " + driver_.version_text());
    gl.glGetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &limits_.storage_blocks);
    gl.glGetIntegerv(GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, &limits_.texture_units);
    gl.glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &limits_.groups_x);
    gl.glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &limits_.block_bytes);
    GLint texels = 0;
    gl.glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
    limits_.texels = texels;
    GLint invocations = 128;
    gl.glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &invocations);
    if (const char* size = std::getenv("RILL_GLSL_LOCAL_SIZE"))  // for measuring
      local_size_ = std::clamp(std::atoi(size), 1, invocations);
    if (const char* t = std::getenv("RILL_GLSL_TILES"); t && *t) {
      const std::string v = t;
      if (v != "on" && v != "off") throw Error("RILL_GLSL_TILES='" + v + "' is not one of on, off");
      tiles_ = v == "on";
    }
    gl.glGenBuffers(1, &counter_);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, counter_);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, 16, nullptr, GL_DYNAMIC_READ);
    flushes_denormals_ = probe_flushes_denormals(gl);
  }

  // Whether the driver's compute arithmetic flushes denormals: 2 * the smallest denormal,
  // computed by a one-invocation shader, comes back as zero. llvmpipe flushes in fragment
  // shaders but not in compute shaders; NVIDIA flushes in both.
  bool probe_flushes_denormals(const GL& gl) {
    GLuint prog = link_program(gl, driver_, kWho, "rill_denormal_probe",
                               {{GL_COMPUTE_SHADER,
                                 "#version 430 core\n"
                                 "layout(local_size_x = 1) in;\n"
                                 "layout(std430, binding = 0) buffer B { float d[]; } b;\n"
                                 "void main() { b.d[1] = b.d[0] * 2.0; }\n"}});
    const float in[4] = {std::numeric_limits<float>::denorm_min(), 1.0f, 0, 0};
    GLuint buf = 0;
    gl.glGenBuffers(1, &buf);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, sizeof in, in, GL_DYNAMIC_COPY);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf);
    gl.glUseProgram(prog);
    gl.glDispatchCompute(1, 1, 1);
    gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float out[4] = {};
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof out, out);
    gl.glUseProgram(0);
    gl.glDeleteProgram(prog);
    gl.glDeleteBuffers(1, &buf);
    check(gl, "probing how the driver treats denormals", kWho);
    return out[1] == 0.0f;
  }

  bool flushes_denormals_ = true;
  Limits limits_;
  int local_size_ = 64;
  bool tiles_ = true;   // 2D launches in 8 x 4 tiles (RILL_GLSL_TILES)
  GLuint counter_ = 0;  // the launch's counts: elements written, selected
  bool times_dispatches_ = false;
};

void ComputeKernel::check_limits(const LaunchArgs& a) const {
  const Limits& lim = be_.limits();
  auto too_big = [&](const detail::Storage& s, const std::string& what) {
    const GLint64 bytes = static_cast<GLint64>(s.words()) * 4;
    if (bytes > lim.block_bytes)
      throw Error(std::string(kWho) + ": kernel '" + fn_.name + "': " + what + " holds " +
                  std::to_string(bytes) +
                  " bytes, over the driver's limit for a storage buffer "
                  "(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, " +
                  std::to_string(lim.block_bytes) + " bytes)");
  };
  for (size_t i = 0; i < a.inputs.size(); ++i) too_big(*a.inputs[i], "input " + std::to_string(i));
  for (size_t o = 0; o < a.outputs.size(); ++o)
    too_big(*a.outputs[o], "output " + std::to_string(o));
  for (auto* arr : a.arrays)
    if (arr->count() > lim.texels)
      throw Error(std::string(kWho) + ": kernel '" + fn_.name + "': array '" + arr->name +
                  "' has " + std::to_string(arr->count()) +
                  " elements, over the driver's limit for a buffer texture " +
                  "(GL_MAX_TEXTURE_BUFFER_SIZE, " + std::to_string(lim.texels) + ")");
}

void ComputeKernel::dispatch(const GL& gl, Pass& p, const LaunchArgs& a,
                             const std::vector<GLuint>& inputs, GLuint mask) {
  Locations& loc = p.loc;
  if (!p.located) {
    auto at = [&](const char* name) { return gl.glGetUniformLocation(p.program, name); };
    loc.count = at("rill_count");
    loc.width = at("rill_width");
    loc.tiled = at("rill_tiled");
    loc.u = at("rill_u");
    loc.k = at("rill_k");
    loc.one = at("rill_one");
    loc.shapes = at("rill_shapes");
    loc.values = at("rill_values");
    loc.nvalues = at("rill_nvalues");
    p.located = true;
  }
  const ComputeBindings bind = compute_bindings(fn_, p.outputs.size());
  for (size_t i = 0; i < inputs.size(); ++i)
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER,
                        static_cast<GLuint>(bind.inputs + static_cast<int>(i)), inputs[i]);
  for (size_t k = 0; k < p.outputs.size(); ++k)
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER,
                        static_cast<GLuint>(bind.outputs + static_cast<int>(k)),
                        be_.to_device(gl, *a.outputs[static_cast<size_t>(p.outputs[k])]).buf);
  gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(bind.counts), be_.counter());
  gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(bind.mask), mask);
  gl.glUseProgram(p.program);
  set_kernel_uniforms(gl, loc, a.count, a.width, words_, p.constants, shapes_);
  if (loc.nvalues >= 0)
    gl.glUniform1i(loc.nvalues, a.mask ? static_cast<GLint>(a.mask_values.size()) : 0);
  if (a.mask && loc.values >= 0)
    gl.glUniform1iv(loc.values, static_cast<GLsizei>(a.mask_values.size()), a.mask_values.data());
  // 2D launches run in 8 x 4 tiles (GLSLEmitter.cpp) unless RILL_GLSL_TILES=off.
  const bool tiled = be_.tiles() && a.height > 1 && !a.warm_up;
  if (loc.tiled >= 0) gl.glUniform1i(loc.tiled, tiled ? 1 : 0);
  const int64_t span = tiled ? codegen::tiled_invocations(a.width, a.height) : a.count;
  check(gl, "preparing a launch", kWho);
  // Groups over a 2D grid: x up to the driver's limit, y as many rows of them as needed.
  const int64_t groups = std::max<int64_t>(1, (span + local_size_ - 1) / local_size_);
  const int64_t gx = std::min<int64_t>(groups, be_.limits().groups_x);
  const int64_t gy = (groups + gx - 1) / gx;
  gl.glDispatchCompute(static_cast<GLuint>(gx), static_cast<GLuint>(gy), 1);
  gl.glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                     GL_BUFFER_UPDATE_BARRIER_BIT);
}

LaunchResult ComputeKernel::run(const LaunchArgs& a) {
  if (a.count == 0 && !a.warm_up) return {0, 0, 0.0};  // nothing ran
  if (a.count > INT32_MAX)
    throw Error(std::string(kWho) + ": kernel '" + fn_.name + "': " + std::to_string(a.count) +
                " elements, over the 2^31 - 1 a launch can number");
  std::lock_guard<std::recursive_mutex> lock(be_.mutex());
  const GL& gl = be_.current();
  check_limits(a);
  // Inputs and the mask. With several passes, a stream that is also an output is read from a
  // copy taken before the first pass stores into it (within one pass, each element reads its
  // own input and state before storing its own output, so the stream itself serves).
  struct Copies {
    const GL& gl;
    std::vector<GLuint> bufs;
    ~Copies() {
      if (!bufs.empty()) gl.glDeleteBuffers(static_cast<GLsizei>(bufs.size()), bufs.data());
    }
  } copies{gl, {}};
  auto readable = [&](detail::StreamState* s) {
    GLuint buf = be_.to_device(gl, *s).buf;
    const bool also_output = std::find(a.outputs.begin(), a.outputs.end(), s) != a.outputs.end();
    if (!also_output || passes_.size() == 1) return buf;
    GLuint copy = 0;
    const GLsizeiptr bytes = std::max<GLsizeiptr>(16, static_cast<GLsizeiptr>(s->words() * 4));
    gl.glGenBuffers(1, &copy);
    copies.bufs.push_back(copy);
    gl.glBindBuffer(GL_COPY_WRITE_BUFFER, copy);
    gl.glBufferData(GL_COPY_WRITE_BUFFER, bytes, nullptr, GL_STREAM_COPY);
    gl.glBindBuffer(GL_COPY_READ_BUFFER, buf);
    gl.glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, 0, bytes);
    return copy;
  };
  in_buf_.clear();
  for (auto* s : a.inputs) in_buf_.push_back(readable(s));
  // Without a mask the program never reads its binding; the counter buffer stands in.
  const GLuint mask = a.mask ? readable(a.mask) : be_.counter();
  shapes_.clear();
  for (size_t i = 0; i < a.arrays.size(); ++i) {
    detail::ArrayState* arr = a.arrays[i];
    gl.glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(i));
    gl.glBindTexture(GL_TEXTURE_BUFFER, be_.texture_of(gl, *arr));
    shapes_.insert(shapes_.end(),
                   {static_cast<GLint>(arr->shape[0]), static_cast<GLint>(arr->shape[1]),
                    static_cast<GLint>(arr->shape[2])});
  }
  words_.clear();
  for (auto* u : a.uniforms) words_.insert(words_.end(), u->bits.begin(), u->bits.end());
  const GLuint zero[3] = {0, 0, 0};
  gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, be_.counter());
  gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
  // The outputs' buffers made current first (dispatch() binds them): the timer covers the
  // dispatches only, and nothing that may switch contexts (a read-back through the other GL
  // backend) runs while its query is active.
  for (auto* s : a.outputs) be_.to_device(gl, *s);
  KernelTimer::Running timed = be_.timer().start(gl);
  for (Pass& p : passes_) dispatch(gl, p, a, in_buf_, mask);
  GLuint counts[3] = {0, 0, 0};  // written, selected, loops cut (DriverRules::loop_guard)
  gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, be_.counter());
  gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counts,
                        counts);  // waits for the dispatches
  double device_ms = timed.end_ms();
  if (!be_.times_dispatches()) device_ms = -1;
  check(gl, "running a kernel", kWho);
  for (auto* s : a.outputs) s->mark_device_written(&be_);  // written, if cut short (below)
  if (counts[2] != 0) throw Error(loop_cut_message(kWho, fn_.name, be_.driver().renderer));
  return {counts[0], a.mask ? static_cast<int64_t>(counts[1]) : a.count, device_ms};
}

}  // namespace

std::unique_ptr<Backend> make_compute_backend() {
  return std::make_unique<ComputeBackend>();
}

}  // namespace rill::glsl
