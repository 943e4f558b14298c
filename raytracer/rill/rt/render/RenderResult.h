// What a render gives back (RenderResult): the image and AOVs asked for, the ray count, and
// where the time went (compile stages, FrameTimes, and per pass for multipass). Plain data,
// below the film and the strategies that fill it in.
#pragma once

#include <rill/rill.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace rt {

// A render's running sums, to stop it and go on later (progressive rendering; the path
// integrator's --save and --resume, docs/path-tracing.md): per pixel, row 0 at the top, the
// compensated sum of its samples' colours (sum + carry, film/Film.h) after `samples` samples.
// Resuming from it adds the later samples to the very same floats, so an image resumed from k
// samples to n is bitwise the image rendered to n at once.
// `squares`, when the render kept them (FrameOutputs::variance), is the float sum of the
// samples' squares, which a resumed render with its variance goes on adding to; empty
// otherwise.
struct Accumulation {
  int width = 0, height = 0;
  int samples = 0;
  std::vector<glm::vec3> sum, carry;
  std::vector<glm::vec3> squares;
};

// A render's time, step by step, in milliseconds (wall clock on the host; they add up to
// RenderResult::trace_ms, less a little bookkeeping).
struct FrameTimes {
  double setup = 0;   // output buffers made or resized (0 when a frame reuses them)
  double launch = 0;  // the tracing kernels' launches, each until its kernel has run
  // Of `launch`: how long the tracing kernels ran, as the device timed them
  // (rill::LaunchStats::device_ms, summed); the rest of `launch` is the cost of launching.
  // -1 where the backend cannot tell.
  double kernel = 0;
  double accumulate = 0;  // samples added up on the device (spp > 1) and their mean
  double reduce = 0;      // the ray count, reduced on the device
  double read_back = 0;   // the outputs asked for, encoded (8-bit) and read back

  // Adds one launch's device time to `kernel` (which stays -1 once a launch could not tell).
  void add_kernel(double device_ms) {
    kernel = kernel < 0 || device_ms < 0 ? -1 : kernel + device_ms;
  }
};

// One pass (kernel) of the multipass or wavefront strategy over a render: launches, elements
// run and written, time.
struct PassStats {
  std::string name;
  int64_t calls = 0, processed = 0, written = 0;
  double ms = 0;
};

// A render's read-backs in flight (render/OutputsInFlight.h).
struct OutputsInFlight;

// The image and AOVs of a render: those RenderSettings::outputs asked for (the others are
// left empty).
struct RenderResult {
  int width = 0, height = 0;
  std::vector<glm::vec3> color;     // linear, row 0 at the top; the mean over the samples
  std::vector<unsigned char> rgb8;  // the same as 8-bit sRGB (to_srgb8), 3 bytes per pixel
  std::vector<float> depth;         // first-sample AOVs: hit distance (+inf: miss)
  std::vector<int32_t> prim;        // primitive id (-1: miss)
  std::vector<glm::vec3> normal;    // shading normal as stored (0 on a miss)
  // Path integrator: the first hit's albedo (SurfaceShader::albedo; 0 on a miss), for
  // denoisers; empty under Whitted.
  std::vector<glm::vec3> albedo;
  // Per pixel, the variance of its mean colour: the samples' variance (n - 1 in the
  // denominator) over n, from their sum and sum of squares (FrameOutputs::variance).
  std::vector<glm::vec3> variance;
  int64_t rays = 0;           // rays traced (camera, shadow, secondary), all samples
  int spp = 0;                // samples per pixel in the image (resumed ones included)
  Accumulation accumulation;  // the running sums, when FrameOutputs::accumulation
  double compile_ms = 0;      // 0 when the compiled kernel came from a cache
  bool from_cache = false;
  // Of compile_ms: the first launches of the frame's kernels at its size, which trace nothing
  // (the megakernel's launch with no iterations, the wavefront's warm-ups, the ray count's
  // reduction): a driver that finishes its compile at a first launch (PoCL, Mesa, NVIDIA's
  // lazy module loading) does it there. 0 when they had run at this size before.
  double first_launch_ms = 0;
  // Whether this frame was the first this tracer traced with its strategy, backend, accuracy,
  // loop and size: its trace time then holds first-use costs that no warm-up launch takes
  // (the first touch of the scene's buffers and of the outputs, caches, a GPU's clocks), so
  // rays / trace_ms is a cold speed, not the device's (rill-trace labels it "cold").
  bool cold = false;
  // The render's kernels' compile stages (Kernel::info()), summed over them: the multipass
  // strategy compiles its nine at once (compile_all), so the sum exceeds compile_ms. origin
  // is the first kernel's.
  rill::CompileInfo stages;
  int kernels = 0;                // how many kernels `stages` sums
  double trace_ms = 0;            // the frame: launches, accumulation, reduction, read-back
  FrameTimes times;               // trace_ms, step by step
  int64_t launches = 0;           // kernel launches while tracing
  std::vector<PassStats> passes;  // multipass and wavefront: per pass
  std::string backend;
  std::string loop;  // the megakernel's loop as run ("ray" or "segment"); empty for multipass
  // The read-backs of the images still in flight (RenderSettings::read_back_later): until
  // wait_outputs(), the image vectors are being written and must not be read, resized or
  // copied. Null when none are.
  std::shared_ptr<OutputsInFlight> in_flight;
  // Waits for the images in flight, if any; adds the wait to times.read_back and trace_ms.
  // Throws rill::Error if a read-back failed.
  void wait_outputs();
};

// Adds one kernel's compile stages to r.stages.
void add_stages(RenderResult& r, const rill::CompileInfo& k);

// A render in parts (the chunks of --save-every, the rounds of a distributed progressive
// render: each part after the first a resumed render) has sample 0's AOVs from the part that
// traced sample 0; a later part that asked for them again would trace sample 0's camera rays
// once more (Frame::retrace_aovs). The caller asks the later parts for none (FrameOutputs:
// depth, prim, normal and albedo off) and moves the first part's into the last result:
void move_aovs(RenderResult& from, RenderResult& to);

}  // namespace rt
