// The film (Film.h): a compensated sum of the samples on the device, their mean, and the
// read-back of what was asked for.
#include "rill/rt/film/Film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <span>

#include "rill/Stopwatch.h"

#include "rill/rt/film/Srgb8.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/PerBackend.h"

namespace rt {

using namespace rill;

// One backend's kernels and the streams of its last frame size.
struct Film::Buffers {
  Buffers(const Film& film, const std::string& backend, Accuracy a)
      : add(compile_for(film.add_, backend, a)),
        mean(compile_for(film.mean_, backend, a)),
        encode(compile_for(film.encode_, backend, a)) {}
  void resize(int w, int h) {
    if (w == width && h == height) return;
    width = w;
    height = h;
    sum.emplace(w, h, "film_sum");
    carry.emplace(w, h, "film_carry");
    mean_color.emplace(w, h, "film_mean");
  }
  Kernel add, mean, encode;
  int width = 0, height = 0;  // of sum, carry and mean_color (made for frames of spp > 1)
  std::optional<Stream<Float3>> sum, carry, mean_color;
  std::optional<Stream<Int>> packed;  // the 8-bit image, at the size last encoded
  std::vector<int32_t> packed_host;   // and its host copy, kept for the next frame
};

Film::Film() {
  // sum + colour as a float and the error that rounding dropped (Knuth's two-sum, exact
  // without FMA contraction or reassociation, which strict rules out); the errors add up
  // in the carry. The first sample starts both.
  add_ = program("rill_film_add", [&] {
    Input<Float3> sum("sum"), carry("carry"), color("color");
    Output<Float3> new_sum("new_sum"), new_carry("new_carry");
    Float3 s = sum + color;
    Float3 back = s - sum;
    Float3 error = (sum - (s - back)) + (color - back);
    Bool first = first_ != 0;
    new_sum = select(first, color, s);
    new_carry = select(first, Float3(0.0f), carry + error);
  });
  mean_ = program("rill_film_mean", [&] {
    Input<Float3> sum("sum"), carry("carry");
    Output<Float3> mean("mean");
    mean = (sum + carry) / samples_;
  });
  encode_ = program("rill_film_encode", [&] {
    Input<Float3> color("color");
    Output<Int> rgb8("rgb8");
    rgb8 = pack_rgb8(srgb8_.encode(color.x()), srgb8_.encode(color.y()), srgb8_.encode(color.z()));
  });
}

Film::~Film() = default;

void Film::begin(const std::string& backend, Accuracy a, int width, int height, int spp) {
  const std::string key = backend_key(backend, a);
  auto it = buffers_.find(key);
  if (it == buffers_.end())
    it = buffers_.emplace(key, std::make_unique<Buffers>(*this, backend, a)).first;
  now_ = it->second.get();
  if (spp > 1) now_->resize(width, height);
  spp_ = spp;
  single_.reset();
  accumulate_ms_ = 0;
}

void Film::add_sample(const Stream<Float3>& color, int s) {
  if (spp_ == 1) {
    single_ = color;
    return;
  }
  Stopwatch add;
  first_.set(s == 0 ? 1 : 0);
  now_->add.inputs(*now_->sum, *now_->carry, color).outputs(*now_->sum, *now_->carry);
  now_->add.execute();
  accumulate_ms_ += add.ms();
}

void Film::finish(const AovStreams& aovs, const FrameOutputs& want, RenderResult& r) {
  Stopwatch step;
  Stream<Float3> color = spp_ == 1 ? *single_ : *now_->mean_color;
  if (spp_ > 1) {
    samples_.set(static_cast<float>(spp_));
    now_->mean.inputs(*now_->sum, *now_->carry).outputs(color);
    now_->mean.execute();
    accumulate_ms_ += step.lap();
  }
  r.times.accumulate += accumulate_ms_;
  // Each output asked for is read straight into the result (whose memory a caller that
  // renders frame after frame into one RenderResult keeps); the others are emptied.
  auto read = [](const auto& stream, auto& into, bool wanted) {
    if (!wanted) return into.clear();
    into.resize(static_cast<size_t>(stream.size()));
    stream.download_into(std::span(into));
  };
  read(color, r.color, want.color);
  read(aovs.depth, r.depth, want.depth);
  read(aovs.prim, r.prim, want.prim);
  read(aovs.normal, r.normal, want.normal);
  if (!want.rgb8) r.rgb8.clear();
  if (want.rgb8) {
    if (!now_->packed || now_->packed->width() != color.width() ||
        now_->packed->height() != color.height())
      now_->packed.emplace(color.width(), color.height(), "film_rgb8");
    now_->encode.inputs(color).outputs(*now_->packed);
    now_->encode.execute();
    read(*now_->packed, now_->packed_host, true);
    const size_t n = now_->packed_host.size();
    r.rgb8.resize(n * 3);  // every byte is written below: a frame of the last one's size
                           // keeps its memory and is not cleared first
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 14), [&](const auto& range) {
      for (size_t p = range.begin(); p < range.end(); ++p)
        unpack_rgb8(static_cast<uint32_t>(now_->packed_host[p]), &r.rgb8[p * 3]);
    });
  }
  r.times.read_back += step.ms();
}

}  // namespace rt
