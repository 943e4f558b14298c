// The megakernel strategy (Sh style, after Moreno-Fortuny and McCool): one kernel instance
// per pixel. It makes the camera ray, then a RILL_DO ... RILL_UNTIL loop follows the path: a
// camera or secondary ray that hits gets its shader's emitted light and then one shadow ray
// per light; when the lights are done, the local colour is weighted as in the thesis's
// eq. 5.1 and the path continues with the shader's reflected or transmitted ray (a second
// branch goes on a small ray stack), until the path ends, the stack is empty and the loop
// finishes. A camera ray whose pixel lies outside the scene's box on screen
// (CameraRays::may_see_scene) is a miss without being made or walked.
//
// The kernel writes the ray count, the linear colour and the camera ray's AOVs (depth,
// primitive, normal; and the path integrator's albedo) in every render: what comes back to the
// host (FrameOutputs) and how many samples a pixel takes are launch-time choices, read back or
// looped over by render(), never compile-time ones. So one kernel per backend, accuracy and
// loop serves every render of a tracer: a render that adds --depth or --spp 2 compiles
// nothing (docs/raytracer.md, "What compiles a kernel"). The AOV writes and the film's
// encoding pass cost a frame little (docs/benchmarks/2026-12-07-first-image.md); a second
// compile costs seconds.
//
// Under the path integrator (SceneOptions::integrator, integrator/PathIntegrator.h) the kernel
// is another, and the loop shapes below do not apply (both names give the one path program).
// Each instance follows the paths of its pixel for several samples in one launch, one after
// the other (path regeneration): an instance whose path ended starts its next sample's camera
// ray in the next iteration, so the instances that run together (a simd lockstep group of 8
// pixels, a GPU's warp) do not wait, sample after sample, for the longest of their paths, as
// they did with one sample per launch, where Russian roulette ends a group's paths at
// different depths. The kernel adds each sample to the pixel's running sum itself, with the
// film's operations in the film's order (film_add), into the film's sum streams: every
// sample's arithmetic and the sum's are as with one sample per launch, and so the bits.
// RenderSettings::path_samples_per_launch (path_samples_per_launch below) sets how many samples
// a launch takes; with 1, or where the film keeps no sums or also the squares, each launch is
// one sample that the film adds. The AOVs a launch writes are its first sample's camera ray's
// (FirstHit::only_if): sample 0's in the launch that traces it, which render() hands to the
// film at once (Film::read_aovs).
//
// The loop has two shapes (MegakernelLoop, Tracer.h), with the same operations in the same
// order and so the same bits:
// - Ray: each iteration traces one ray and reacts to what it hit, a state (`mode`) telling a
//   shadow ray from the others. The walk has a single call site, so a GPU's lanes, each
//   holding a different kind of ray, still run it together.
// - Segment: each iteration traces a camera or secondary ray, shades what it hit and traces
//   that point's shadow rays in a light loop inside. It saves the iterations (and their state
//   merges) per light, and each walk is specialized to its kind of ray: the closest-hit walk
//   has no any-hit tests, and for shadow rays any-hit is a constant. The CPU backends run it
//   (megakernel_loop_for); on a GPU, lanes holding different kinds of rays would diverge.
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rill/rt/film/Film.h"
#include "rill/rt/integrator/PathIntegrator.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/DeviceScene.h"
#include "rill/rt/kernel/PerBackend.h"
#include "rill/rt/strategy/RenderStrategy.h"

namespace rt {

// The path megakernel's samples per launch when RenderSettings::path_samples_per_launch is 0
// and RILL_PATH_REGENERATE is not off: enough that a pixel's samples, not its longest path,
// set a launch's length; few enough that a render's after_pass (progress, a time limit, an
// interrupt) comes every few seconds at most.
constexpr int kPathSamplesPerLaunch = 16;
// RenderSettings::path_samples_per_launch as resolved for `backend`: 1 or more. A setting of
// 0 takes RILL_PATH_REGENERATE (`regenerate`: its value, or null where it is unset): on, 16;
// off, 1; unset, the backend's default, path_regeneration_default. Throws for a value other
// than on or off, naming it.
int path_samples_per_launch(int setting, const std::string& backend, const char* regenerate);
// The same, with RILL_PATH_REGENERATE read from the environment (once).
int path_samples_per_launch(int setting, const std::string& backend);
// Whether a backend regenerates paths by default: everywhere but on `simd`. There one sample
// per launch measured faster on most built-in scenes under the path integrator (glass, bounce,
// textured, thesis B and C: 1.03-1.14x) and slower on three with short walks (cornell-path,
// cornell, thesis A: up to 1.18x; docs/benchmarks/2026-12-08-simd-path-default.md): with one
// sample per launch a lockstep group's camera rays start together and walk the grid alike for
// a bounce or two, which regeneration gives up by mixing camera rays and later bounces in one
// group.
bool path_regeneration_default(const std::string& backend);

class Megakernel final : public RenderStrategy {
 public:
  explicit Megakernel(DeviceScene& scene);
  ~Megakernel() override;
  // The program with loop Ray or Segment (Segment's captured by the constructor, Ray's at its
  // first use), with lane groups walking the grid together or not (Options.h, Packets; the
  // kernel of a backend takes packets_for's choice).
  const rill::Program& program(MegakernelLoop loop, bool packets = false) const;
  // Compiled once per backend, accuracy and loop (Auto: the backend's, megakernel_loop_for),
  // whatever the render's outputs and samples per pixel.
  rill::Kernel& kernel(const std::string& backend, rill::Accuracy a,
                       MegakernelLoop loop = MegakernelLoop::Auto);
  void render(const Frame& frame, RenderResult& r) override;

