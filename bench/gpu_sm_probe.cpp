// rill-bench-sm-probe: which of the GPU's multiprocessors a launch runs on, and how long it
// takes, through OpenCL and through OpenGL compute, in one process, step by step (issue 52
// item 1: OpenCL slows 3-5x when a GL or Vulkan context shares its process, and GL compute
// runs the ray tracer 2-3x slower than OpenCL).
//
// The same spinning kernel runs through each API: `groups` work-groups of 128 work-items,
// each item a dependent chain of float operations, and the first item of each group writes
// the multiprocessor it ran on (NVIDIA: PTX's %smid in OpenCL, GL_NV_shader_thread_group's
// gl_SMIDNV in GLSL; elsewhere -1, "unknown"). Each step prints the median wall time of 7
// launches (after a first one, not counted) and how many distinct multiprocessors ran them.
// The steps come from the command line, in order:
//   cl        launch through OpenCL (the context made at the first use)
//   gl        launch through GL compute (an EGL device context made at the first use)
//   glctx     make the GL context only;    gldrop  destroy it
//   cldrop    release the OpenCL context
//   cl2       launch through a second OpenCL context (made at its first use)
//   sleep S   wait S seconds (for two processes side by side: one holding a context)
// e.g. `rill-bench-sm-probe cl glctx cl gl cl gldrop cl`. A diagnostic for the GPU machine
// (docs/benchmarks/2026-12-08-shared-process-cause.md); it uses the APIs directly, not Rill,
// so that nothing of Rill's own set-up is in the way.
#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace {

constexpr int kLocal = 128;
int g_groups = 1056;  // 8 per multiprocessor of a 132-SM H100/H200
int g_spin = 20000;   // iterations of each work-item's chain
constexpr int kRepeats = 7;

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "rill-bench-sm-probe: %s\n", what.c_str());
  std::exit(1);
}

double now_ms() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

struct Result {
  double median_ms = 0;
  int sms = 0;  // distinct multiprocessor ids; 0 when unknown
  int max_sm = -1;
};

Result summarize(std::vector<double> ms, const std::vector<int>& ids) {
  std::sort(ms.begin(), ms.end());
  Result r;
  r.median_ms = ms[ms.size() / 2];
  std::set<int> s;
  for (int id : ids)
    if (id >= 0) s.insert(id);
  r.sms = static_cast<int>(s.size());
  r.max_sm = s.empty() ? -1 : *s.rbegin();
  return r;
}

void print(const char* step, const Result& r) {
  std::printf(
      "%-8s median %8.3f ms over %d launches; %d groups ran on %d distinct SMs (highest id %d)\n",
      step, r.median_ms, kRepeats, g_groups, r.sms, r.max_sm);
  std::fflush(stdout);
}

// ---- OpenCL -------------------------------------------------------------------------------

const char* kClSource = R"(
#ifdef SMID
static uint sm_id(void) { uint s; asm volatile("mov.u32 %0, %%smid;" : "=r"(s)); return s; }
#else
static uint sm_id(void) { return 0xffffffffu; }
#endif
__kernel void spin(__global float* out, __global uint* sm, int n) {
  float x = (float)get_global_id(0) * 1e-6f;
  for (int i = 0; i < n; ++i) x = x * 0.999f + 0.5f;
  out[get_global_id(0)] = x;
  if (get_local_id(0) == 0) sm[get_group_id(0)] = sm_id();
}
)";

struct Cl {
  cl_context ctx = nullptr;
  cl_command_queue q = nullptr;
  cl_kernel k = nullptr;
  cl_program p = nullptr;
  cl_mem out = nullptr, sm = nullptr;

