// The GL context, exit handling and program linking both GLSL backends share (GLSession.h).
#include "GLSession.h"

#include "DriverProbes.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>

#include "../cache/DiskCache.h"
#include "../codegen/SourceText.h"
#include "rill/Error.h"

namespace rill::glsl {

const GL* Session::current_if_alive() noexcept {
  if (!context) return nullptr;
  try {
    context->make_current();
  } catch (const Error&) {
    return nullptr;
  }
  return &context->gl();
}

Driver describe_driver(const GL& gl, const std::string& renderer_line) {
  auto str = [&](GLenum e) {
    const GLubyte* s = gl.glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  Driver d;
  d.vendor = str(GL_VENDOR);
  d.renderer = str(GL_RENDERER);
  d.version = str(GL_VERSION);
  gl.glGetIntegerv(GL_MAJOR_VERSION, &d.major);
  gl.glGetIntegerv(GL_MINOR_VERSION, &d.minor);
  gl.glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &d.binary_formats);
  d.rules.divsqrt = divsqrt_mode(renderer_line);
  // Probed only where it matters: the corrections run, and the context has compute shaders.
  const std::optional<bool> fused = fused_fma_mode();
  const bool probe = !fused && divsqrt_corrects(d.rules.divsqrt) &&
                     (d.major > 4 || (d.major == 4 && d.minor >= 3));
  d.rules.fused_fma = fused ? *fused : probe && probe_fused_fma(gl, d, "GLSL backend");
  d.rules.lean = lean_fused_mode();
  d.rules.native_compare = native_compare_mode(renderer_line);
  d.rules.loop_guard = loop_guard_mode(renderer_line);
  return d;
}

bool native_compare_mode(const std::string& renderer) {
  const char* env = std::getenv("RILL_GLSL_COMPARE");
  const std::string v = env ? env : "auto";
  if (v == "auto" || v.empty()) return renderer.find("NVIDIA") != std::string::npos;
  if (v == "native") return true;
  if (v == "bits") return false;
  throw Error("RILL_GLSL_COMPARE='" + v + "' is not one of auto, native, bits");
}

bool is_llvmpipe(const std::string& renderer) {
  return renderer.find("llvmpipe") != std::string::npos;
}

bool warm_up_pays(const std::string& renderer, const ir::Function& f) {
  const bool reads_textures = !f.inputs.empty() || !f.arrays.empty();
  return !(reads_textures && is_llvmpipe(renderer));
}

bool loop_guard_mode(const std::string& renderer) {
  return is_llvmpipe(renderer);
}

std::string loop_cut_message(const std::string& backend, const std::string& kernel,
                             const std::string& renderer) {
  return backend + ": kernel '" + kernel + "' ran longer loops than the driver (" + renderer +
         ") runs: Mesa's llvmpipe ends every loop of a shader once a batch of lanes has run " +
         "65535 loop iterations in all (LP_MAX_TGSI_LOOP_ITERATIONS), so this launch's results " +
         "are cut short. Run the kernel on cpu, simd or opencl, or on a GPU's GL driver, or " +
         "split its work into launches of fewer iterations per element";
}

bool is_software_renderer(const std::string& renderer) {
  for (const char* cpu : {"llvmpipe", "softpipe", "swrast", "SwiftShader"})
    if (renderer.find(cpu) != std::string::npos) return true;
  return false;
}

const char* compare_name(bool native) {
  return native ? "native" : "bits";
}

std::string Driver::cache_identity() const {
  return "vendor=" + vendor + "\nrenderer=" + renderer + "\ndriver=" + version + "\n";
}

std::string Driver::version_text() const {
  return std::to_string(major) + "." + std::to_string(minor) + " (" + version + ")";
}

// The owners that have made a context, for the exit handler. Globals, constructed before
// main: they are destroyed after every exit handler registered later has run.
namespace {
std::mutex g_live_mutex;
std::vector<SessionOwner*> g_live;

void shut_down_live_owners() {
  std::vector<SessionOwner*> live;
  {
    std::lock_guard<std::mutex> lock(g_live_mutex);
    live.swap(g_live);
  }
  for (SessionOwner* o : live) o->shutdown();
}
}  // namespace

void shut_down_at_exit(SessionOwner* owner) {
  static std::once_flag registered;
  {
    std::lock_guard<std::mutex> lock(g_live_mutex);
    g_live.push_back(owner);
  }
  std::call_once(registered, [] { std::atexit(shut_down_live_owners); });
}

void forget_at_exit(SessionOwner* owner) {
  std::lock_guard<std::mutex> lock(g_live_mutex);
  g_live.erase(std::remove(g_live.begin(), g_live.end(), owner), g_live.end());
}

void check(const GL& gl, const char* what, const char* backend) {
  GLenum e = gl.glGetError();
  if (e == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "%04x", e);
  throw Error(std::string(backend) + ": OpenGL error 0x" + code + " while " + what);
}

GLuint link_program(const GL& gl, const Driver& d, const std::string& backend,
                    const std::string& kernel, const std::vector<ShaderSource>& shaders) {
  // The source shown with an error: the last stage (the kernel's; the vertex shader that
  // precedes a fragment shader is fixed).
  const std::string& main_source = shaders.back().text;
  GLuint prog = gl.glCreateProgram();
  if (d.binary_formats > 0)
    gl.glProgramParameteri(prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  for (const ShaderSource& s : shaders) {
    GLuint sh = gl.glCreateShader(s.stage);
    const char* text = s.text.c_str();
    gl.glShaderSource(sh, 1, &text, nullptr);
    gl.glCompileShader(sh);
    GLint ok = 0;
    gl.glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint n = 0;
      gl.glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &n);
      std::string log(static_cast<size_t>(std::max(n, 1)), '\0');
      gl.glGetShaderInfoLog(sh, n, nullptr, log.data());
      gl.glDeleteShader(sh);
      gl.glDeleteProgram(prog);
      throw Error(backend + ": the driver (" + d.renderer + ", OpenGL " + d.version +
                  ") rejected the shader of kernel '" + kernel + "':\n" + log +
                  "\ngenerated source:\n" + codegen::numbered(s.text));
    }
    gl.glAttachShader(prog, sh);
    gl.glDeleteShader(sh);  // deleted with the program
  }
  gl.glLinkProgram(prog);
  GLint ok = 0;
  gl.glGetProgramiv(prog, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint n = 0;
    gl.glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &n);
    std::string log(static_cast<size_t>(std::max(n, 1)), '\0');
    gl.glGetProgramInfoLog(prog, n, nullptr, log.data());
    gl.glDeleteProgram(prog);
    throw Error(backend + ": linking kernel '" + kernel + "' failed (" + d.renderer + "):\n" + log +
                "\ngenerated source:\n" + codegen::numbered(main_source));
  }
  return prog;
}

