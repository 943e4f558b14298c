// The OpenCL backend's launcher role (ClLauncher.h).
#include "ClLauncher.h"

#include <algorithm>
#include <cstdlib>

#include "../codegen/Tiles.h"
#include "WarmUpLaunch.h"

namespace rill::opencl {

namespace {

// How launches are laid out, read once from the environment:
//   RILL_OPENCL_GROUP=N      work-items per group (default 64; the kernel's and the device's
//                            limits cap it)
//   RILL_OPENCL_TILES=on|off 2D launches in 8 x 4 tiles (default on)
//   RILL_OPENCL_WARM_UP=all|small  the grid classes compile()'s warm-up builds for (default all)
struct LaunchTuning {
  size_t group = 64;
  bool tiles = true;
  bool warm_up_large = true;
};

const LaunchTuning& launch_tuning() {
  static const LaunchTuning t = [] {
    LaunchTuning t;
    if (const char* g = std::getenv("RILL_OPENCL_GROUP"); g && *g) {
      char* end = nullptr;
      const long v = std::strtol(g, &end, 10);
      if (*end != '\0' || v < 1 || v > 1024)
        throw Error(std::string("RILL_OPENCL_GROUP='") + g + "' is not a group size in 1..1024");
      t.group = static_cast<size_t>(v);
    }
    if (const char* s = std::getenv("RILL_OPENCL_TILES"); s && *s) {
      const std::string v = s;
      if (v != "on" && v != "off")
        throw Error("RILL_OPENCL_TILES='" + v + "' is not one of on, off");
      t.tiles = v == "on";
    }
    if (const char* s = std::getenv("RILL_OPENCL_WARM_UP"); s && *s) {
      const std::string v = s;
      if (v != "all" && v != "small")
        throw Error("RILL_OPENCL_WARM_UP='" + v + "' is not one of all, small");
      t.warm_up_large = v == "all";
    }
    return t;
  }();
  return t;
}

}  // namespace

void check_launch_settings() {
  launch_tuning();
}

void ClKernel::warm_up() {
  WarmUpLaunch stand_ins(fn_);
  const size_t grids[] = {1, 65536};
  const size_t classes = launch_tuning().warm_up_large ? 2 : 1;  // RILL_OPENCL_WARM_UP
  for (size_t c = 0; c < classes; ++c) {
    warm_up_grid_ = grids[c];
    run(stand_ins.args());
  }
}

LaunchResult ClKernel::run(const LaunchArgs& a) {
  Device& d = device_;
  cl_uint arg = 0;
  auto set_mem = [&](cl_mem m) {
    check(clSetKernelArg(kernel_, arg++, sizeof(cl_mem), &m), "clSetKernelArg");
  };
  for (auto* s : a.inputs) set_mem(memory_.to_device(*s));
  for (auto* s : a.outputs) set_mem(memory_.to_device(*s));
  shapes_now_.clear();
  for (auto* arr : a.arrays) {
    set_mem(memory_.to_device(*arr));
    shapes_now_.insert(shapes_now_.end(), {arr->shape[0], arr->shape[1], arr->shape[2]});
  }
  uniforms_now_.clear();
  for (auto* u : a.uniforms)
    uniforms_now_.insert(uniforms_now_.end(), u->bits.begin(), u->bits.end());
  if (!counter_) {
    totals_[0] = totals_[1] = 0;
    counter_ = memory_.scratch(sizeof totals_, totals_);
  }
  cl_long width = a.width, count = a.count;
  set_mem(memory_.table(shapes_, shapes_now_));
  set_mem(memory_.table(uniforms_, uniforms_now_));
  check(clSetKernelArg(kernel_, arg++, sizeof width, &width), "clSetKernelArg");
  check(clSetKernelArg(kernel_, arg++, sizeof count, &count), "clSetKernelArg");
  set_mem(counter_);
  // The mask (none: an empty set, and the values table stands in for the state stream).
  cl_mem values_buf = memory_.table(values_, a.mask_values);
  cl_int mask_count = a.mask ? static_cast<cl_int>(a.mask_values.size()) : 0;
  set_mem(a.mask ? memory_.to_device(*a.mask) : values_buf);
  set_mem(values_buf);
  check(clSetKernelArg(kernel_, arg++, sizeof mask_count, &mask_count), "clSetKernelArg");
  // 2D launches run in 8 x 4 tiles (OpenCLEmitter.cpp) unless RILL_OPENCL_TILES=off.
  const LaunchTuning& tuning = launch_tuning();
  cl_int tiled = tuning.tiles && a.height > 1 && !a.warm_up ? 1 : 0;
  check(clSetKernelArg(kernel_, arg++, sizeof tiled, &tiled), "clSetKernelArg");

  cl_uint written[2] = {0, 0};
  double device_ms = 0;  // nothing ran
  if (a.count > 0 || a.warm_up) {
    if (group_ == 0) {
      size_t kernel_group = 0;
      clGetKernelWorkGroupInfo(kernel_, d.id, CL_KERNEL_WORK_GROUP_SIZE, sizeof kernel_group,
                               &kernel_group, nullptr);
      group_ = std::max<size_t>(
          1, std::min({tuning.group, kernel_group ? kernel_group : tuning.group, d.max_group}));
    }
    // A warm-up runs no element (count 0) but spans warm_up_grid_ work-items (warm_up()).
    size_t span = a.warm_up ? warm_up_grid_ : static_cast<size_t>(a.count);
    if (tiled) span = static_cast<size_t>(codegen::tiled_invocations(a.width, a.height));
    size_t global = (span + group_ - 1) / group_ * group_;
    cl_uint totals[2] = {0, 0};
    // The blocking read of the counter is the launch's only wait: it returns once the kernel
    // has run (the queue is in order).
    cl_event ran = nullptr;
    cl_int e =
        clEnqueueNDRangeKernel(d.queue, kernel_, 1, nullptr, &global, &group_, 0, nullptr, &ran);
    if (e == CL_SUCCESS)
      e = clEnqueueReadBuffer(d.queue, counter_, CL_TRUE, 0, sizeof totals, totals, 0, nullptr,
                              nullptr);
    device_ms = -1;
    if (ran) {
      cl_ulong start = 0, end = 0;
      if (e == CL_SUCCESS &&
          clGetEventProfilingInfo(ran, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr) ==
              CL_SUCCESS &&
          clGetEventProfilingInfo(ran, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr) ==
              CL_SUCCESS &&
          end >= start)
        device_ms = static_cast<double>(end - start) * 1e-6;
      clReleaseEvent(ran);
    }
    if (e != CL_SUCCESS) {
      // The totals are unknown now: the next launch starts a fresh counter.
      clReleaseMemObject(counter_);
      counter_ = nullptr;
      check(e, "running the kernel");
    }
    for (int i = 0; i < 2; ++i) {
      written[i] = totals[i] - totals_[i];
      totals_[i] = totals[i];
    }
  }
  const int64_t selected = a.mask ? written[1] : a.count;
  // The device wrote the outputs: their host copies are stale until read back.
  for (auto* s : a.outputs) s->mark_device_written(&memory_.owner());
  return {written[0], selected, device_ms};
}

}  // namespace rill::opencl
