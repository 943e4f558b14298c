// What a render asks for (RenderSettings): the backend and accuracy, the strategy and its
// knobs, the image size, depth and samples, the window, and what comes back to the host
// (FrameOutputs). Plain data, below the film and the strategies that read it; the Tracer
// facade (Tracer.h) takes it per render.
#pragma once

#include <rill/rill.h>

#include "rill/rt/render/BounceRays.h"
#include "rill/rt/render/RenderResult.h"

#include <functional>
#include <string>
#include <vector>

namespace rt {

// A render strategy (strategy/RenderStrategy.h), by the name it is registered under
// (Tracer.h: register_strategy, parse_strategy). Three are built in:
//   Strategy::Megakernel  one kernel per pixel with a RILL_DO loop (Sh; megakernel/)
//   Strategy::Multipass   the thesis's kernel sequence with ray states, no refraction, the
//                         Whitted tracer only (multipass/)
//   Strategy::Wavefront   the path integrator's stages, a kernel each (wavefront/)
struct Strategy {
  std::string name = "megakernel";
  static const Strategy Megakernel, Multipass, Wavefront;
  bool operator==(const Strategy&) const = default;
};
inline const Strategy Strategy::Megakernel{"megakernel"};
inline const Strategy Strategy::Multipass{"multipass"};
inline const Strategy Strategy::Wavefront{"wavefront"};
// The shape of the megakernel's loop (megakernel/Megakernel.h). Images do not depend on it,
// only speed does (docs/benchmarks/2026-11-25-gpu-frame.md, "Session 23").
enum class MegakernelLoop {
  Auto,     // Segment on cpu and simd; Ray on every other backend, whatever its device
  Ray,      // one traced ray per iteration, camera, secondary or shadow: the walk has one call
            // site, so a GPU's lanes walk together whichever kind of ray each one holds
  Segment,  // one path segment per iteration, its shadow rays traced in a light loop inside
            // it: no loop iteration per light, and a walk specialized for each kind of ray
};
// "auto", "ray" or "segment"; throws std::invalid_argument naming the bad value.
MegakernelLoop parse_megakernel_loop(const std::string& s);
const char* megakernel_loop_name(MegakernelLoop loop);
// The shape `loop` stands for on `backend`: Auto resolved, the others as they are.
MegakernelLoop megakernel_loop_for(MegakernelLoop loop, const std::string& backend);

// What a render reads back to the host (RenderResult): everything else stays on the device.
// A PNG needs only `rgb8`; a PFM needs `color`; the AOVs only when asked for.
//
// By default the colour image alone: the linear colour, which every format rt::save writes
// takes (a PNG encodes it on the host to the bytes the device's rgb8 would have:
// ResultFiles.h), and no AOV, a third of the megakernel's writes that most renders never
// look at. `rgb8` stays off: with `color` on it would be a second read-back of the same image.
struct FrameOutputs {
  bool color = true;      // RenderResult::color: the linear mean colour, 3 floats per pixel
  bool rgb8 = false;      // RenderResult::rgb8: the 8-bit sRGB encoding, encoded on the device
  bool depth = false;     // RenderResult::depth
  bool prim = false;      // RenderResult::prim
  bool normal = false;    // RenderResult::normal
  bool albedo = false;    // RenderResult::albedo (the path integrator's; empty under Whitted)
  bool variance = false;  // RenderResult::variance (2 samples or more; resumed: if it kept squares)
  bool accumulation = false;  // RenderResult::accumulation: the running sums, to resume from
  // These outputs with no AOV (RenderResult.h, move_aovs: the later parts of a render in parts).
  FrameOutputs without_aovs() const {
    FrameOutputs o = *this;
    o.depth = o.prim = o.normal = o.albedo = false;
    return o;
  }
};

struct RenderSettings {
  std::string backend = "cpu";
  Strategy strategy = Strategy::Megakernel;
  MegakernelLoop loop = MegakernelLoop::Auto;  // the megakernel strategy's loop
  // The path megakernel's samples per launch (path regeneration, megakernel/Megakernel.h):
  // within a launch, a pixel whose path ended starts its next sample at once. 1: one sample
  // per launch, summed by the film; more: up to kPathSamplesPerLaunch (16); 0:
  // RILL_PATH_REGENERATE's choice (off: 1, on: 16), or where it is unset the backend's (1 on
  // simd, 16 elsewhere: rt::path_samples_per_launch). `after_pass` is called after each
  // launch. Images have the same bits whatever it is.
  int path_samples_per_launch = 0;
  rill::Accuracy accuracy = rill::Accuracy::Strict;
  // 0: the scene's (Scene::width, height; each side on its own); otherwise within the image
  // limits, 1..16384 a side and 2^25 pixels (scene/ImageLimits.h), or Tracer::render throws.
  int width = 0, height = 0;
  int max_depth = -1;  // -1: the scene's
  int spp = 0;         // 0: the scene's
  // Multipass strategy (Multipass.cpp): rerun the intersector while at least this fraction
  // of the traced rays waits for it (thesis 5.6: 20%); launch each pass masked to its state.
  double wait_threshold = 0.2;
  bool masking = true;
  FrameOutputs outputs;  // what comes back to the host
  // A window of the image, in its pixels (row 0 at the top): only these are rendered, through
  // the whole image's camera, bitwise the same as those pixels of the whole render, and the
  // RenderResult is the window's size. Empty (width or height 0): the whole image. The
  // distributed renderer's tiles (apps/rill-trace/distributed/).
  struct Window {
    int x = 0, y = 0, width = 0, height = 0;
    bool empty() const { return width <= 0 || height <= 0; }
  } window;
  // Progressive rendering. A render runs in passes of one sample per pixel, samples 0 to
  // spp - 1 in order. With `resume` (the accumulation of an earlier render of the same scene,
  // seed and size; RenderResult::accumulation) it starts after that render's samples.
  // `after_pass`, if set, is called after each pass with the samples per pixel done so far;
  // returning false stops the render there (a time limit, a cancel button): the image is the
  // mean of the samples done, RenderResult::spp says how many.
  const Accumulation* resume = nullptr;
  std::function<bool(int samples_done)> after_pass;
  // If set, the render also reads back the path tracer's rays after bounce_rays->bounce
  // scatterings into it (render/BounceRays.h): the wavefront strategy only; for the others
  // the Tracer throws. It costs a read-back of the paths per sample; the image is the same.
  BounceRays* bounce_rays = nullptr;
  // Whether Tracer::render may return with the outputs' read-back still in flight, so that a
  // frame sequence overlaps frame n's read-back with frame n + 1's trace: the result's images
  // are there once RenderResult::wait_outputs() returns (docs/raytracer.md, "First use and
  // overlap"). Only a backend that reads back asynchronously (OpenCL) leaves anything in
  // flight; the variance and the accumulation are read before render returns. The bytes are
  // the same either way.
  bool read_back_later = false;
};

}  // namespace rt