  void make() {
    cl_platform_id plats[8];
    cl_uint np = 0;
    if (clGetPlatformIDs(8, plats, &np) != CL_SUCCESS || np == 0) fail("no OpenCL platform");
    cl_device_id dev = nullptr;
    for (cl_uint i = 0; i < np && !dev; ++i)
      if (clGetDeviceIDs(plats[i], CL_DEVICE_TYPE_GPU, 1, &dev, nullptr) != CL_SUCCESS)
        dev = nullptr;
    if (!dev && clGetDeviceIDs(plats[0], CL_DEVICE_TYPE_ALL, 1, &dev, nullptr) != CL_SUCCESS)
      fail("no OpenCL device");
    char name[256] = {};
    clGetDeviceInfo(dev, CL_DEVICE_NAME, sizeof name, name, nullptr);
    cl_int e = 0;
    ctx = clCreateContext(nullptr, 1, &dev, nullptr, nullptr, &e);
    if (e) fail("clCreateContext " + std::to_string(e));
    q = clCreateCommandQueue(ctx, dev, 0, &e);
    if (e) fail("clCreateCommandQueue " + std::to_string(e));
    // %smid through inline PTX on NVIDIA; without it where the compiler refuses.
    bool smid = true;
    for (int attempt = 0; attempt < 2; ++attempt, smid = false) {
      p = clCreateProgramWithSource(ctx, 1, &kClSource, nullptr, &e);
      if (clBuildProgram(p, 1, &dev, smid ? "-DSMID" : "", nullptr, nullptr) == CL_SUCCESS) break;
      clReleaseProgram(p);
      p = nullptr;
    }
    if (!p) fail("the OpenCL probe kernel does not build");
    k = clCreateKernel(p, "spin", &e);
    out = clCreateBuffer(ctx, CL_MEM_READ_WRITE, sizeof(float) * g_groups * kLocal, nullptr, &e);
    sm = clCreateBuffer(ctx, CL_MEM_READ_WRITE, sizeof(cl_uint) * g_groups, nullptr, &e);
    std::printf("opencl: %s, SM ids %s\n", name, smid ? "from %smid" : "unknown");
  }
  Result run() {
    if (!ctx) make();
    clSetKernelArg(k, 0, sizeof out, &out);
    clSetKernelArg(k, 1, sizeof sm, &sm);
    clSetKernelArg(k, 2, sizeof g_spin, &g_spin);
    size_t global = static_cast<size_t>(g_groups) * kLocal, local = kLocal;
    std::vector<double> ms;
    for (int r = 0; r <= kRepeats; ++r) {
      double t0 = now_ms();
      if (clEnqueueNDRangeKernel(q, k, 1, nullptr, &global, &local, 0, nullptr, nullptr))
        fail("launch");
      clFinish(q);
      if (r > 0) ms.push_back(now_ms() - t0);
    }
    std::vector<cl_uint> ids(g_groups);
    clEnqueueReadBuffer(q, sm, CL_TRUE, 0, sizeof(cl_uint) * g_groups, ids.data(), 0, nullptr,
                        nullptr);
    return summarize(ms, std::vector<int>(ids.begin(), ids.end()));
  }
  void drop() {
    if (!ctx) return;
    clReleaseMemObject(out);
    clReleaseMemObject(sm);
    clReleaseKernel(k);
    clReleaseProgram(p);
    clReleaseCommandQueue(q);
    clReleaseContext(ctx);
    *this = Cl{};
  }
};

// ---- OpenGL compute through an EGL device ---------------------------------------------------

struct Gl {
  void* lib = nullptr;
  PFNEGLGETPROCADDRESSPROC proc = nullptr;
  EGLDisplay dpy = EGL_NO_DISPLAY;
  EGLContext ctx = EGL_NO_CONTEXT;
  GLuint prog = 0, out = 0, sm = 0;

