// The GLSL backend: streams as float textures, kernels as fragment shaders drawn over them.
//
// Layout: a stream or array of n elements is a 2D texture of rows of min(n, 4096) texels
// (R32F, RG32F or RGBA32F; integer formats for Int data; 3-component data is padded to 4).
// A launch draws one triangle covering the outputs' texture with the kernel's shader:
//   - inputs and arrays are bound as textures and read with texelFetch;
//   - each output is a color attachment; a discarded fragment leaves its texel as it was,
//     which is the "discarded elements keep their previous value" rule for free;
//   - the previous values the kernel may read (an output not written on some path, or a
//     stream bound as both input and output) come from a copy taken before the draw, so no
//     texture is ever read while it is being rendered to;
//   - a GL_SAMPLES_PASSED query counts the fragments written.
// With more outputs than the context has draw buffers, the kernel is drawn once per group
// of outputs (each draw computes everything and writes its group).
//
// A masked launch (rill::where, StateMask.h) first draws a small shader over the state texture
// that keeps the fragments whose state is in the set and writes 1 to a stencil buffer there
// (its occlusion query counts the selected elements); the kernel is then drawn with the
// stencil test EQUAL 1 and stencil writes off. With no depth or stencil writes in the
// kernel's draw, drivers test before shading (early stencil / early-z: llvmpipe skips
// whole 4x4 blocks, GPUs whole tiles), so masked elements cost close to nothing.
// layout(early_fragment_tests) is not used: it would make the occlusion query count
// fragments the kernel then discards.
//
// The context, its shutdown at exit and the disk cache of program binaries: GLSession.h.
#include "GLSLBackend.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>
#include <vector>

#include "../codegen/SourceText.h"
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

constexpr int64_t kMaxRow = kTextureRow;  // GLSLEmitter.h

struct Format {
  GLenum internal, format, type;
  int channels;
};

