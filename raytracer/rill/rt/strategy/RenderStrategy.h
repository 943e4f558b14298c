// The render strategy interface (after pbrt's and Mitsuba's integrators): how a frame's
// pixels are computed on the device. The megakernel (megakernel/), the thesis's multipass
// sequence (multipass/) and the path integrator's wavefront (wavefront/) implement it;
// Tracer.cpp registers them by name, so a new strategy
// of the library is a folder of its own and one line there, and a program registers its own
// with rt::register_strategy (Tracer.h).
//
// The Tracer facade does what every strategy shares before it calls one: it resolves the
// image size, depth and samples, checks the window, and sets the camera on the device
// (DeviceScene::camera) for the frame's eye. A strategy compiles what it needs (cached per
// backend and accuracy), launches its kernels once per sample, hands each sample's colour to
// the film, and fills in the RenderResult's counts and times. Every strategy gives the same
// bits for the same frame where it supports the scene.
#pragma once

#include <optional>

#include "rill/Stopwatch.h"
#include "rill/rt/film/Film.h"
#include "rill/rt/kernel/Records.h"
#include "rill/rt/render/RenderResult.h"
#include "rill/rt/render/RenderSettings.h"

namespace rt {

// One frame as a strategy renders it: the settings as given, and what the Tracer resolved
// from them and the scene.
struct Frame {
  const RenderSettings& settings;  // backend, accuracy, outputs, the strategy's knobs
  int width = 0, height = 0;       // the pixels to render: the window's (or the image's) size
  int depth = 0;                   // bounces: the settings' max_depth, else the scene's
  int spp = 1;                     // samples per pixel: the settings', else the scene's
  Film& film;                      // where the samples meet (film/Film.h)
  // The first sample to render: 0, or the resumed accumulation's count (settings.resume).
  int first_sample = 0;
  // After sample s was handed to the film: whether to go on (settings.after_pass).
  bool more_after(int s) const { return !settings.after_pass || settings.after_pass(s + 1); }
  // Whether the frame is resumed and asks for AOVs: sample 0 was traced by the render it
  // resumes, so the strategy traces sample 0's camera rays once more, for their AOVs alone
  // (Film::read_aovs), without adding anything to the film.
  bool retrace_aovs() const { return first_sample > 0 && wants_aovs(settings.outputs); }
  // Whether the film must keep running sums even for one sample (to resume from, or to be
  // resumed): a strategy then does not encode a one-sample frame itself.
  bool summing() const {
    return settings.resume != nullptr || settings.outputs.accumulation || settings.outputs.variance;
  }
};

// One launch of a strategy of several kernels (multipass, wavefront), masked where a mask is
// given: counted in r.launches, its time and elements in `pass` (one of r.passes) and its
// device time in r.times. Returns the elements written.
inline int64_t run_pass(rill::Kernel& k, const std::optional<rill::StateMask>& mask,
                        PassStats& pass, RenderResult& r) {
  ++r.launches;
  rill::Stopwatch launch;
  const int64_t written = mask ? k.execute(*mask) : k.execute();
  pass.ms += launch.ms();
  r.times.add_kernel(k.last_launch().device_ms);
  ++pass.calls;
  pass.processed += k.last_launch().processed;
  pass.written += written;
  return written;
}

// The AOV streams of such a strategy: the camera ray's AOVs in `aov` (and the path
// integrator's albedo).
inline AovStreams aov_streams(const rill::Stream<Aov>& aov,
                              const rill::Stream<rill::Float3>* albedo = nullptr) {
  return AovStreams{aov.field<rill::Float>("depth"), aov.field<rill::Int>("prim"),
                    aov.field<rill::Float3>("normal"), albedo};
}

// The end of such a frame: the launch time is its passes', and the film finishes (with the
// AOVs read after sample 0, Film::read_aovs).
inline void finish_passes(Film& film, const FrameOutputs& want, RenderResult& r) {
  r.times.launch = 0;
  for (const PassStats& p : r.passes) r.times.launch += p.ms;
  film.finish(want, r);
}

class RenderStrategy {
 public:
  virtual ~RenderStrategy() = default;
  // Renders frame.spp samples of frame.width x frame.height pixels through the camera set in
  // the scene's CameraRays into r (a fresh result; its image vectors may hold the memory of
  // an earlier frame). Throws std::runtime_error for a backend that cannot run the frame.
  virtual void render(const Frame& frame, RenderResult& r) = 0;
};

}  // namespace rt