GLuint link_program_cached(const GL& gl, const Driver& d, const std::string& cache_name,
                           const std::string& backend, const std::string& kernel,
                           const std::vector<ShaderSource>& shaders, bool& from_cache) {
  from_cache = false;
  // No binary format (Mesa without its shader cache): compile every time.
  if (d.binary_formats <= 0) return link_program(gl, d, backend, kernel, shaders);
  std::string all;
  for (const ShaderSource& s : shaders) all += s.text + "\n";
  const std::string key =
      "backend=" + cache_name + "\n" + d.cache_identity() + cache::source_line(all);
  std::optional<std::string> binary = cache::load(cache_name, key);
  if (binary && binary->size() > sizeof(GLenum)) {
    GLenum format = 0;
    std::memcpy(&format, binary->data(), sizeof format);
    GLuint prog = gl.glCreateProgram();
    gl.glProgramBinary(prog, format, binary->data() + sizeof format,
                       static_cast<GLsizei>(binary->size() - sizeof format));
    GLint ok = 0;
    gl.glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    // A format this driver does not know raises GL_INVALID_ENUM: a refused binary.
    for (int i = 0; i < 8 && gl.glGetError() != GL_NO_ERROR; ++i) ok = 0;
    if (ok) {
      from_cache = true;
      return prog;
    }
    gl.glDeleteProgram(prog);
    cache::remove(cache_name, key);
  }
  GLuint prog = link_program(gl, d, backend, kernel, shaders);
  GLint length = 0;
  gl.glGetProgramiv(prog, GL_PROGRAM_BINARY_LENGTH, &length);
  if (length > 0) {
    std::string payload(sizeof(GLenum) + static_cast<size_t>(length), '\0');
    GLenum format = 0;
    GLsizei got = 0;
    gl.glGetProgramBinary(prog, length, &got, &format, payload.data() + sizeof format);
    if (gl.glGetError() == GL_NO_ERROR && got > 0) {
      std::memcpy(payload.data(), &format, sizeof format);
      payload.resize(sizeof format + static_cast<size_t>(got));
      cache::store(cache_name, key, payload);
    }
  }
  return prog;
}

}  // namespace rill::glsl
