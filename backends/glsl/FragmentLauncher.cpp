// The GLSL backend's launcher role (FragmentLauncher.h).
#include "FragmentLauncher.h"

#include <algorithm>

#include "GLSession.h"
#include "KernelTimer.h"
#include "rill/StateMask.h"

namespace rill::glsl {

void FragmentObjects::create(const GL& gl) {
  GLint units = 16;
  gl.glGetIntegerv(GL_MAX_TEXTURE_IMAGE_UNITS, &units);
  max_texture_units = units;
  gl.glGenFramebuffers(1, &fbo);
  gl.glGenVertexArrays(1, &vao);
  gl.glGenQueries(1, &query);
}

GLuint FragmentObjects::guard(const GL& gl) {
  if (!guard_) {
    gl.glGenBuffers(1, &guard_);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, guard_);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, 16, nullptr, GL_DYNAMIC_READ);
  }
  return guard_;
}
GLuint FragmentObjects::mask_program(const GL& gl, const Driver& driver) {
  if (mask_program_ == 0)
    mask_program_ =
        link_program(gl, driver, "GLSL backend", "rill_mask",
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

void FragmentObjects::release(const GL* gl) noexcept {
  if (gl) {
    if (mask_program_) gl->glDeleteProgram(mask_program_);
    gl->glDeleteQueries(1, &query);
    if (guard_) gl->glDeleteBuffers(1, &guard_);
    gl->glDeleteVertexArrays(1, &vao);
    gl->glDeleteFramebuffers(1, &fbo);
  }
  fbo = vao = query = mask_program_ = guard_ = 0;
}

// Destroyed with the kernel cache, possibly after the backend and the context are gone.
GLSLKernel::~GLSLKernel() {
  std::lock_guard<std::recursive_mutex> lock(session_->mutex);
  if (const GL* gl = session_->current_if_alive())
    for (Pass& p : passes_) gl->glDeleteProgram(p.program);
}

GLuint GLSLKernel::draw_mask(const GL& gl, const LaunchArgs& a, const Shape& shape) {
  GLuint state = textures_.to_device(gl, *a.mask).tex;
  gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                               textures_.stencil(gl, shape));
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
  GLuint prog = objects_.mask_program(gl, be_.driver());
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
  gl.glBeginQuery(GL_SAMPLES_PASSED, objects_.query);
  gl.glDrawArrays(GL_TRIANGLES, 0, 3);
  gl.glEndQuery(GL_SAMPLES_PASSED);
  gl.glGetQueryObjectuiv(objects_.query, GL_QUERY_RESULT, &selected);
  // The kernel's draws: only where the mask wrote 1, and the stencil stays as it is.
  gl.glStencilMask(0);
  gl.glStencilFunc(GL_EQUAL, 1, 0xff);
  gl.glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  glsl::check(gl, "building the mask of a masked launch");
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
    locate_kernel_uniforms(l, at);
    l.row = at("rill_row");
  }
  located_ = true;
}

LaunchResult GLSLKernel::run(const LaunchArgs& a) {
  if (a.count == 0 && !a.warm_up) return {0, 0, 0.0};  // nothing ran
  if (a.count > kTextureRow * kTextureRow)
    throw Error("GLSL backend: streams are limited to 4096 x 4096 elements");
  std::lock_guard<std::recursive_mutex> lock(be_.mutex());
  const GL& gl = be_.current();
  size_t widest = 0;
  for (const Pass& p : passes_) widest = std::max(widest, p.outputs.size());
  const int units = static_cast<int>(a.inputs.size() + widest + a.arrays.size());
  if (units > objects_.max_texture_units)
    throw Error("GLSL backend: kernel '" + fn_.name + "' reads " + std::to_string(units) +
                " textures but the context has " + std::to_string(objects_.max_texture_units) +
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
    FragmentTextures& textures;
    const GL& gl;
    std::vector<Texture*>& out;
    std::vector<GLuint>& prev;
    ~GiveBack() {
      for (size_t i = 0; i < prev.size(); ++i)
        if (prev[i]) textures.give_back_copy(gl, out[i]->fmt, out[i]->shape, prev[i]);
    }
  } give_back{textures_, gl, out_tex_, prev_};
  for (size_t o = 0; o < a.outputs.size(); ++o) {
    detail::StreamState* s = a.outputs[o];
    Texture& t = textures_.to_device(gl, *s);
    out_tex_.push_back(&t);
    const bool also_input = std::find(a.inputs.begin(), a.inputs.end(), s) != a.inputs.end();
    GLuint copy = 0;
    if (reads_prev_[o] || also_input) {
      copy = textures_.take_copy(gl, t.fmt, t.shape);
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
                                            : textures_.to_device(gl, *s).tex);
  }
  arr_tex_.clear();
  shapes_.clear();
  for (auto* arr : a.arrays) {
    arr_tex_.push_back(textures_.to_device(gl, *arr).tex);
    shapes_.insert(shapes_.end(),
                   {static_cast<GLint>(arr->shape[0]), static_cast<GLint>(arr->shape[1]),
                    static_cast<GLint>(arr->shape[2])});
  }
  words_.clear();
  for (auto* u : a.uniforms) words_.insert(words_.end(), u->bits.begin(), u->bits.end());
  glsl::check(gl, "preparing a launch");

  const Shape shape = out_tex_.empty() ? shape_of(a.count) : out_tex_[0]->shape;
  GLuint written = 0;
  gl.glBindFramebuffer(GL_FRAMEBUFFER, objects_.fbo);
  gl.glBindVertexArray(objects_.vao);
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
  } stencil_off{gl, objects_.fbo, a.mask != nullptr};
  const bool guarded = be_.driver().rules.loop_guard;
  if (guarded) {  // cleared, then set by any lane that saw a loop cut short
    const GLuint zero = 0;
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, objects_.guard(gl));
    gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, &zero);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kGuardBinding, objects_.guard(gl));
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
    if (pi == 0) gl.glBeginQuery(GL_SAMPLES_PASSED, objects_.query);
    gl.glDrawArrays(GL_TRIANGLES, 0, 3);
    if (pi == 0) {
      gl.glEndQuery(GL_SAMPLES_PASSED);
      gl.glGetQueryObjectuiv(objects_.query, GL_QUERY_RESULT, &written);
    }
    for (size_t k = 0; k < p.outputs.size(); ++k)
      gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(k),
                                GL_TEXTURE_2D, 0, 0);
  }
  const double device_ms = timed.end_ms();
  gl.glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glsl::check(gl, "running a kernel");
  // The draws wrote the outputs' textures: their host copies are stale until read back.
  for (auto* s : a.outputs) s->mark_device_written(&be_);
  if (guarded) {
    GLuint cut = 0;
    gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, objects_.guard(gl));
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof cut, &cut);
    if (cut != 0) throw Error(loop_cut_message("GLSL backend", fn_.name, be_.driver().renderer));
  }
  return {written, selected, device_ms};
}

}  // namespace rill::glsl
