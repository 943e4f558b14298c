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
// The roles, each in its own file: the device memory (FragmentTextures.h: textures, the copy
// pool, stencil buffers), the launcher (FragmentLauncher.h: a kernel's draws, and the GL
// objects they use); this file is the compiler (emit_glsl, then link_program_cached) and the
// Backend interface over them. The context, its shutdown at exit and the disk cache of program
// binaries: GLBackend.h and GLSession.h.
#include "GLSLBackend.h"

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <vector>

#include "../codegen/SourceMap.h"
#include "FragmentLauncher.h"
#include "FragmentTextures.h"
#include "GLBackend.h"
#include "GLSLEmitter.h"
#include "GLSession.h"
#include "rill/Stopwatch.h"

namespace rill::glsl {

namespace {

class GLSLBackend : public GLBackend {
 public:
  GLSLBackend() : GLBackend("GLSL backend"), textures_(*this, session_) {}
  // Backends live in the registry until exit; the exit handler has normally shut this one
  // down by then.
  ~GLSLBackend() override;

  std::string name() const override { return "glsl"; }

  std::string description() const override {
    std::string why = unavailable_reason();
    if (!why.empty()) return "glsl: unavailable: " + why;
    auto* self = const_cast<GLSLBackend*>(this);
    return "glsl: fragment shaders; " + self->context().kind() + ", " + self->context().renderer +
           "; strict / and sqrt: " +
           divsqrt_description(self->driver_.rules.divsqrt, self->driver_.rules.fused_fma,
                               self->driver_.rules.lean) +
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
      GLSLShader shader = emit_glsl(f, o.accuracy, p.outputs, driver_.rules, o.source_map);
      codegen_ms += stage.lap();
      p.source = std::move(shader.source);
      p.constants = std::move(shader.constants);
      bool cached = false;
      p.program = codegen::reporting_user_lines(
          p.source, [&] { return emit_glsl(f, o.accuracy, p.outputs, driver_.rules, true).source; },
          [&] {
            return link_program_cached(
                gl, driver_, "glsl", "GLSL backend", f.name,
                {{GL_VERTEX_SHADER, vertex_shader()}, {GL_FRAGMENT_SHADER, p.source}}, cached);
          });
      all_cached = all_cached && cached;
      link_ms += stage.lap();
      passes.push_back(std::move(p));
    }
    auto kernel =
        std::make_unique<GLSLKernel>(*this, textures_, objects_, session_, f, std::move(passes));
    kernel->set_origin(all_cached ? KernelOrigin::DiskCache : KernelOrigin::Built);
    kernel->set_build_times(codegen_ms, link_ms);
    return kernel;
  }

  void read_back(const detail::Storage& s, uint32_t* host) override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    textures_.read_back(current(), s, host);
  }

  // Deletes the backend's GL objects and destroys the context (see GLSession.h): called by the
  // exit handler and the destructor, from any thread; the second call does nothing. Objects
  // it cannot delete (the context not current here) go with the context.
  void shutdown() noexcept override {
    std::lock_guard<std::recursive_mutex> lock(mutex());
    const GL* gl = session_->current_if_alive();
    textures_.release(gl);
    objects_.release(gl);
    if (gl) timer_.destroy(*gl);
    session_->context.reset();  // destroys the GL context (GLContext.cpp)
  }

 private:
  void set_up(const GL& gl, GLContext&) override {
    GLint draw = 1, attach = 1;
    gl.glGetIntegerv(GL_MAX_DRAW_BUFFERS, &draw);
    gl.glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &attach);
    max_draw_buffers_ = std::min(draw, attach);
    if (const char* force = std::getenv("RILL_GL_MAX_DRAW_BUFFERS"))  // to test pass splitting
      max_draw_buffers_ = std::clamp(std::atoi(force), 1, max_draw_buffers_);
    objects_.create(gl);
    gl.glDisable(GL_DITHER);
    gl.glDisable(GL_BLEND);
    gl.glDisable(GL_DEPTH_TEST);
  }

  int max_draw_buffers_ = 1;
  FragmentTextures textures_;
  FragmentObjects objects_;
};

GLSLBackend::~GLSLBackend() {
  forget_at_exit(this);
  shutdown();
}

}  // namespace

std::unique_ptr<Backend> make_backend() {
  return std::make_unique<GLSLBackend>();
}

}  // namespace rill::glsl
