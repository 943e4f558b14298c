// The GLSL backend's launcher role: a kernel's programs (one per group of outputs that fits
// the context's draw buffers) drawn over its outputs' textures. A launch binds the inputs and
// arrays as textures, each output as a colour attachment (a discarded fragment leaves its texel
// as it was), the previous values the kernel reads from copies taken before the draw (no
// texture is read while it is rendered to), and counts the fragments written with an
// occlusion query. A masked launch first draws the mask shader into the stencil buffer and then
// the kernel with the stencil test on (early stencil: masked elements cost close to nothing).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "FragmentTextures.h"
#include "GLBackend.h"
#include "WarmUpLaunch.h"
#include "rill/Backend.h"
#include "rill/ir/IR.h"

namespace rill::glsl {

// The GL objects every launch draws with: made when the context is set up (create), the loop
// guard's word and the mask shader at the first launch that needs them, and deleted at
// shutdown (release).
struct FragmentObjects {
  GLuint fbo = 0, vao = 0, query = 0;
  int max_texture_units = 16;
  void create(const GL& gl);
  // DriverRules::loop_guard's word (kGuardBinding).
  GLuint guard(const GL& gl);
  // The shader that turns a state texture into the stencil mask: it keeps (does not
  // discard) the elements whose state is one of rill_values[0 .. rill_nvalues).
  GLuint mask_program(const GL& gl, const Driver& driver);
  // Deletes them (gl null: the context is gone, and they with it).
  void release(const GL* gl) noexcept;

 private:
  GLuint guard_ = 0, mask_program_ = 0;
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
  GLSLKernel(GLBackend& be, FragmentTextures& textures, FragmentObjects& objects,
             std::shared_ptr<Session> session, ir::Function f, std::vector<Pass> passes)
      : be_(be),
        textures_(textures),
        objects_(objects),
        session_(std::move(session)),
        fn_(std::move(f)),
        passes_(std::move(passes)) {
    for (const Pass& p : passes_) source_ += p.source;
  }
  ~GLSLKernel() override;
  LaunchResult run(const LaunchArgs& a) override;
  const std::string& source() const override { return source_; }
  // llvmpipe compiles a shader's variant for the bound texture and framebuffer formats at
  // its first draw: one draw over one texel that the shader discards (rill_count 0) does it
  // now, where that variant is the one real launches use (warm_up_pays). (A masked launch,
  // with the stencil test on, is another variant, built at the first.)
  void warm_up() override {
    if (warm_up_pays(be_.driver().renderer, fn_)) run(WarmUpLaunch(fn_).args());
  }

 private:
  // Masked launches: fills the stencil buffer from a.mask; returns the elements selected.
  GLuint draw_mask(const GL& gl, const LaunchArgs& a, const Shape& shape);
  // Fills every pass's Locations and reads_prev_ (at the first launch).
  void locate(const GL& gl, const LaunchArgs& a);

  // run() is only called while the backend exists, and with it its textures and objects.
  GLBackend& be_;
  FragmentTextures& textures_;
  FragmentObjects& objects_;
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

}  // namespace rill::glsl
