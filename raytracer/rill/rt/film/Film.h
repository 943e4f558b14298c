// The film (after pbrt's): where a render's samples meet, on the device, and what of them
// comes back to the host.
//
// A strategy launches its kernels once per sample and hands each sample's colour stream to
// the film, which adds it to a running sum on the same backend (a compensated sum: a float
// sum and the rounding error it dropped, so many samples lose almost nothing). At the end,
// the film makes the mean and reads back only what FrameOutputs asks for (the AOVs, sample
// 0's, it read right after the launch that traced them: read_aovs): the 8-bit image
// is encoded on the device (Srgb8.h) into the very bytes of RenderResult::rgb8, so a PNG
// costs 3 bytes per pixel to read back and nothing to unpack.
//
// Its buffers and kernels are kept per backend and accuracy and reused by later frames of
// the same size: a frame allocates nothing and uploads nothing. Each kernel is compiled at
// the first frame that needs it: a first image of one sample compiles no sum. They are never shared
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

// The film's running sum after one more sample `color`: a compensated sum (a float sum and
// the rounding error it dropped, Knuth's two-sum, exact without FMA contraction or
// reassociation, which strict rules out; the errors add up in the carry). `first` starts
// both. The film's own sum kernel and a strategy that sums its samples in its kernel (the
// path megakernel, Megakernel.h) use it, so both give the same bits.
struct FilmSum {
  rill::Float3 sum, carry;
};
FilmSum film_add(const rill::Float3& sum, const rill::Float3& carry, const rill::Float3& color,
                 const rill::Bool& first);

// A strategy's AOV streams, holding sample 0's just after the launch that traced its camera
// rays (the launches of later samples write over them).
struct AovStreams {
  rill::Stream<rill::Float> depth;
  rill::Stream<rill::Int> prim;
  rill::Stream<rill::Float3> normal;
  const rill::Stream<rill::Float3>* albedo = nullptr;  // the path integrator's, or none
};

// Whether `want` asks for any AOV (depth, prim, normal, albedo).
bool wants_aovs(const FrameOutputs& want);

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
  // Compiles now the 8-bit encoder that finish() will run for a frame whose samples the
  // strategy writes to `color` (a strategy does this while its own kernel compiles).
  void prepare_encoder(const rill::Stream<rill::Float3>& color);
  // Sample s's colour, just written by the strategy on the frame's backend.
  void add_sample(const rill::Stream<rill::Float3>& color, int s);
  // The running sums (film_add) of a frame that keeps them and no squares, for a strategy
  // that adds samples to them in its own kernel (then it calls added_samples);
  // both null otherwise.
  struct Sums {
    rill::Stream<rill::Float3>* sum = nullptr;
    rill::Stream<rill::Float3>* carry = nullptr;
  };
  Sums sums();
  // n samples added to sums() by the strategy, in order after those before.
  void added_samples(int n) { samples_done_ += n; }
  // Sample 0's AOVs, read back into r now as `want` asks (the others emptied), once per frame:
  // right after the launch that traced sample 0, or, in a resumed frame, after a launch that
  // traced sample 0's camera rays once more without adding it to the film. The AOVs are
  // sample 0's, the pixel centre's, however many samples follow and however they are
  // launched. Adds the time it took to r.times.read_back.
  void read_aovs(const AovStreams& aovs, const FrameOutputs& want, RenderResult& r);
  // The mean of the samples added (and resumed), encoded and read back as `want` asks, with
  // the AOVs read_aovs read; r.spp is their count. Adds the time it took to r.times. Throws
  // std::logic_error where `want` asks for an AOV and read_aovs was not called.
  void finish(const FrameOutputs& want, RenderResult& r);
  // Whether read_aovs() and finish() may leave the read-backs in flight
  // (RenderSettings::read_back_later, set by the Tracer per frame): finish() then puts them in
  // r.in_flight. The variance and the accumulation are read at once.
  void read_back_later(bool later) { later_ = later; }
  // Waits for the read-backs a frame that did not finish left in flight (its strategy threw),
  // so that the result's memory may go.
  void wait_read_backs() { flight_.reset(); }

 private:
  struct Buffers;
  // The 8-bit encoder, gathering from one colour stream (the strategy's, or the mean).
  rill::Program encode_program(const rill::Stream<rill::Float3>& color) const;
  // That program for the frame's colour stream, compiled again when the stream it gathers
  // from is another.
  rill::Kernel& encoder_for(const rill::Stream<rill::Float3>& source, int width, int height);

  rill::Uniform<rill::Int> first_{0, "first_sample"};
  rill::Uniform<rill::Float> samples_{1.0f, "samples"};
  rill::Uniform<rill::Int> width_{1, "film_width"};
  Srgb8Encoder srgb8_;
  rill::Program add_, mean_, add_squares_;
  std::map<std::string, std::unique_ptr<Buffers>> buffers_;  // per backend and accuracy
  Buffers* now_ = nullptr;                                   // the frame's
  bool summing_ = false;    // running sums (spp > 1, resumed, or their read-back wanted)
  bool squares_ = false;    // and the sum of the samples' squares (FrameOutputs::variance)
  int samples_done_ = 0;    // samples in the sums (resumed ones included)
  bool aovs_read_ = false;  // read_aovs was called in this frame
  std::optional<rill::Stream<rill::Float3>> single_;  // spp == 1: the sample itself
  double accumulate_ms_ = 0;
  bool later_ = false;
  // The frame's read-backs started so far when they may stay in flight (later_), handed to
  // the result by finish().
  std::shared_ptr<OutputsInFlight> flight_;
  // The read-backs in flight for `want`, made at the frame's first; null when they are read
  // at once.
  OutputsInFlight* flight(const FrameOutputs& want);
};

}  // namespace rt
