#include "GLContext.h"

#include <dlfcn.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "rill/Error.h"

namespace rill::glsl {

namespace {

using ProcLoader = void* (*)(const char*);

// Loads every GL function through `load`; names the first one missing.
void load_functions(GL& gl, ProcLoader load, const std::string& who) {
#define GL_FN(ret, name, params)                                                            \
  gl.name = reinterpret_cast<ret(APIENTRY*) params>(load(#name));                          \
  if (!gl.name) throw Error("GLSL backend: " + who + " has no " #name " (OpenGL 4.3 needed)");
#include "GLFunctions.def"
#undef GL_FN
}

void describe(GLContext& c, const GL& gl) {
  auto str = [&](GLenum e) {
    const GLubyte* s = gl.glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  c.renderer = str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

// ---- OSMesa ------------------------------------------------------------------------------

// From GL/osmesa.h (spelled out so that header's GL/gl.h does not meet glcorearb.h).
constexpr int kOsmesaFormat = 0x22, kOsmesaRgba = 0x1908, kOsmesaDepthBits = 0x30, kOsmesaStencilBits = 0x31,
              kOsmesaAccumBits = 0x32, kOsmesaProfile = 0x33, kOsmesaCoreProfile = 0x34, kOsmesaMajor = 0x36,
              kOsmesaMinor = 0x37;

class OSMesaContext : public GLContext {
 public:
  OSMesaContext() {
    lib_ = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib_) lib_ = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib_) throw Error("GLSL backend: libOSMesa not found (install libosmesa6)");
    create_ = reinterpret_cast<CreateFn>(dlsym(lib_, "OSMesaCreateContextAttribs"));
    make_current_ = reinterpret_cast<MakeCurrentFn>(dlsym(lib_, "OSMesaMakeCurrent"));
    get_proc_ = reinterpret_cast<GetProcFn>(dlsym(lib_, "OSMesaGetProcAddress"));
    destroy_ = reinterpret_cast<DestroyFn>(dlsym(lib_, "OSMesaDestroyContext"));
    if (!create_ || !make_current_ || !get_proc_ || !destroy_)
      throw Error("GLSL backend: libOSMesa lacks OSMesaCreateContextAttribs (Mesa too old)");
    const int attribs[] = {kOsmesaFormat, kOsmesaRgba, kOsmesaDepthBits, 0, kOsmesaStencilBits, 0,
                           kOsmesaAccumBits, 0, kOsmesaProfile, kOsmesaCoreProfile, kOsmesaMajor, 4,
                           kOsmesaMinor, 3, 0};
    ctx_ = create_(attribs, nullptr);
    if (!ctx_) throw Error("GLSL backend: OSMesa could not create an OpenGL 4.3 core context");
    make_current();
    load_functions(gl_, reinterpret_cast<ProcLoader>(get_proc_), "OSMesa");
    describe(*this, gl_);
  }
  ~OSMesaContext() override {
    // Called from GLSLBackend's explicit shutdown (before Mesa's own exit handlers run).
    if (ctx_) destroy_(ctx_);
    // lib_ stays loaded: Mesa does not support being unloaded and reloaded.
  }
  void make_current() override {
    if (!make_current_(ctx_, pixel_, 0x1401 /* GL_UNSIGNED_BYTE */, 1, 1))
      throw Error("GLSL backend: OSMesaMakeCurrent failed");
  }
  std::string kind() const override { return "osmesa"; }

 private:
  using CreateFn = void* (*)(const int*, void*);
  using MakeCurrentFn = unsigned char (*)(void*, void*, unsigned, int, int);
  using GetProcFn = void* (*)(const char*);
  using DestroyFn = void (*)(void*);
  void* lib_ = nullptr;
  void* ctx_ = nullptr;
  unsigned char pixel_[16] = {};  // the 1x1 default framebuffer; kernels render to FBOs
  CreateFn create_ = nullptr;
  MakeCurrentFn make_current_ = nullptr;
  GetProcFn get_proc_ = nullptr;
  DestroyFn destroy_ = nullptr;
};

// ---- EGL (GPU, no display) ---------------------------------------------------------------

class EGLDeviceContext : public GLContext {
 public:
  EGLDeviceContext() {
    lib_ = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib_) throw Error("GLSL backend: libEGL.so.1 not found (install libegl1 and a GPU driver)");
    get_proc_ = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(lib_, "eglGetProcAddress"));
    if (!get_proc_) throw Error("GLSL backend: libEGL has no eglGetProcAddress");
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(get_proc_("eglQueryDevicesEXT"));
    auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(get_proc_("eglGetPlatformDisplayEXT"));
    initialize_ = reinterpret_cast<PFNEGLINITIALIZEPROC>(get_proc_("eglInitialize"));
    auto bind_api = reinterpret_cast<PFNEGLBINDAPIPROC>(get_proc_("eglBindAPI"));
    auto choose = reinterpret_cast<PFNEGLCHOOSECONFIGPROC>(get_proc_("eglChooseConfig"));
    auto create = reinterpret_cast<PFNEGLCREATECONTEXTPROC>(get_proc_("eglCreateContext"));
    make_current_ = reinterpret_cast<PFNEGLMAKECURRENTPROC>(get_proc_("eglMakeCurrent"));
    destroy_ = reinterpret_cast<PFNEGLDESTROYCONTEXTPROC>(get_proc_("eglDestroyContext"));
    if (!query_devices || !platform_display || !initialize_ || !bind_api || !choose || !create || !make_current_)
      throw Error("GLSL backend: EGL lacks EGL_EXT_device_enumeration / EGL_EXT_platform_device");
    EGLDeviceEXT devices[16];
    EGLint n = 0;
    if (!query_devices(16, devices, &n) || n == 0) throw Error("GLSL backend: EGL reports no devices");
    const char* want = std::getenv("RILL_EGL_DEVICE");
    int index = want ? std::atoi(want) : 0;
    if (index < 0 || index >= n)
      throw Error("GLSL backend: RILL_EGL_DEVICE=" + std::string(want) + " but EGL has " + std::to_string(n) +
                  " device(s)");
    // The first device that initializes, from the requested one on.
    for (int i = index; i < n && display_ == EGL_NO_DISPLAY; ++i) {
      EGLDisplay d = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
      EGLint major = 0, minor = 0;
      if (d != EGL_NO_DISPLAY && initialize_(d, &major, &minor)) display_ = d;
    }
    if (display_ == EGL_NO_DISPLAY) throw Error("GLSL backend: no EGL device could be initialized");
    if (!bind_api(EGL_OPENGL_API)) throw Error("GLSL backend: EGL cannot bind the OpenGL API");
    // Device displays have no windows, and EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT:
    // ask for pbuffer configs (we render to framebuffer objects; no surface is made).
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                     EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!choose(display_, config_attribs, &config, 1, &count) || count == 0)
      config = nullptr;  // EGL_KHR_no_config_context: a context without a config
    if (!config && !has_extension(display_, "EGL_KHR_no_config_context"))
      throw Error("GLSL backend: EGL has no OpenGL pbuffer config");
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 3,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    ctx_ = create(display_, config, EGL_NO_CONTEXT, ctx_attribs);
    if (ctx_ == EGL_NO_CONTEXT) throw Error("GLSL backend: EGL could not create an OpenGL 4.3 core context");
    make_current();
    load_functions(gl_, reinterpret_cast<ProcLoader>(get_proc_), "EGL");
    describe(*this, gl_);
  }
  bool has_extension(EGLDisplay d, const char* name) {
    auto query = reinterpret_cast<PFNEGLQUERYSTRINGPROC>(get_proc_("eglQueryString"));
    const char* ext = query ? query(d, EGL_EXTENSIONS) : nullptr;
    return ext && std::strstr(ext, name) != nullptr;
  }

  ~EGLDeviceContext() override {
    // Not current any more on this thread, then destroyed (GLSLBackend.cpp destroys contexts
    // before EGL's own exit handlers run). The display stays initialized: EGL has one per
    // device and process, which other code in the process may be using.
    if (ctx_ == EGL_NO_CONTEXT) return;
    make_current_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (destroy_) destroy_(display_, ctx_);
  }

  void make_current() override {
    if (!make_current_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_))
      throw Error("GLSL backend: eglMakeCurrent failed (surfaceless contexts unsupported?)");
  }
  std::string kind() const override { return "egl"; }

 private:
  void* lib_ = nullptr;
  PFNEGLGETPROCADDRESSPROC get_proc_ = nullptr;
  PFNEGLINITIALIZEPROC initialize_ = nullptr;
  PFNEGLMAKECURRENTPROC make_current_ = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroy_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext ctx_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GLContext> create_context() {
  const char* env = std::getenv("RILL_GL");
  std::string want = env ? env : "";
  if (want == "osmesa") return std::make_unique<OSMesaContext>();
  if (want == "egl") return std::make_unique<EGLDeviceContext>();
  if (!want.empty()) throw Error("GLSL backend: RILL_GL must be 'osmesa' or 'egl', not '" + want + "'");
  std::string first;
  try {
    return std::make_unique<OSMesaContext>();
  } catch (const Error& e) {
    first = e.what();
  }
  try {
    return std::make_unique<EGLDeviceContext>();
  } catch (const Error& e) {
    throw Error("no OpenGL context: " + first + "; and " + e.what());
  }
}

}  // namespace rill::glsl