  template <typename F>
  F fn(const char* name) {
    auto f = reinterpret_cast<F>(proc(name));
    if (!f) fail(std::string("no ") + name);
    return f;
  }
  void make_context() {
    lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) fail("no libEGL.so.1");
    proc = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(lib, "eglGetProcAddress"));
    auto query = fn<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
    auto platform = fn<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    EGLDeviceEXT devs[16];
    EGLint n = 0;
    if (!query(16, devs, &n) || n == 0) fail("EGL has no devices");
    for (int i = 0; i < n && dpy == EGL_NO_DISPLAY; ++i) {
      EGLDisplay d = platform(EGL_PLATFORM_DEVICE_EXT, devs[i], nullptr);
      EGLint a, b;
      if (d != EGL_NO_DISPLAY && fn<PFNEGLINITIALIZEPROC>("eglInitialize")(d, &a, &b)) dpy = d;
    }
    if (dpy == EGL_NO_DISPLAY) fail("no EGL device initializes");
    fn<PFNEGLBINDAPIPROC>("eglBindAPI")(EGL_OPENGL_API);
    const EGLint cfg_attr[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                               EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig cfg = nullptr;
    EGLint count = 0;
    if (!fn<PFNEGLCHOOSECONFIGPROC>("eglChooseConfig")(dpy, cfg_attr, &cfg, 1, &count) || !count)
      cfg = nullptr;
    const EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION,
                           4,
                           EGL_CONTEXT_MINOR_VERSION,
                           3,
                           EGL_CONTEXT_OPENGL_PROFILE_MASK,
                           EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                           EGL_NONE};
    ctx = fn<PFNEGLCREATECONTEXTPROC>("eglCreateContext")(dpy, cfg, EGL_NO_CONTEXT, attr);
    if (ctx == EGL_NO_CONTEXT) fail("no GL 4.3 context");
    if (!fn<PFNEGLMAKECURRENTPROC>("eglMakeCurrent")(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx))
      fail("eglMakeCurrent");
    auto get_string = fn<PFNGLGETSTRINGPROC>("glGetString");
    std::printf("gl: %s\n", reinterpret_cast<const char*>(get_string(GL_RENDERER)));
  }
  void make_program() {
    const char* src = R"(#version 430
#extension GL_NV_shader_thread_group : enable
layout(local_size_x = 128) in;
layout(std430, binding = 0) buffer O { float o[]; };
layout(std430, binding = 1) buffer S { uint s[]; };
uniform int n;
void main() {
  float x = float(gl_GlobalInvocationID.x) * 1e-6;
  for (int i = 0; i < n; ++i) x = x * 0.999 + 0.5;
  o[gl_GlobalInvocationID.x] = x;
#ifdef GL_NV_shader_thread_group
  if (gl_LocalInvocationIndex == 0u) s[gl_WorkGroupID.x] = gl_SMIDNV;
#else
  if (gl_LocalInvocationIndex == 0u) s[gl_WorkGroupID.x] = 0xffffffffu;
#endif
}
)";
    GLuint sh = fn<PFNGLCREATESHADERPROC>("glCreateShader")(GL_COMPUTE_SHADER);
    fn<PFNGLSHADERSOURCEPROC>("glShaderSource")(sh, 1, &src, nullptr);
    fn<PFNGLCOMPILESHADERPROC>("glCompileShader")(sh);
    GLint ok = 0;
    fn<PFNGLGETSHADERIVPROC>("glGetShaderiv")(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[2048] = {};
      fn<PFNGLGETSHADERINFOLOGPROC>("glGetShaderInfoLog")(sh, sizeof log, nullptr, log);
      fail(std::string("GL probe shader: ") + log);
    }
    prog = fn<PFNGLCREATEPROGRAMPROC>("glCreateProgram")();
    fn<PFNGLATTACHSHADERPROC>("glAttachShader")(prog, sh);
    fn<PFNGLLINKPROGRAMPROC>("glLinkProgram")(prog);
    auto gen = fn<PFNGLGENBUFFERSPROC>("glGenBuffers");
    auto bind = fn<PFNGLBINDBUFFERPROC>("glBindBuffer");
    auto data = fn<PFNGLBUFFERDATAPROC>("glBufferData");
    gen(1, &out);
    gen(1, &sm);
    bind(GL_SHADER_STORAGE_BUFFER, out);
    data(GL_SHADER_STORAGE_BUFFER, sizeof(float) * g_groups * kLocal, nullptr, GL_DYNAMIC_COPY);
    bind(GL_SHADER_STORAGE_BUFFER, sm);
    data(GL_SHADER_STORAGE_BUFFER, sizeof(GLuint) * g_groups, nullptr, GL_DYNAMIC_READ);
  }
  Result run() {
    if (ctx == EGL_NO_CONTEXT) make_context();
    if (!prog) make_program();
    fn<PFNGLUSEPROGRAMPROC>("glUseProgram")(prog);
    fn<PFNGLUNIFORM1IPROC>("glUniform1i")(
        fn<PFNGLGETUNIFORMLOCATIONPROC>("glGetUniformLocation")(prog, "n"), g_spin);
    auto base = fn<PFNGLBINDBUFFERBASEPROC>("glBindBufferBase");
    base(GL_SHADER_STORAGE_BUFFER, 0, out);
    base(GL_SHADER_STORAGE_BUFFER, 1, sm);
    auto dispatch = fn<PFNGLDISPATCHCOMPUTEPROC>("glDispatchCompute");
    auto finish = fn<PFNGLFINISHPROC>("glFinish");
    std::vector<double> ms;
    for (int r = 0; r <= kRepeats; ++r) {
      double t0 = now_ms();
      dispatch(g_groups, 1, 1);
      finish();
      if (r > 0) ms.push_back(now_ms() - t0);
    }
    fn<PFNGLMEMORYBARRIERPROC>("glMemoryBarrier")(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<GLuint> ids(g_groups);
    fn<PFNGLBINDBUFFERPROC>("glBindBuffer")(GL_SHADER_STORAGE_BUFFER, sm);
    fn<PFNGLGETBUFFERSUBDATAPROC>("glGetBufferSubData")(GL_SHADER_STORAGE_BUFFER, 0,
                                                        sizeof(GLuint) * g_groups, ids.data());
    return summarize(ms, std::vector<int>(ids.begin(), ids.end()));
  }
  void drop() {
    if (ctx == EGL_NO_CONTEXT) return;
    fn<PFNEGLMAKECURRENTPROC>("eglMakeCurrent")(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE,
                                                EGL_NO_CONTEXT);
    fn<PFNEGLDESTROYCONTEXTPROC>("eglDestroyContext")(dpy, ctx);
    ctx = EGL_NO_CONTEXT;
    prog = out = sm = 0;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: rill-bench-sm-probe [--groups N] [--spin N] STEP...\n"
                 "  STEP: cl | cl2 | gl | glctx | gldrop | cldrop | sleep S (see the comment at "
                 "the top of bench/gpu_sm_probe.cpp)\n");
    return 2;
  }
  Cl cl, cl2;
  Gl gl;
  for (int i = 1; i < argc; ++i) {
    std::string s = argv[i];
    if ((s == "--groups" || s == "--spin") && i + 1 < argc) {
      int v = std::atoi(argv[++i]);
      if (v <= 0) {
        std::fprintf(stderr, "rill-bench-sm-probe: %s needs a positive integer\n", s.c_str());
        return 2;
      }
      (s == "--groups" ? g_groups : g_spin) = v;
    } else if (s == "cl") {
      print("cl", cl.run());
    } else if (s == "cl2") {
      print("cl2", cl2.run());
    } else if (s == "sleep" && i + 1 < argc) {
      std::this_thread::sleep_for(std::chrono::duration<double>(std::atof(argv[++i])));
      std::printf("sleep    done\n");
    } else if (s == "gl") {
      print("gl", gl.run());
    } else if (s == "glctx") {
      if (gl.ctx == EGL_NO_CONTEXT) gl.make_context();
      std::printf("glctx    made\n");
    } else if (s == "gldrop") {
      gl.drop();
      std::printf("gldrop   done\n");
    } else if (s == "cldrop") {
      cl.drop();
      std::printf("cldrop   done\n");
    } else {
      std::fprintf(
          stderr,
          "rill-bench-sm-probe: unknown step '%s' (cl, cl2, gl, glctx, gldrop, cldrop, sleep S)\n",
          s.c_str());
      return 2;
    }
  }
  return 0;
}
