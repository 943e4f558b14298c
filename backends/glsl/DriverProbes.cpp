// The driver probes (see DriverProbes.h).
#include "DriverProbes.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace rill::glsl {

std::vector<float> run_probe(const GL& gl, const Driver& d, const char* backend,
                             const std::string& kernel, const std::string& main_body,
                             std::vector<float> data) {
  GLuint prog = link_program(gl, d, backend, kernel,
                             {{GL_COMPUTE_SHADER,
                               "#version 430 core\n"
                               "layout(local_size_x = 1) in;\n"
                               "layout(std430, binding = 0) buffer B { float v[]; } b;\n"
                               "void main() {\n" +
                                   main_body + "}\n"}});
  const GLsizeiptr bytes = static_cast<GLsizeiptr>(data.size() * sizeof(float));
  GLuint buf = 0;
  gl.glGenBuffers(1, &buf);
  gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buf);
  gl.glBufferData(GL_SHADER_STORAGE_BUFFER, bytes, data.data(), GL_DYNAMIC_COPY);
  gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buf);
  gl.glUseProgram(prog);
  gl.glDispatchCompute(1, 1, 1);
  gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, data.data());
  gl.glUseProgram(0);
  gl.glDeleteProgram(prog);
  gl.glDeleteBuffers(1, &buf);
  check(gl, ("running the driver probe " + kernel).c_str(), backend);
  return data;
}

bool probe_flushes_denormals(const GL& gl, const Driver& d, const char* backend) {
  const std::vector<float> out =
      run_probe(gl, d, backend, "rill_denormal_probe", "  b.v[1] = b.v[0] * 2.0;\n",
                {std::numeric_limits<float>::denorm_min(), 1.0f, 0, 0});
  return out[1] == 0.0f;
}

namespace {

// (x, y, z) triples whose exact x*y needs more than 24 bits, so that a product rounded before
// the sum gives another result: 1 + 2^-23 times 1 - 2^-24 is 1 + 2^-24 - 2^-47 (rounded: 1),
// then the corrections' own case, a quotient's residual (1/3 rounded, times 3, from 1).
constexpr int kCases = 4;
const float kX[kCases] = {1.00000012f, 0.333333343f, 1.5f, 0.99999994f};
const float kY[kCases] = {0.99999994f, 3.0f, 1.00000012f, 0.99999994f};
const float kZ[kCases] = {1.0f, 1.0f, 1.5f, 0.99999988f};

}  // namespace

std::vector<float> fma_probe_data() {
  std::vector<float> data(4 * kCases, 0.0f);
  for (int i = 0; i < kCases; ++i) {
    data[static_cast<size_t>(i)] = kX[i];
    data[static_cast<size_t>(kCases + i)] = kY[i];
    data[static_cast<size_t>(2 * kCases + i)] = kZ[i];
  }
  return data;
}

const char* const kFmaProbeBody =
    "  for (int i = 0; i < 4; ++i) {\n"
    "    precise float r = fma(-b.v[i], b.v[4 + i], b.v[8 + i]);\n"
    "    b.v[12 + i] = r;\n"
    "  }\n";

bool fma_probe_fused(const std::vector<float>& out) {
  if (out.size() < static_cast<size_t>(4 * kCases)) return false;
  for (int i = 0; i < kCases; ++i) {
    const float want = std::fma(-kX[i], kY[i], kZ[i]);
    if (std::memcmp(&want, &out[static_cast<size_t>(3 * kCases + i)], sizeof want) != 0)
      return false;
  }
  return true;
}

bool probe_fused_fma(const GL& gl, const Driver& d, const char* backend) {
  return fma_probe_fused(
      run_probe(gl, d, backend, "rill_fma_probe", kFmaProbeBody, fma_probe_data()));
}

}  // namespace rill::glsl