Format format_of(ir::Type t) {
  bool f = t.is_float();
  switch (t.width) {
    case 1:
      return {GLenum(f ? GL_R32F : GL_R32I), GLenum(f ? GL_RED : GL_RED_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 1};
    case 2:
      return {GLenum(f ? GL_RG32F : GL_RG32I), GLenum(f ? GL_RG : GL_RG_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 2};
    default:
      return {GLenum(f ? GL_RGBA32F : GL_RGBA32I), GLenum(f ? GL_RGBA : GL_RGBA_INTEGER),
              GLenum(f ? GL_FLOAT : GL_INT), 4};
  }
}

struct Shape {
  int row = 1, rows = 1;
};
Shape shape_of(int64_t count) {
  Shape s;
  s.row = static_cast<int>(std::clamp<int64_t>(count, 1, kMaxRow));
  s.rows = static_cast<int>(std::max<int64_t>(1, (count + s.row - 1) / s.row));
  return s;
}

class GLSLBackend;

struct Texture : detail::DeviceBuffer {
  std::shared_ptr<Session> session;
  GLuint tex = 0;
  Format fmt{};
  Shape shape;
  ~Texture() override;
};

class GLSLKernel : public CompiledKernel {
 public:
  // Where a pass's program takes each of its uniforms (-1: the program does not use it),
  // asked once, at the first launch.
  struct Locations {
    std::vector<GLint> in, prev, arr;  // parallel to inputs, Pass::outputs, arrays
    GLint count = -1, row = -1, width = -1, u = -1, k = -1, one = -1, shapes = -1;
  };
  struct Pass {
    std::vector<int> outputs;
    GLuint program = 0;
    std::string source;
    std::vector<uint32_t> constants;
    Locations loc;
  };
  GLSLKernel(GLSLBackend& be, std::shared_ptr<Session> session, ir::Function f,
             std::vector<Pass> passes)
      : be_(be), session_(std::move(session)), fn_(std::move(f)), passes_(std::move(passes)) {
    for (const Pass& p : passes_) source_ += p.source;
  }
  ~GLSLKernel() override;
  // Where the programs came from, and what linking or loading them took.
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // llvmpipe compiles a shader's variant for the bound texture and framebuffer formats at
  // its first draw: one draw over one texel that the shader discards (rill_count 0) does it
  // now. (A masked launch, with the stencil test on, is another variant, built at the first.)
  void warm_up() override { run(WarmUpLaunch(fn_).args()); }

 private:
  // Masked launches: fills the stencil buffer from a.mask; returns the elements selected.
  GLuint draw_mask(const GL& gl, const LaunchArgs& a, const Shape& shape);
  // Fills every pass's Locations and reads_prev_ (at the first launch).
  void locate(const GL& gl, const LaunchArgs& a);

  GLSLBackend& be_;                   // run() is only called while the backend exists
  std::shared_ptr<Session> session_;  // the destructor may run after the backend's
  ir::Function fn_;
  std::vector<Pass> passes_;
  std::string source_;
  bool located_ = false;
  // Per output: whether some pass reads its previous values (an output not written on every
  // path). Outputs that no pass reads, and that are not also inputs, need no copy.
  std::vector<bool> reads_prev_;
  // Per launch, kept to reuse their memory: output textures, copies of outputs (0: none),
  // input and array textures, array shapes, uniform words and draw buffers.
  std::vector<Texture*> out_tex_;
  std::vector<GLenum> draw_bufs_;
  std::vector<GLuint> prev_, in_tex_, arr_tex_, words_;
  std::vector<GLint> shapes_;
};

class GLSLBackend : public GLBackend {
 public:
  GLSLBackend() : GLBackend("GLSL backend") {}
  // Backends live in the registry until exit; the exit handler has normally shut this one
  // down by then.
  ~GLSLBackend() override;

  std::string name() const override { return "glsl"; }

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return "glsl: unavailable: " + why;
    auto* self = const_cast<GLSLBackend*>(this);
    return "glsl: fragment shaders; " + self->context().kind() + ", " + self->context().renderer +
           "; strict / and sqrt: " + divsqrt_name(self->driver_.rules.divsqrt) +
           ", comparisons: " + compare_name(self->driver_.rules.native_compare) + "; disk cache: " +
           (self->driver_.binary_formats > 0
                ? std::string("program binaries")
                : std::string("none (the driver offers no program binary format)"));
  }

  std::unique_ptr<CompiledKernel> compile(const ir::Function& f, const CompileOptions& o) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    const GL& gl = current();
    if (o.accuracy == Accuracy::Double)
      throw Error(
          "GLSL backend: accuracy mode 'double' is not supported (GLSL kernels compute in "
          "binary32)");
    int group = std::max(1, max_draw_buffers_);
    std::vector<GLSLKernel::Pass> passes;
    double codegen_ms = 0, link_ms = 0;
    bool all_cached = true;
    Stopwatch stage;
    for (size_t first = 0; first < std::max<size_t>(1, f.outputs.size());
         first += static_cast<size_t>(group)) {
      GLSLKernel::Pass p;
      for (size_t i = first; i < std::min(f.outputs.size(), first + static_cast<size_t>(group));
           ++i)
        p.outputs.push_back(static_cast<int>(i));
      GLSLShader shader = emit_glsl(f, o.accuracy, p.outputs, driver_.rules);
      codegen_ms += stage.lap();
      p.source = std::move(shader.source);
      p.constants = std::move(shader.constants);
      bool cached = false;
      p.program = link_program_cached(
          gl, driver_, "glsl", "GLSL backend", f.name,
          {{GL_VERTEX_SHADER, vertex_shader()}, {GL_FRAGMENT_SHADER, p.source}}, cached);
      all_cached = all_cached && cached;
      link_ms += stage.lap();
      passes.push_back(std::move(p));
    }
    auto kernel = std::make_unique<GLSLKernel>(*this, session_, f, std::move(passes));
    kernel->set_origin(all_cached ? KernelOrigin::DiskCache : KernelOrigin::Built);
    kernel->set_build_times(codegen_ms, link_ms);
    return kernel;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    const GL& gl = current();
    auto* t = s.device_buffer<Texture>(this);
    std::vector<uint32_t> padded(static_cast<size_t>(t->shape.row) *
                                 static_cast<size_t>(t->shape.rows) *
                                 static_cast<size_t>(t->fmt.channels));
    gl.glBindTexture(GL_TEXTURE_2D, t->tex);
    gl.glPixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.glGetTexImage(GL_TEXTURE_2D, 0, t->fmt.format, t->fmt.type, padded.data());
    check(gl, "reading a texture back");
    int w = s.type().width;
    for (int64_t i = 0; i < s.count(); ++i)
      for (int c = 0; c < w; ++c)
        host[static_cast<size_t>(i * w + c)] = padded[static_cast<size_t>(i * t->fmt.channels + c)];
  }

  // --- used by GLSLKernel::run, under the lock --------------------------------------------

  static void check(const GL& gl, const char* what) { glsl::check(gl, what); }

  // The texture holding s, current with the host copy.
  Texture& to_device(const GL& gl, detail::Storage& s) {
    auto* t = s.device_buffer<Texture>(this);
    if (t && s.is_device_current(this)) return *t;
    // The freshest copy may be another backend's, read back now: with the other GLSL
    // backend, through its own context, so this one is made current again.
    const uint32_t* host = s.host_data_for_read();
    current();
    t = s.device_buffer<Texture>(this);
    Format fmt = format_of(s.type());
    Shape shape = shape_of(s.count());
    if (!t || t->fmt.internal != fmt.internal || t->shape.row != shape.row ||
        t->shape.rows != shape.rows) {
      auto fresh = std::make_unique<Texture>();
      fresh->session = session_;
      fresh->fmt = fmt;
      fresh->shape = shape;
      fresh->tex = new_texture(gl, fmt, shape);
      t = fresh.get();
      s.set_device_buffer(this, std::move(fresh));
      current();  // releasing another backend's copy may have made its context current
    }
    std::vector<uint32_t> padded(static_cast<size_t>(shape.row) * static_cast<size_t>(shape.rows) *
                                 static_cast<size_t>(fmt.channels));
    int w = s.type().width;
    for (int64_t i = 0; i < s.count(); ++i)
      for (int c = 0; c < w; ++c)
        padded[static_cast<size_t>(i * fmt.channels + c)] = host[static_cast<size_t>(i * w + c)];
    gl.glBindTexture(GL_TEXTURE_2D, t->tex);
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, shape.row, shape.rows, fmt.format, fmt.type,
                       padded.data());
    check(gl, "uploading a texture");
    s.mark_device_current(this);
    return *t;
  }

  GLuint new_texture(const GL& gl, const Format& fmt, const Shape& shape) {
    GLuint tex = 0;
    gl.glGenTextures(1, &tex);
    gl.glBindTexture(GL_TEXTURE_2D, tex);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(fmt.internal), shape.row, shape.rows, 0,
                    fmt.format, fmt.type, nullptr);
    check(gl, "allocating a texture");
    return tex;
  }

  // A texture of this format and shape for a launch's copy of an output's previous values:
  // one from the pool, else a new one. give_back() returns it.
  GLuint take_copy_texture(const GL& gl, const Format& fmt, const Shape& shape) {
    auto it = copy_pool_.find({fmt.internal, shape.row, shape.rows});
    if (it == copy_pool_.end() || it->second.empty()) return new_texture(gl, fmt, shape);
    GLuint tex = it->second.back();
    it->second.pop_back();
    return tex;
  }
  // Keeps the textures of small launches (up to kPooledTexels texels, a few per shape) for the
  // next launch, where allocating them would cost more than the kernel; deletes the others.
  void give_back_copy_texture(const GL& gl, const Format& fmt, const Shape& shape, GLuint tex) {
    constexpr int64_t kPooledTexels = int64_t{1} << 20;
    constexpr size_t kPerShape = 4;
    std::vector<GLuint>& pool = copy_pool_[{fmt.internal, shape.row, shape.rows}];
    if (int64_t{shape.row} * shape.rows <= kPooledTexels && pool.size() < kPerShape)
      pool.push_back(tex);
    else
      gl.glDeleteTextures(1, &tex);
  }

  // A depth-stencil renderbuffer of this size, for masked launches (kept for reuse).
  GLuint stencil(const GL& gl, const Shape& shape) {
    GLuint& rb = stencils_[{shape.row, shape.rows}];
    if (rb == 0) {
      gl.glGenRenderbuffers(1, &rb);
      gl.glBindRenderbuffer(GL_RENDERBUFFER, rb);
      gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, shape.row, shape.rows);
      check(gl, "allocating a stencil buffer");
    }
    return rb;
  }

  // The shader that turns a state texture into the stencil mask: it keeps (does not
  // discard) the elements whose state is one of rill_values[0 .. rill_nvalues).
  GLuint mask_program(const GL& gl) {
    if (mask_program_ == 0)
      mask_program_ =
          link_program(gl, driver_, "GLSL backend", "rill_mask",
                       {{GL_VERTEX_SHADER, vertex_shader()},
                        {GL_FRAGMENT_SHADER,
                         "#version 430 core\n"
                         "// Rill: the stencil mask of a masked launch.\n"
                         "uniform isampler2D rill_state;\n"
                         "uniform int rill_values[" +
                             std::to_string(StateMask::kMaxValues) +
                             "];\n"
                             "uniform int rill_nvalues;\n"
                             "uniform int rill_count;\n"
                             "uniform int rill_row;\n"
                             "void main() {\n"
                             "  ivec2 p = ivec2(gl_FragCoord.xy);\n"
                             "  if (p.y * rill_row + p.x >= rill_count) discard;\n"
                             "  int s = texelFetch(rill_state, p, 0).r;\n"
                             "  bool selected = false;\n"
                             "  for (int k = 0; k < rill_nvalues; ++k) selected = selected || s "
                             "== rill_values[k];\n"
                             "  if (!selected) discard;\n"
                             "}\n"}});
    return mask_program_;
  }

  GLuint fbo() const { return fbo_; }
  GLuint vao() const { return vao_; }
  GLuint query() const { return query_; }
  // DriverRules::loop_guard's word (kGuardBinding), made on the first launch that needs it.
  GLuint guard(const GL& gl) {
    if (!guard_) {
      gl.glGenBuffers(1, &guard_);
      gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, guard_);
      gl.glBufferData(GL_SHADER_STORAGE_BUFFER, 16, nullptr, GL_DYNAMIC_READ);
    }
    return guard_;
  }
  int max_texture_units() const { return max_units_; }

 public:
  // Deletes the backend's GL objects and destroys the context (see GLSession.h): called by the
  // exit handler and the destructor, from any thread; the second call does nothing. Objects
  // it cannot delete (the context not current here) go with the context.
  void shutdown() noexcept override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    if (const GL* gl = session_->current_if_alive()) {
      for (auto& [size, rb] : stencils_) gl->glDeleteRenderbuffers(1, &rb);
      for (auto& [key, pool] : copy_pool_)
        if (!pool.empty()) gl->glDeleteTextures(static_cast<GLsizei>(pool.size()), pool.data());
      if (mask_program_) gl->glDeleteProgram(mask_program_);
      gl->glDeleteQueries(1, &query_);
      if (guard_) gl->glDeleteBuffers(1, &guard_);
      timer_.destroy(*gl);
      gl->glDeleteVertexArrays(1, &vao_);
      gl->glDeleteFramebuffers(1, &fbo_);
    }
    stencils_.clear();
    copy_pool_.clear();
    fbo_ = vao_ = query_ = mask_program_ = guard_ = 0;
    session_->context.reset();  // destroys the GL context (GLContext.cpp)
  }

 private:
  void set_up(const GL& gl, GLContext&) override {
    GLint draw = 1, attach = 1, units = 16;
    gl.glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw);
    gl.glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attach);
    gl.glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
    max_draw_buffers_ = std::min(draw, attach);
    if (const char* force = std::getenv("RILL_GL_MAX_DRAW_BUFFERS"))  // to test pass splitting
      max_draw_buffers_ = std::clamp(std::atoi(force), 1, max_draw_buffers_);
    max_units_ = units;
    gl.glGenFramebuffers(1, &fbo_);
    gl.glGenVertexArrays(1, &vao_);
    gl.glGenQueries(1, &query_);
    gl.glDisable(GL_DITHER);
    gl.glDisable(GL_BLEND);
    gl.glDisable(GL_DEPTH_TEST);
  }

  int max_draw_buffers_ = 1, max_units_ = 16;
  GLuint fbo_ = 0, vao_ = 0, query_ = 0, guard_ = 0;
  GLuint mask_program_ = 0;
  std::map<std::pair<int, int>, GLuint> stencils_;
  // Textures for copies of outputs, by (internal format, row, rows), for reuse (see
  // give_back_copy_texture).
  std::map<std::tuple<GLenum, int, int>, std::vector<GLuint>> copy_pool_;
};

