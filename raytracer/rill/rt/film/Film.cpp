// The film (Film.h): a compensated sum of the samples on the device, their mean, and the
// read-back of what was asked for.
#include "rill/rt/film/Film.h"

#include <algorithm>
#include <array>
#include <bit>
#include <functional>
#include <span>
#include <stdexcept>

#include "rill/Stopwatch.h"

#include "rill/rt/film/Srgb8.h"
#include "rill/rt/kernel/Compile.h"
#include "rill/rt/kernel/PerBackend.h"
#include "rill/rt/render/OutputsInFlight.h"

namespace rt {

using namespace rill;

// One backend's kernels and the streams of its last frame size.
struct Film::Buffers {
  Buffers(const std::string& backend, Accuracy a) : backend(backend), accuracy(a) {}
  // The sum's kernels, compiled at the first frame that sums (not for a first image of one
  // sample: each is another compiler run before it).
  void summing(const Film& film) {
    if (!add) add.emplace(compile_for(film.add_, backend, accuracy));
    if (!mean) mean.emplace(compile_for(film.mean_, backend, accuracy));
  }
  void resize(int w, int h) {
    if (w == width && h == height) return;
    width = w;
    height = h;
    sum.emplace(w, h, "film_sum");
    carry.emplace(w, h, "film_carry");
    mean_color.emplace(w, h, "film_mean");
    squares.reset();
  }
  std::optional<Kernel> add, mean;
  std::string backend;
  Accuracy accuracy;
  int width = 0, height = 0;  // of sum, carry and mean_color (made for frames of spp > 1)
  std::optional<Stream<Float3>> sum, carry, mean_color;
  std::optional<Stream<Float3>> squares;  // made at a frame's first use (FrameOutputs::variance)
  std::optional<Kernel> add_squares;
  // The encoder gathers from the colour stream it was captured with: it is captured again
  // when a frame's colour is another stream (another size, or the other strategy's).
  std::optional<Kernel> encode;
  std::shared_ptr<detail::StreamState> encode_source;
  glm::ivec2 encode_size{0};
  std::optional<Stream<Int3>> packed;  // the 8-bit image as bytes, 4 pixels per element
};

FilmSum film_add(const Float3& sum, const Float3& carry, const Float3& color, const Bool& first) {
  Float3 s = sum + color;
  Float3 back = s - sum;
  Float3 error = (sum - (s - back)) + (color - back);
  return FilmSum{select(first, color, s), select(first, Float3(0.0f), carry + error)};
}

Film::Film() {
  add_ = program("rill_film_add", [&] {
    Input<Float3> sum("sum"), carry("carry"), color("color");
    Output<Float3> new_sum("new_sum"), new_carry("new_carry");
    const FilmSum next = film_add(sum, carry, color, first_ != 0);
    new_sum = next.sum;
    new_carry = next.carry;
  });
  // The samples' squares, summed in float for the variance (an estimate: no carry).
  add_squares_ = program("rill_film_add_squares", [&] {
    Input<Float3> squares("squares"), color("color");
    Output<Float3> new_squares("new_squares");
    new_squares = select(first_ != 0, color * color, squares + color * color);
  });
  mean_ = program("rill_film_mean", [&] {
    Input<Float3> sum("sum"), carry("carry");
    Output<Float3> mean("mean");
    mean = (sum + carry) / samples_;
  });
}

glm::vec2 sample_offset(int k) {
  if (k == 0) return glm::vec2(0.5f);
  // Halton (2, 3): a low-discrepancy sequence, the same on every machine.
  auto halton = [](int i, int b) {
    double f = 1.0, r = 0.0;
    for (; i > 0; i /= b) {
      f /= b;
      r += f * (i % b);
    }
    return static_cast<float>(r);
  };
  return glm::vec2(halton(k, 2), halton(k, 3));
}

namespace {

// An output asked for, read straight into the result (whose memory a caller that renders
// frame after frame into one RenderResult keeps); one not asked for is emptied.
// With `flight`, the read-back is started and left there (the backend keeps a copy of what
// it reads, so later launches may write the stream at once: rill/ReadBack.h).
template <typename S, typename V>
void read_into(const S& stream, V& into, bool wanted, OutputsInFlight* flight = nullptr) {
  if (!wanted) return into.clear();
  into.resize(static_cast<size_t>(stream.size()));
  if (flight)
    flight->reads.push_back(stream.download_async(std::span(into)));
  else
    stream.download_into(std::span(into));
}

// Element i makes pixels 4i .. 4i + 3 into 12 bytes, R G B R G B ..., as three little-endian
// Ints: the memory of the 8-bit image itself, which is read back into RenderResult::rgb8 as
// it is, with nothing to unpack on the host. rgb(x, y) gives a pixel's three bytes.
Program rgb8_program(const char* name, const Uniform<Int>& width,
                     const std::function<std::array<Int, 3>(const Int&, const Int&)>& rgb) {
  return program(name, [&] {
    Output<Int3> out("rgb");
    // One division for the first pixel's (x, y); the next three step along the row, onto
    // the next rows where they end (up to three times over for images 1 to 3 wide). Past
    // the last pixel the gather's clamp reads some pixel of the image: those bytes are cut
    // off on the host.
    Int first = element_index() * 4;
    Int y0 = first / width;
    Int x0 = first - y0 * width;
    std::vector<Int> bytes;
    for (int k = 0; k < 4; ++k) {
      Int x = x0 + k, y = y0;
      for (int wrap = 0; wrap < k; ++wrap) {
        Bool past = x >= width;
        x = select(past, x - width, x);
        y = select(past, y + 1, y);
      }
      for (const Int& b : rgb(x, y)) bytes.push_back(b);
    }
    auto word = [&](int w) {  // integer arithmetic wraps: the top byte lands in the sign bit
      return bytes[4 * w] + bytes[4 * w + 1] * 256 + bytes[4 * w + 2] * 65536 +
             bytes[4 * w + 3] * 16777216;
    };
    out = Int3(word(0), word(1), word(2));
  });
}

}  // namespace

Program Film::encode_program(const Stream<Float3>& color) const {
  return rgb8_program("rill_film_encode", width_, [&](const Int& x, const Int& y) {
    Float3 c = color(x, y);
    return std::array<Int, 3>{srgb8_.encode(c[0]), srgb8_.encode(c[1]), srgb8_.encode(c[2])};
  });
}

Film::~Film() = default;

void Film::begin(const std::string& backend, Accuracy a, int width, int height, int spp,
                 const Accumulation* resume, bool summing, bool squares) {
  const std::string key = backend_key(backend, a);
  auto it = buffers_.find(key);
  if (it == buffers_.end()) it = buffers_.emplace(key, std::make_unique<Buffers>(backend, a)).first;
  now_ = it->second.get();
  summing_ = spp > 1 || summing || resume != nullptr || squares;
  if (summing_) {
    now_->summing(*this);
    now_->resize(width, height);
  }
  // The variance needs every sample's square: of a resumed render, only if its accumulation
  // kept them.
  squares_ = squares && (resume == nullptr || !resume->squares.empty());
  if (squares_ && !now_->squares) {
    now_->squares.emplace(width, height, "film_squares");
    now_->add_squares.emplace(compile_for(add_squares_, backend, a));
  }
  samples_done_ = 0;
  if (resume != nullptr) {
    const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (resume->width != width || resume->height != height || resume->sum.size() != n ||
        resume->carry.size() != n || resume->samples < 1 ||
        (!resume->squares.empty() && resume->squares.size() != n))
      throw std::invalid_argument(
          "Film: the accumulation to resume is of " + std::to_string(resume->width) + "x" +
          std::to_string(resume->height) + " pixels and " + std::to_string(resume->samples) +
          " samples, the frame is " + std::to_string(width) + "x" + std::to_string(height));
    now_->sum->upload(resume->sum);
    now_->carry->upload(resume->carry);
    if (squares_) now_->squares->upload(resume->squares);
    samples_done_ = resume->samples;
  }
  // The encoder holds the colour stream it gathers from: one of another size goes now,
  // before the strategy makes this frame's streams (PerBackend.h: the old streams go first).
  if (now_->encode_source && (now_->encode_size.x != width || now_->encode_size.y != height)) {
    now_->encode.reset();
    now_->encode_source.reset();
  }
  single_.reset();
  accumulate_ms_ = 0;
  aovs_read_ = false;
  flight_.reset();
}

OutputsInFlight* Film::flight(const FrameOutputs& want) {
  if (!later_ || want.variance || want.accumulation) return nullptr;
  if (!flight_) flight_ = std::make_shared<OutputsInFlight>();
  return flight_.get();
}

Film::Sums Film::sums() {
  if (!summing_ || squares_) return Sums{};
  return Sums{&*now_->sum, &*now_->carry};
}

void Film::add_sample(const Stream<Float3>& color, int s) {
  ++samples_done_;
  if (!summing_) {
    single_ = color;
    return;
  }
  Stopwatch add;
  first_.set(s == 0 ? 1 : 0);
  now_->add->inputs(*now_->sum, *now_->carry, color).outputs(*now_->sum, *now_->carry);
  now_->add->execute();
  if (squares_) {
    now_->add_squares->inputs(*now_->squares, color).outputs(*now_->squares);
    now_->add_squares->execute();
  }
  accumulate_ms_ += add.ms();
}

Kernel& Film::encoder_for(const Stream<Float3>& source, int width, int height) {
  if (!now_->encode || now_->encode_source != StreamRef(source).shared()) {
    now_->encode.emplace(compile_for(encode_program(source), now_->backend, now_->accuracy));
    now_->encode_source = StreamRef(source).shared();
    now_->encode_size = {width, height};
  }
  return *now_->encode;
}

void Film::prepare_encoder(const Stream<Float3>& color) {
  // The stream finish() encodes: the mean when summing, else the sample itself.
  const Stream<Float3>& source = summing_ ? *now_->mean_color : color;
  encoder_for(source, static_cast<int>(source.width()), static_cast<int>(source.height()));
}

bool wants_aovs(const FrameOutputs& want) {
  return want.depth || want.prim || want.normal || want.albedo;
}

void Film::read_aovs(const AovStreams& aovs, const FrameOutputs& want, RenderResult& r) {
  Stopwatch step;
  OutputsInFlight* later = flight(want);
  read_into(aovs.depth, r.depth, want.depth, later);
  read_into(aovs.prim, r.prim, want.prim, later);
  read_into(aovs.normal, r.normal, want.normal, later);
  if (aovs.albedo)
    read_into(*aovs.albedo, r.albedo, want.albedo, later);
  else
    r.albedo.clear();
  aovs_read_ = true;
  r.times.read_back += step.ms();
}

void Film::finish(const FrameOutputs& want, RenderResult& r) {
  Stopwatch step;
  // The colour stream: one sample's or the mean.
  const Stream<Float3> color = summing_ ? *now_->mean_color : *single_;
  r.spp = samples_done_;
  if (summing_) {
    samples_.set(static_cast<float>(samples_done_));
    now_->mean->inputs(*now_->sum, *now_->carry).outputs(color);
    now_->mean->execute();
    accumulate_ms_ += step.lap();
  }
  r.times.accumulate += accumulate_ms_;
  if (!aovs_read_) {
    // A strategy that does not read its AOVs would give empty ones where they were asked for.
    if (wants_aovs(want))
      throw std::logic_error("Film::finish: AOVs were asked for and the strategy read none");
    r.depth.clear();
    r.prim.clear();
    r.normal.clear();
    r.albedo.clear();
  }
  OutputsInFlight* later = flight(want);
  read_into(color, r.color, want.color, later);
  r.variance.clear();
  if (want.variance && squares_) {
    // (squares / n - mean^2) n / (n - 1) / n, in double on the host; 0 below 2 samples.
    std::vector<glm::vec3> sq, mean;
    read_into(*now_->squares, sq, true);
    if (want.color)
      mean = r.color;
    else
      read_into(color, mean, true);
    const double n = samples_done_;
    r.variance.resize(sq.size());
    for (size_t p = 0; p < sq.size(); ++p)
      for (int c = 0; c < 3; ++c) {
        const double m = mean[p][c], v = n > 1 ? (sq[p][c] / n - m * m) / (n - 1) : 0.0;
        r.variance[p][c] = static_cast<float>(std::max(v, 0.0));
      }
  }
  r.accumulation = Accumulation{};
  if (want.accumulation && summing_) {
    r.accumulation.width = static_cast<int>(now_->sum->width());
    r.accumulation.height = static_cast<int>(now_->sum->height());
    r.accumulation.samples = samples_done_;
    read_into(*now_->sum, r.accumulation.sum, true);
    read_into(*now_->carry, r.accumulation.carry, true);
    if (squares_) read_into(*now_->squares, r.accumulation.squares, true);
  }
  if (!want.rgb8) r.rgb8.clear();
  if (want.rgb8) {
    static_assert(std::endian::native == std::endian::little,
                  "the 8-bit image is read back as little-endian Ints");
    const int64_t n = color.size(), groups = (n + 3) / 4;
    const int width = static_cast<int>(color.width());
    const int height = static_cast<int>(color.height());
    if (!now_->packed || now_->packed->size() != groups) now_->packed.emplace(groups, "film_rgb8");
    Kernel& encode = encoder_for(color, width, height);
    width_.set(static_cast<int32_t>(width));
    encode.outputs(*now_->packed);
    encode.execute();
    // Read straight into the image's memory (a frame of the last one's size keeps it and
    // does not clear it), with room for the last group's padding, then cut to 3 n bytes.
    r.rgb8.resize(static_cast<size_t>(groups) * 12);
    const std::span<glm::ivec3> words(reinterpret_cast<glm::ivec3*>(r.rgb8.data()),
                                      static_cast<size_t>(groups));
    if (later) {
      later->reads.push_back(now_->packed->download_async(words));
      later->rgb8_bytes = static_cast<size_t>(n) * 3;
    } else {
      now_->packed->download_into(words);
      r.rgb8.resize(static_cast<size_t>(n) * 3);
    }
  }
  r.times.read_back += step.ms();
  if (flight_) {
    // Nothing left in flight (a backend that reads back at once): finished here.
    const bool any = std::any_of(flight_->reads.begin(), flight_->reads.end(),
                                 [](const ReadBack& b) { return b.in_flight(); });
    r.in_flight = std::move(flight_);
    if (!any) r.wait_outputs();
  }
}

}  // namespace rt
