// The film (after pbrt's): where a render's samples meet, on the device, and what of them
// comes back to the host.
//
// A strategy launches its kernels once per sample and hands each sample's colour stream to
// the film, which adds it to a running sum on the same backend (a compensated sum: a float
// sum and the rounding error it dropped, so many samples lose almost nothing). At the end,
// the film makes the mean and reads back only what FrameOutputs asks for: the 8-bit image
// is encoded on the device (Srgb8.h) into the very bytes of RenderResult::rgb8, so a PNG
// costs 3 bytes per pixel to read back and nothing to unpack. A strategy may encode a frame
// of one sample itself, where the colour is made (add_encoded): the film then only packs
// its pixels' bytes.
//
// Its buffers and kernels are kept per backend and accuracy and reused by later frames of
// the same size: a frame allocates nothing and uploads nothing. They are never shared
// between backends, so a tracer that renders on several in turn moves no data between them.
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "rill/rt/film/Srgb8.h"
#include "rill/rt/render/RenderResult.h"
#include "rill/rt/render/RenderSettings.h"

namespace rt {

// Where in its pixel sample k of a frame looks (sample 0 is the pixel centre, then the Halton
// (2, 3) sequence): the same on every machine and strategy.
glm::vec2 sample_offset(int k);

// The first sample's AOV streams, as a strategy wrote them.
struct AovStreams {
  rill::Stream<rill::Float> depth;
  rill::Stream<rill::Int> prim;
  rill::Stream<rill::Float3> normal;
  const rill::Stream<rill::Float3>* albedo = nullptr;  // the path integrator's, or none
};

class Film {
 public:
  Film();
  ~Film();
  Film(const Film&) = delete;
  Film& operator=(const Film&) = delete;

  // Starts a frame of up to spp samples on a backend. With `resume` (an earlier frame's
  // accumulation, of this size) its sums are uploaded and the frame goes on from them; with
  // `summing`, the film keeps running sums even for one sample (finish can then read them
  // back).
  void begin(const std::string& backend, rill::Accuracy a, int width, int height, int spp,
             const Accumulation* resume = nullptr, bool summing = false, bool squares = false);
  // Sample s's colour, just written by the strategy on the frame's backend.
  void add_sample(const rill::Stream<rill::Float3>& color, int s);
  // Instead, for a frame of one sample whose linear colour is not read back: the 8-bit image
  // that the strategy encoded itself, one Int per pixel (R + 256 G + 65536 B, each byte as
  // Srgb8Encoder gives it). The film packs it into RenderResult::rgb8's bytes.
  void add_encoded(const rill::Stream<rill::Int>& pixels);
  // The mean of the samples added (and resumed), encoded and read back as `want` asks, with
  // the first sample's AOVs; r.spp is their count. Adds the time it took to r.times.
  void finish(const AovStreams& aovs, const FrameOutputs& want, RenderResult& r);

 private:
  struct Buffers;
  // The 8-bit encoder, gathering from one colour stream (the strategy's, or the mean).
  rill::Program encode_program(const rill::Stream<rill::Float3>& color) const;
  // The same bytes from pixels encoded by add_encoded's strategy.
  rill::Program pack_program(const rill::Stream<rill::Int>& pixels) const;
  // The program that makes the 8-bit image from one of the two, compiled again when the
  // stream it gathers from is another.
  rill::Kernel& encoder_for(rill::StreamRef source, int width, int height, bool packed);

  rill::Uniform<rill::Int> first_{0, "first_sample"};
  rill::Uniform<rill::Float> samples_{1.0f, "samples"};
  rill::Uniform<rill::Int> width_{1, "film_width"};
  Srgb8Encoder srgb8_;
  rill::Program add_, mean_, add_squares_;
  std::map<std::string, std::unique_ptr<Buffers>> buffers_;  // per backend and accuracy
  Buffers* now_ = nullptr;                                   // the frame's
  bool summing_ = false;  // running sums (spp > 1, resumed, or their read-back wanted)
  bool squares_ = false;  // and the sum of the samples' squares (FrameOutputs::variance)
  int samples_done_ = 0;  // samples in the sums (resumed ones included)
  std::optional<rill::Stream<rill::Float3>> single_;  // spp == 1: the sample itself
  std::optional<rill::Stream<rill::Int>> encoded_;    // or its 8-bit encoding (add_encoded)
  double accumulate_ms_ = 0;
};

}  // namespace rt