GLSLBackend::~GLSLBackend() {
  forget_at_exit(this);
  shutdown();
}

// Destroyed with its stream or array, possibly after the backend and the context are gone.
Texture::~Texture() {
  if (!tex) return;
  std::lock_guard<std::recursive_mutex> lock(session->mutex);
  if (const GL* gl = session->current_if_alive()) gl->glDeleteTextures(1, &tex);
}

// Destroyed with the kernel cache, possibly after the backend and the context are gone.
GLSLKernel::~GLSLKernel() {
  std::lock_guard<std::recursive_mutex> lock(session_->mutex);
  if (const GL* gl = session_->current_if_alive())
    for (Pass& p : passes_) gl->glDeleteProgram(p.program);
}

GLuint GLSLKernel::draw_mask(const GL& gl, const LaunchArgs& a, const Shape& shape) {
  GLuint state = be_.to_device(gl, *a.mask).tex;
  gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                               be_.stencil(gl, shape));
  const GLenum none = GL_NONE;
  gl.glDrawBuffers(1, &none);
  if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("GLSL backend: the stencil buffer for a masked launch of kernel '" + fn_.name +
                "' does not form a complete framebuffer");
  gl.glEnable(GL_STENCIL_TEST);
  gl.glStencilMask(0xff);
  gl.glClearStencil(0);
  gl.glClear(GL_STENCIL_BUFFER_BIT);
  gl.glStencilFunc(GL_ALWAYS, 1, 0xff);
  gl.glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
  GLuint prog = be_.mask_program(gl);
  gl.glUseProgram(prog);
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glBindTexture(GL_TEXTURE_2D, state);
  gl.glUniform1i(gl.glGetUniformLocation(prog, "rill_state"), 0);
  gl.glUniform1iv(gl.glGetUniformLocation(prog, "rill_values"),
                  static_cast<GLsizei>(a.mask_values.size()), a.mask_values.data());
  gl.glUniform1i(gl.glGetUniformLocation(prog, "rill_nvalues"),
                 static_cast<GLint>(a.mask_values.size()));
  gl.glUniform1i(gl.glGetUniformLocation(prog, "rill_count"), static_cast<GLint>(a.count));
  gl.glUniform1i(gl.glGetUniformLocation(prog, "rill_row"), shape.row);
  GLuint selected = 0;
  gl.glBeginQuery(GL_SAMPLES_PASSED, be_.query());
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
  gl.glEndQuery(GL_SAMPLES_PASSED);
  gl.glGetQueryObjectuiv(be_.query(), GL_QUERY_RESULT, &selected);
  // The kernel's draws: only where the mask wrote 1, and the stencil stays as it is.
  gl.glStencilMask(0);
  gl.glStencilFunc(GL_EQUAL, 1, 0xff);
  gl.glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  be_.check(gl, "building the mask of a masked launch");
  return selected;
}

