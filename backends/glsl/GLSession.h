// What both GLSL backends (the fragment stage, `glsl`, and the compute stage,
// `glsl-compute`) need from OpenGL besides their kernels: a context shared with their
// kernels and device buffers, shut down before the GL library's own exit handlers run, and
// programs linked from source or loaded from Rill's disk cache of program binaries.
//
// Why the context is shared, and why backends shut down explicitly: at exit, static
// destructors run in an order of their own (the kernel cache, the backend registry, streams
// and arrays kept in statics), and the GL library, loaded with dlopen at first use, tears
// itself down from its own exit handlers. So:
//   - right after a backend makes its context (the library is loaded by then), it registers
//     an exit handler (std::atexit, through shut_down_at_exit). Exit handlers run
//     last-registered first, so this one runs before every handler the library registered
//     while loading and making the context; it calls the backend's shutdown(), which deletes
//     the backend's GL objects and destroys the context while GL still works. A handler the
//     driver registers later still runs first: Mesa's thread queues register theirs at their
//     first use (a shader compile, say) and only stop their threads there, after which
//     destroying the context is still safe;
//   - a device buffer or kernel destroyed after that (or after the backend itself) holds the
//     Session, not the backend: it finds `context` null under the lock and skips its GL
//     calls. Destroying the context already freed every object made in it.
//
// The disk cache (cache/DiskCache.h) keeps each linked program as a program binary
// (glGetProgramBinary), keyed by GL_VENDOR, GL_RENDERER, GL_VERSION and the shaders' source,
// and loads it with glProgramBinary; a binary the driver refuses (GL_LINK_STATUS false) is
// removed and the shaders compiled again. Drivers that offer no binary format
// (GL_NUM_PROGRAM_BINARY_FORMATS 0) always compile: Mesa offers one only while its own shader
// disk cache is on, so with MESA_SHADER_CACHE_DISABLE=true (.ci/run) nothing is cached.
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "DivSqrt.h"
#include "GLContext.h"
#include "GLSLEmitter.h"

namespace rill::glsl {

struct Session {
  // Recursive: replacing a stream's device buffer inside a launch releases the old one.
  std::recursive_mutex mutex;
  std::unique_ptr<GLContext> context;  // null before the first use and after shutdown

  // Under the lock: the context, made current on this thread; null after shutdown. Never
  // throws (for destructors): null also when the context cannot be made current here.
  const GL* current_if_alive() noexcept;
};

// What a backend learns about the driver when it makes its context.
struct Driver {
  std::string vendor, renderer, version;  // GL_VENDOR, GL_RENDERER, GL_VERSION
  int major = 0, minor = 0;               // the context's GL version
  GLint binary_formats = 0;  // GL_NUM_PROGRAM_BINARY_FORMATS: 0, no disk cache of programs
  DriverRules rules;         // how strict kernels divide and compare here (GLSLEmitter.h)
  std::string cache_identity() const;  // the driver, as disk cache key lines
  std::string version_text() const;    // "4.5 (Mesa 22.3.6)"
};
Driver describe_driver(const GL& gl, const std::string& renderer_line);

// RILL_GLSL_COMPARE = auto (default) | native | bits: how strict kernels compare floats.
// auto: native on NVIDIA's driver (its comparisons pass the strict conformance suite, NaN,
// signed zeros and denormals included, and cost far less), on bit patterns elsewhere
// (Mesa may rewrite comparisons as if there were no NaN). Throws on an unknown value.
bool native_compare_mode(const std::string& renderer);
const char* compare_name(bool native);  // "native", "bits"
// DriverRules::loop_guard: on for Mesa's llvmpipe, whose loop limit it catches, off elsewhere
// (a GPU's driver has no such limit, and the guard's read-back would cost each launch).
bool loop_guard_mode(const std::string& renderer);
// The error of a launch in which the guard saw a loop cut short: names the backend, the
// kernel, the driver and the limit, and where the kernel can run instead.
std::string loop_cut_message(const std::string& backend, const std::string& kernel,
                             const std::string& renderer);
// Whether GL_RENDERER names Mesa's llvmpipe, whose rules several choices follow (the loop
// guard, native division, the warm-up).
bool is_llvmpipe(const std::string& renderer);
// Whether GL_RENDERER names a software rasterizer on the CPU (llvmpipe, softpipe, swrast,
// SwiftShader) rather than a GPU.
bool is_software_renderer(const std::string& renderer);
// Whether compile()'s warm-up (a launch over no elements with 1x1 stand-ins) builds what the
// kernel's first launch will use. Not on Mesa's llvmpipe for a kernel that reads streams or
// arrays: its shader variant depends on whether each texture's width and height are powers of
// two, which the stand-ins cannot know, so the warm-up compiled a variant that real launches
// rarely used (the ray tracer's light-buffer test: 31 s with it, 18 s without, on glsl; 26
// and 16 s on glsl-compute). Such a kernel compiles at its first launch, or at k.warm_up()
// with the streams bound.
bool warm_up_pays(const std::string& renderer, const ir::Function& f);

// A backend whose context must go before the GL library's exit handlers run.
class SessionOwner {
 public:
  virtual void shutdown() noexcept = 0;

 protected:
  ~SessionOwner() = default;
};
// Registers `owner` for shutdown at exit (call right after making its context), and
// forgets it (call from its destructor).
void shut_down_at_exit(SessionOwner* owner);
void forget_at_exit(SessionOwner* owner);

// "GLSL backend: OpenGL error 0x0502 while <what>" if glGetError reports one.
void check(const GL& gl, const char* what, const char* backend = "GLSL backend");

// One shader stage's source.
struct ShaderSource {
  GLenum stage;  // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER
  std::string text;
};

// Compiles and links a program; a rejected shader is an Error naming the kernel, with the
// driver's log and the numbered source. `backend` names the backend in messages.
GLuint link_program(const GL& gl, const Driver& d, const std::string& backend,
                    const std::string& kernel, const std::vector<ShaderSource>& shaders);
// link_program through the disk cache (see the top of this file), in the entries of backend
// `cache_name` ("glsl", "glsl-compute"); `from_cache`: the program was loaded from a cached
// binary.
GLuint link_program_cached(const GL& gl, const Driver& d, const std::string& cache_name,
                           const std::string& backend, const std::string& kernel,
                           const std::vector<ShaderSource>& shaders, bool& from_cache);

}  // namespace rill::glsl
