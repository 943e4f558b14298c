// The glsl-compute backend's launcher role (ComputeLauncher.h).
#include "ComputeLauncher.h"

#include <algorithm>
#include <cstring>

#include "../codegen/Tiles.h"
#include "GLSLEmitter.h"
#include "GLSession.h"
#include "KernelTimer.h"

namespace rill::glsl {

void ComputeKernel::check_limits(const LaunchArgs& a) const {
  const Limits& lim = device_.limits;
  auto too_big = [&](const detail::Storage& s, const std::string& what) {
    const GLint64 bytes = static_cast<GLint64>(s.words()) * 4;
    if (bytes > lim.block_bytes)
      throw Error(std::string(kComputeWho) + ": kernel '" + fn_.name + "': " + what + " holds " +
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
      throw Error(std::string(kComputeWho) + ": kernel '" + fn_.name + "': array '" + arr->name +
                  "' has " + std::to_string(arr->count()) +
                  " elements, over the driver's limit for a buffer texture " +
                  "(GL_MAX_TEXTURE_BUFFER_SIZE, " + std::to_string(lim.texels) + ")");
}

void ComputeKernel::dispatch(const GL& gl, Pass& p, const LaunchArgs& a,
                             const std::vector<GLuint>& inputs, GLuint mask) {
  Locations& loc = p.loc;
  if (!p.located) {
    auto at = [&](const char* name) { return gl.glGetUniformLocation(p.program, name); };
    locate_kernel_uniforms(loc, at);
    loc.tiled = at("rill_tiled");
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
                        buffers_.to_device(gl, *a.outputs[static_cast<size_t>(p.outputs[k])]).buf);
  gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(bind.counts), device_.counter);
  gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(bind.mask), mask);
  gl.glUseProgram(p.program);
  set_kernel_uniforms(gl, loc, a.count, a.width, words_, p.constants, shapes_);
  if (loc.nvalues >= 0)
    gl.glUniform1i(loc.nvalues, a.mask ? static_cast<GLint>(a.mask_values.size()) : 0);
  if (a.mask && loc.values >= 0)
    gl.glUniform1iv(loc.values, static_cast<GLsizei>(a.mask_values.size()), a.mask_values.data());
  // 2D launches run in 8 x 4 tiles (GLSLEmitter.cpp) unless RILL_GLSL_TILES=off.
  const bool tiled = device_.tiles && a.height > 1 && !a.warm_up;
  if (loc.tiled >= 0) gl.glUniform1i(loc.tiled, tiled ? 1 : 0);
  const int64_t span = tiled ? codegen::tiled_invocations(a.width, a.height) : a.count;
  check(gl, "preparing a launch", kComputeWho);
  // Groups over a 2D grid: x up to the driver's limit, y as many rows of them as needed.
  const int64_t groups = std::max<int64_t>(1, (span + local_size_ - 1) / local_size_);
  const int64_t gx = std::min<int64_t>(groups, device_.limits.groups_x);
  const int64_t gy = (groups + gx - 1) / gx;
  gl.glDispatchCompute(static_cast<GLuint>(gx), static_cast<GLuint>(gy), 1);
  gl.glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT |
                     GL_BUFFER_UPDATE_BARRIER_BIT);
}

LaunchResult ComputeKernel::run(const LaunchArgs& a) {
  if (a.count == 0 && !a.warm_up) return {0, 0, 0.0};  // nothing ran
  if (a.count > INT32_MAX)
    throw Error(std::string(kComputeWho) + ": kernel '" + fn_.name + "': " +
                std::to_string(a.count) + " elements, over the 2^31 - 1 a launch can number");
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
    GLuint buf = buffers_.to_device(gl, *s).buf;
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
  const GLuint mask = a.mask ? readable(a.mask) : device_.counter;
  shapes_.clear();
  for (size_t i = 0; i < a.arrays.size(); ++i) {
    detail::ArrayState* arr = a.arrays[i];
    gl.glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(i));
    gl.glBindTexture(GL_TEXTURE_BUFFER, buffers_.texture_of(gl, *arr));
    shapes_.insert(shapes_.end(),
                   {static_cast<GLint>(arr->shape[0]), static_cast<GLint>(arr->shape[1]),
                    static_cast<GLint>(arr->shape[2])});
  }
  words_.clear();
  for (auto* u : a.uniforms) words_.insert(words_.end(), u->bits.begin(), u->bits.end());
  const GLuint zero[3] = {0, 0, 0};
  gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, device_.counter);
  gl.glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
  // The outputs' buffers made current first (dispatch() binds them): the timer covers the
  // dispatches only, and nothing that may switch contexts (a read-back through the other GL
  // backend) runs while its query is active.
  for (auto* s : a.outputs) buffers_.to_device(gl, *s);
  KernelTimer::Running timed = be_.timer().start(gl);
  for (Pass& p : passes_) dispatch(gl, p, a, in_buf_, mask);
  GLuint counts[3] = {0, 0, 0};  // written, selected, loops cut (DriverRules::loop_guard)
  gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, device_.counter);
  gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counts,
                        counts);  // waits for the dispatches
  double device_ms = timed.end_ms();
  if (!device_.times_dispatches) device_ms = -1;
  check(gl, "running a kernel", kComputeWho);
  for (auto* s : a.outputs) s->mark_device_written(&be_);  // written, if cut short (below)
  if (counts[2] != 0) throw Error(loop_cut_message(kComputeWho, fn_.name, be_.driver().renderer));
  return {counts[0], a.mask ? static_cast<int64_t>(counts[1]) : a.count, device_ms};
}

}  // namespace rill::glsl