 private:
  struct PathLoop;
  struct Aovs;
  struct Buffers;  // a backend's output streams (PerBackend.h: buffers_for)
  // A resumed frame's AOVs: sample 0's camera rays traced once more (Frame::retrace_aovs).
  void retrace_aovs(rill::Kernel& k, Buffers& out, const Film::Sums& film_sums, RenderResult& r);
  rill::Program capture(MegakernelLoop loop) const;
  rill::Program capture_path() const;
  bool path() const { return S_.options.integrator == Integrator::Path; }
  static std::string kernel_key(const std::string& backend, rill::Accuracy a, MegakernelLoop loop);
  // The loop body's steps (Megakernel.cpp). Ray: trace, camera_or_secondary_ray or
  // shadow_ray_back, next_ray once the lights are done, pop_or_finish.
  Hit trace(PathLoop& L) const;
  void set_surface(Surface& to, const Surface& from) const;
  MaterialTable::Slots begin_surface(PathLoop& L, const Hit& hit, Aovs& aovs) const;
  void miss(PathLoop& L) const;
  void camera_or_secondary_ray(PathLoop& L, const Hit& hit, Aovs& aovs) const;
  void shadow_ray_back(PathLoop& L, const Hit& hit) const;
  void shadow_ray_to_light(PathLoop& L) const;
  // Segment: path_segment (which ends with next_ray), pop_or_finish.
  void path_segment(PathLoop& L, Aovs& aovs) const;
  void shadowed_lights(PathLoop& L, const MaterialTable::Slots& slots) const;
  void area_shadowed_lights(PathLoop& L, const MaterialTable::Slots& slots) const;
  // Area lights (F.area_lights): what keys the surface's samples; none without.
  std::optional<LightKey> light_key(const PathLoop& L) const;
  void next_ray(PathLoop& L, const MaterialTable::Slots* slots = nullptr) const;
  void pop_or_finish(PathLoop& L) const;

  DeviceScene& S_;
  std::unique_ptr<PathIntegrator> path_;  // under Integrator::Path
  // The loop's iteration limit; 0 skips all tracing (render()'s warm-up launch).
  rill::Uniform<Int> max_iter_{64, "max_iterations"};
  // The path program's samples: the launch's first and count, whether they add to the sums
  // read (else each restarts the sum), and the offset in its pixel (sample_offset, made on the
  // host) of each: uniforms, not an array, since the glsl backend's kernels have 32 textures
  // at most and a textured scene's path kernel uses them all.
  rill::Uniform<Int> path_first_{0, "path_first_sample"}, path_samples_{1, "path_samples"};
  rill::Uniform<Int> path_accumulate_{0, "path_accumulate"};
  std::vector<std::unique_ptr<rill::Uniform<Float2>>> sample_offsets_;
  // The offset of the launch's sample path_first_ + i (i < kPathSamplesPerLaunch).
  Float2 launch_sample_offset(const Int& i) const;
  // Captured on demand, from const accessors (Tracer::program is const): a GPU never needs
  // Segment's program beyond the constructor's, a CPU backend never Ray's.
  mutable std::map<std::pair<MegakernelLoop, bool>, rill::Program> programs_;
  std::map<std::string, rill::Kernel> kernels_;
  std::map<std::string, std::unique_ptr<Buffers>> buffers_;  // per backend and accuracy
  std::set<std::pair<std::string, int64_t>> warmed_;         // kernels launched at a size before
};

}  // namespace rt