void GLSLKernel::locate(const GL& gl, const LaunchArgs& a) {
  reads_prev_.assign(fn_.outputs.size(), false);
  for (Pass& p : passes_) {
    Locations& l = p.loc;
    l = Locations{};
    auto at = [&](const std::string& name) {
      return gl.glGetUniformLocation(p.program, name.c_str());
    };
    for (size_t i = 0; i < a.inputs.size(); ++i) l.in.push_back(at("rill_in" + std::to_string(i)));
    for (int o : p.outputs) {
      l.prev.push_back(at("rill_prev" + std::to_string(o)));
      if (l.prev.back() >= 0) reads_prev_[static_cast<size_t>(o)] = true;
    }
    for (size_t i = 0; i < a.arrays.size(); ++i)
      l.arr.push_back(at("rill_arr" + std::to_string(i)));
    l.count = at("rill_count");
    l.row = at("rill_row");
    l.width = at("rill_width");
    l.u = at("rill_u");
    l.k = at("rill_k");
    l.one = at("rill_one");
    l.shapes = at("rill_shapes");
  }
  located_ = true;
}

LaunchResult GLSLKernel::run(const LaunchArgs& a) {
  if (a.count == 0 && !a.warm_up) return {0, 0, 0.0};  // nothing ran
  if (a.count > kMaxRow * kMaxRow)
    throw Error("GLSL backend: streams are limited to 4096 x 4096 elements");
  std::lock_guard<std::recursive_mutex> lock(be_.mutex());
  const GL& gl = be_.current();
  size_t widest = 0;
  for (const Pass& p : passes_) widest = std::max(widest, p.outputs.size());
  const int units = static_cast<int>(a.inputs.size() + widest + a.arrays.size());
  if (units > be_.max_texture_units())
    throw Error("GLSL backend: kernel '" + fn_.name + "' reads " + std::to_string(units) +
                " textures but the context has " + std::to_string(be_.max_texture_units()) +
                " texture units");
  if (!located_ || passes_[0].loc.in.size() != a.inputs.size() ||
      passes_[0].loc.arr.size() != a.arrays.size())
    locate(gl, a);

  // Outputs: their textures, and a copy of their current contents (the previous values) where
  // the kernel reads them or reads the stream as an input too. The copies go back to the
  // backend's pool at the end of the launch, also when it throws.
  out_tex_.clear();
  prev_.clear();
  struct GiveBack {
    GLSLBackend& be;
    const GL& gl;
    std::vector<Texture*>& out;
    std::vector<GLuint>& prev;
    ~GiveBack() {
      for (size_t i = 0; i < prev.size(); ++i)
        if (prev[i]) be.give_back_copy_texture(gl, out[i]->fmt, out[i]->shape, prev[i]);
    }
  } give_back{be_, gl, out_tex_, prev_};
  for (size_t o = 0; o < a.outputs.size(); ++o) {
    detail::StreamState* s = a.outputs[o];
    Texture& t = be_.to_device(gl, *s);
    out_tex_.push_back(&t);
    const bool also_input = std::find(a.inputs.begin(), a.inputs.end(), s) != a.inputs.end();
    GLuint copy = 0;
    if (reads_prev_[o] || also_input) {
      copy = be_.take_copy_texture(gl, t.fmt, t.shape);
      gl.glCopyImageSubData(t.tex, GL_TEXTURE_2D, 0, 0, 0, 0, copy, GL_TEXTURE_2D, 0, 0, 0, 0,
                            t.shape.row, t.shape.rows, 1);
    }
    prev_.push_back(copy);
  }
  // Inputs: a stream that is also an output is read from its copy.
  in_tex_.clear();
  for (auto* s : a.inputs) {
    auto it = std::find(a.outputs.begin(), a.outputs.end(), s);
    in_tex_.push_back(it != a.outputs.end() ? prev_[static_cast<size_t>(it - a.outputs.begin())]
                                            : be_.to_device(gl, *s).tex);
  }
  arr_tex_.clear();
  shapes_.clear();
  for (auto* arr : a.arrays) {
    arr_tex_.push_back(be_.to_device(gl, *arr).tex);
    shapes_.insert(shapes_.end(),
                   {static_cast<GLint>(arr->shape[0]), static_cast<GLint>(arr->shape[1]),
                    static_cast<GLint>(arr->shape[2])});
  }
  words_.clear();
  for (auto* u : a.uniforms) words_.insert(words_.end(), u->bits.begin(), u->bits.end());
  be_.check(gl, "preparing a launch");

  const Shape shape = out_tex_.empty() ? shape_of(a.count) : out_tex_[0]->shape;
  GLuint written = 0;
  gl.glBindFramebuffer(GL_FRAMEBUFFER, be_.fbo());
  gl.glBindVertexArray(be_.vao());
  gl.glViewport(0, 0, shape.row, shape.rows);
  // After a masked launch (also one that throws), the stencil test is off and the stencil
  // buffer detached again, so it cannot clip or mask the next launch.
  struct StencilOff {
    const GL& gl;
    GLuint fbo;
    bool active;
    ~StencilOff() {
      if (!active) return;
      gl.glBindFramebuffer(GL_FRAMEBUFFER, fbo);
      gl.glDisable(GL_STENCIL_TEST);
      gl.glStencilMask(0xff);
      gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, 0);
      gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
  } stencil_off{gl, be_.fbo(), a.mask != nullptr};
  const bool guarded = be_.driver().rules.loop_guard;
  if (guarded) {  // cleared, then set by any lane that saw a loop cut short
    const GLuint zero = 0;
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, be_.guard(gl));
    gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, &zero);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGuardBinding, be_.guard(gl));
  }
  KernelTimer::Running timed = be_.timer().start(gl);
  const int64_t selected = a.mask ? draw_mask(gl, a, shape) : a.count;
  for (size_t pi = 0; pi < passes_.size(); ++pi) {
    const Pass& p = passes_[pi];
    const Locations& l = p.loc;
    draw_bufs_.clear();
    for (size_t k = 0; k < p.outputs.size(); ++k) {
      gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k),
                                GL_TEXTURE_2D, out_tex_[static_cast<size_t>(p.outputs[k])]->tex, 0);
      draw_bufs_.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k));
    }
    gl.glDrawBuffers(static_cast<GLsizei>(draw_bufs_.size()), draw_bufs_.data());
    if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw Error("GLSL backend: the output textures of kernel '" + fn_.name +
                  "' do not form a complete framebuffer");
    gl.glUseProgram(p.program);
    // Texture units in order: inputs, this pass's outputs' previous values, arrays; a unit is
    // skipped (left unbound) where the program does not use the texture.
    GLint unit = 0;
    auto bind = [&](GLint loc, GLuint tex) {
      if (loc >= 0) {
        gl.glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
        gl.glBindTexture(GL_TEXTURE_2D, tex);
        gl.glUniform1i(loc, unit);
      }
      ++unit;
    };
    for (size_t i = 0; i < in_tex_.size(); ++i) bind(l.in[i], in_tex_[i]);
    for (size_t k = 0; k < p.outputs.size(); ++k)
      bind(l.prev[k], prev_[static_cast<size_t>(p.outputs[k])]);
    for (size_t i = 0; i < arr_tex_.size(); ++i) bind(l.arr[i], arr_tex_[i]);
    set_kernel_uniforms(gl, l, a.count, a.width, words_, p.constants, shapes_);
    if (l.row >= 0) gl.glUniform1i(l.row, shape.row);
    if (pi == 0) gl.glBeginQuery(GL_SAMPLES_PASSED, be_.query());
    gl.glDrawArrays(GL_TRIANGLES, 0, 3);
    if (pi == 0) {
      gl.glEndQuery(GL_SAMPLES_PASSED);
      gl.glGetQueryObjectuiv(be_.query(), GL_QUERY_RESULT, &written);
    }
    for (size_t k = 0; k < p.outputs.size(); ++k)
      gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k),
                                GL_TEXTURE_2D, 0, 0);
  }
  const double device_ms = timed.end_ms();
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  be_.check(gl, "running a kernel");
  // The draws wrote the outputs' textures: their host copies are stale until read back.
  for (auto* s : a.outputs) s->mark_device_written(&be_);
  if (guarded) {
    GLuint cut = 0;
    gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, be_.guard(gl));
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof cut, &cut);
    if (cut != 0) throw Error(loop_cut_message("GLSL backend", fn_.name, be_.driver().renderer));
  }
  return {written, selected, device_ms};
}

}  // namespace

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<GLSLBackend>();
}

}  // namespace rill::glsl
