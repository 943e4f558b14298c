// The tile farm (Farm.h): rank 0's loop, which hands out tiles, renders some itself and
// watches the other ranks, and the workers' loop. In both the main thread only talks (MPI,
// heartbeats, deadlines) and polls; loading and rendering run on a thread beside it, so a
// rank busy with a long tile still answers within half a second.
#include "distributed/Farm.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <deque>
#include <exception>
#include <limits>
#include <map>
#include <memory>
#include <thread>

#include "ProgressBar.h"
#include "distributed/AccumulationSlice.h"
#include "rill/rt/scene/Scene.h"

namespace rt::distributed {

namespace {

// Tiles a worker holds at once: the one it renders and the next, so it never waits for one.
constexpr int kAhead = 2;

// How often the render loops poll MPI: every millisecond, and every 50 microseconds while a
// message they sent is still on its way.
constexpr std::chrono::microseconds kPoll(1000), kSendingPoll(50);

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void nap() {
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g s", s);
  return buf;
}

volatile std::sig_atomic_t g_signal = 0;
// Whether it came from this process's parent: mpirun (or its daemon) ending the job, as it
// does when a rank dies or when mpirun itself is interrupted. Otherwise someone signalled
// rank 0 itself (kill, a scheduler): an interrupt, after which the other ranks are stopped.
volatile std::sig_atomic_t g_from_launcher = 0;
void on_signal(int sig, siginfo_t* info, void*) {
  if (g_signal != 0) return;
  // getppid is async-signal-safe; si_pid is the sender for a kill() (0 from the kernel).
  g_from_launcher = info != nullptr && info->si_pid != 0 && info->si_pid == getppid();
  g_signal = sig;
}

// A function's result, computed on the farm's lane (below), polled by the main thread.
template <class T>
class Background {
 public:
  void start(Lane& lane, std::function<T()> f) {
    s_ = std::make_shared<State>();
    lane.post([s = s_, f = std::move(f)] {
      try {
        s->value = f();
      } catch (...) {
        s->error = std::current_exception();
      }
      s->done = true;
    });
  }
  bool idle() const { return s_ == nullptr; }
  bool ready() const { return s_ != nullptr && s_->done; }
  bool running() const { return s_ != nullptr && !s_->done; }
  // The result (or the exception) of a ready function; idle afterwards.
  T take() {
    std::shared_ptr<State> s = std::move(s_);
    if (s->error) std::rethrow_exception(s->error);
    return std::move(s->value);
  }

 private:
  struct State {
    std::atomic<bool> done{false};
    T value{};
    std::exception_ptr error;
  };
  std::shared_ptr<State> s_;
};

// An image of the outputs asked for, every pixel as a miss with nothing behind it.
RenderResult blank_image(int width, int height, const FrameOutputs& o) {
  RenderResult r;
  r.width = width;
  r.height = height;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  if (o.color) r.color.assign(n, glm::vec3(0.0f));
  if (o.rgb8) r.rgb8.assign(3 * n, 0);
  if (o.depth) r.depth.assign(n, std::numeric_limits<float>::infinity());
  if (o.prim) r.prim.assign(n, -1);
  if (o.normal) r.normal.assign(n, glm::vec3(0.0f));
  // The albedo and variance are left to the first tile that brings them (place): the tracer
  // leaves them out where it has none (the albedo under Whitted), and the image must hold the
  // channels a single-process render would, no more. So are the sums' squares.
  if (o.accumulation) {
    r.accumulation.width = width;
    r.accumulation.height = height;
    r.accumulation.sum.assign(n, glm::vec3(0.0f));
    r.accumulation.carry.assign(n, glm::vec3(0.0f));
  }
  return r;
}

// Why a tile's pixels do not fit the tile (empty if they do): a round's tile must also bring
// its sums of the round's samples (spp; 0: any).
std::string misfit(const RenderResult& p, const Tile& t, const FrameOutputs& o, int spp) {
  const size_t n = static_cast<size_t>(t.width) * static_cast<size_t>(t.height);
  auto sized = [&](bool wanted, size_t got, size_t per_pixel) {
    return got == (wanted ? n * per_pixel : 0);
  };
  if (p.width != t.width || p.height != t.height)
    return "a " + std::to_string(p.width) + "x" + std::to_string(p.height) + " tile for a " +
           std::to_string(t.width) + "x" + std::to_string(t.height) + " one";
  if (!sized(o.color, p.color.size(), 1) || !sized(o.rgb8, p.rgb8.size(), 3) ||
      !sized(o.depth, p.depth.size(), 1) || !sized(o.prim, p.prim.size(), 1) ||
      !sized(o.normal, p.normal.size(), 1))
    return "other outputs than were asked for";
  // Asked for, the albedo and variance may still be absent (place), but never cut short.
  if ((!p.albedo.empty() && !sized(o.albedo, p.albedo.size(), 1)) ||
      (!p.variance.empty() && !sized(o.variance, p.variance.size(), 1)))
    return "other outputs than were asked for";
  const Accumulation& a = p.accumulation;
  if (o.accumulation &&
      (a.width != t.width || a.height != t.height || a.sum.size() != n || a.carry.size() != n ||
       (!a.squares.empty() && a.squares.size() != n) || (spp > 0 && a.samples != spp)))
    return "no sums, or sums that do not fit the tile";
  return {};
}

// Copies a tile's rows into the image.
void place(RenderResult& image, const Tile& t, const RenderResult& p) {
  auto rows = [&](auto& dst, const auto& src, int per_pixel) {
    if (src.empty()) return;
    for (int y = 0; y < t.height; ++y) {
      const size_t from = static_cast<size_t>(y) * t.width * per_pixel;
      const size_t to = (static_cast<size_t>(t.y + y) * image.width + t.x) * per_pixel;
      std::copy(src.begin() + from, src.begin() + from + t.width * per_pixel, dst.begin() + to);
    }
  };
  rows(image.color, p.color, 1);
  rows(image.rgb8, p.rgb8, 3);
  rows(image.depth, p.depth, 1);
  rows(image.prim, p.prim, 1);
  rows(image.normal, p.normal, 1);
  // The albedo and variance come with the first tile that has them (blank_image).
  const size_t n = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (!p.albedo.empty() && image.albedo.empty()) image.albedo.assign(n, glm::vec3(0.0f));
  if (!p.variance.empty() && image.variance.empty()) image.variance.assign(n, glm::vec3(0.0f));
  rows(image.albedo, p.albedo, 1);
  rows(image.variance, p.variance, 1);
  if (!p.accumulation.sum.empty()) {
    place_slice(image.accumulation, t, p.accumulation);
    image.accumulation.samples = p.accumulation.samples;
  }
  image.spp = p.spp;
  image.rays += p.rays;
}

}  // namespace

struct Farm::Peer {
  std::string host, backend;
  bool hello = false;
  uint64_t hash = 0;
  bool alive = true;       // false: lost
  bool responsive = true;  // false: lost without a word
  std::string lost;
  double heard = 0;        // when it was last heard from
  double progress_at = 0;  // when it last returned a tile, or got one with none in hand
  int in_flight = 0;
  int tiles = 0;
  double busy_ms = 0;
};

Farm::Farm(MpiSession& mpi, const FarmOptions& options)
    : mpi_(mpi), o_(options), lane_(std::make_unique<Lane>()) {}
// Rank 0 answers SIGTERM and SIGINT by returning what it has (Farm.h); the handlers rill-trace
// had before come back afterwards.
struct Farm::Signals {
  Signals() {
    g_signal = 0;
    g_from_launcher = 0;
    struct sigaction sa {};
    sa.sa_sigaction = on_signal;
    sa.sa_flags = SA_SIGINFO;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, &term_);
    sigaction(SIGINT, &sa, &int_);
  }
  ~Signals() {
    sigaction(SIGTERM, &term_, nullptr);
    sigaction(SIGINT, &int_, nullptr);
  }
  Signals(const Signals&) = delete;
  Signals& operator=(const Signals&) = delete;

 private:
  struct sigaction term_ {
  }, int_{};
};

Farm::~Farm() = default;

void Farm::beat() {
  const double t = now_s();
  if (t - last_beat_ < o_.heartbeat) return;
  last_beat_ = t;
  if (mpi_.rank() != 0) return mpi_.post(0, kHeartbeat);
  // Lost ranks that said why (a failed render) wait for the stop: they hear from rank 0 too.
  for (int r = 1; r < mpi_.size(); ++r)
    if (peers_[static_cast<size_t>(r)].responsive) mpi_.post(r, kHeartbeat);
}

void Farm::lose(int rank, const std::string& why, bool responsive, TileQueue* queue) {
  Peer& p = peers_[static_cast<size_t>(rank)];
  if (!p.alive) return;
  p.alive = false;
  p.responsive = responsive;
  p.lost = why;
  for (char& c : p.lost)
    if (c == '\n') c = ' ';  // a backend's message may list devices line by line
  p.in_flight = 0;
  if (!responsive) mpi_.forget(rank);
  const int back = queue != nullptr ? queue->requeue(rank) : 0;
  const std::string w = "rank " + std::to_string(rank) + " on " +
                        (p.host.empty() ? std::string("an unknown host") : p.host) + " is lost (" +
                        p.lost + "); " +
                        (back > 0 ? std::to_string(back) + " of its tiles go to the other ranks"
                                  : std::string("the other ranks go on"));
  std::fprintf(stderr, "%srill-trace: warning: %s\n", o_.progress ? "\n" : "", w.c_str());
  warnings_.push_back(w);
}

void Farm::check_silence(TileQueue* queue) {
  const double t = now_s();
  if (mpi_.rank() != 0) {
    // Twice as long: rank 0, which holds the image, decides first. A worker that rank 0 gave
    // up on (it hung, then went on) hears nothing more from it, and is ended by rank 0's
    // MPI_Abort rather than by an exit of its own racing with that abort.
    if (t - heard0_ > 2 * o_.rank_timeout)
      throw std::runtime_error("rank 0 sent nothing for " + seconds_text(2 * o_.rank_timeout) +
                               " (crashed, killed or hung): this rank ends");
    return;
  }
  for (int r = 1; r < mpi_.size(); ++r) {
    Peer& p = peers_[static_cast<size_t>(r)];
    if (!p.alive) continue;
    if (t - p.heard > o_.rank_timeout)
      lose(r, "sent nothing for " + seconds_text(o_.rank_timeout) + ": crashed, killed or hung",
           false, queue);
    else if (o_.tile_timeout > 0 && p.in_flight > 0 && t - p.progress_at > o_.tile_timeout)
      lose(r, "no tile back within --tile-timeout " + seconds_text(o_.tile_timeout), false, queue);
  }
}

void Farm::start(const std::function<uint64_t()>& load, const std::string& backend) {
  backend_ = backend;
  last_beat_ = 0;
  if (mpi_.rank() == 0)
    start_master(load);
  else
    start_worker(load);
}

void Farm::start_worker(const std::function<uint64_t()>& load) {
  Background<uint64_t> job;
  job.start(*lane_, load);
  heard0_ = now_s();
  for (;;) {
    int source = 0, tag = 0;
    Bytes bytes;
    while (mpi_.receive(source, tag, bytes, o_.rank_timeout)) heard0_ = now_s();
    if (job.ready()) {
      Hello h;
      h.host = mpi_.host();
      h.backend = backend_;
      try {
        h.scene_hash = job.take();
        h.ok = true;
        loaded_ = true;
      } catch (const std::exception& e) {
        h.message = e.what();
      }
      mpi_.post(0, kHello, pack(h));
      return;  // rank 0 answers with tiles, or ends the job
    }
    check_silence(nullptr);
    beat();
    nap();
  }
}

void Farm::start_master(const std::function<uint64_t()>& load) {
  peers_.assign(static_cast<size_t>(mpi_.size()), Peer{});
  const double t0 = now_s();
  for (Peer& p : peers_) p.heard = t0;
  peers_[0].host = mpi_.host();
  peers_[0].backend = backend_;
  peers_[0].hello = true;
  Background<uint64_t> job;
  job.start(*lane_, load);
  std::optional<uint64_t> mine;
  for (;;) {
    if (!mine && job.ready()) {
      mine = job.take();  // rank 0's own failure: its message as it is
      loaded_ = true;
    }
    int source = 0, tag = 0;
    Bytes bytes;
    while (mpi_.receive(source, tag, bytes, o_.rank_timeout)) {
      Peer& p = peers_[static_cast<size_t>(source)];
      p.heard = now_s();
      if (tag != kHello) continue;
      Hello h;
      unpack(bytes, h);
      p.host = h.host;
      p.backend = h.backend;
      p.hello = true;
      p.hash = h.scene_hash;
      if (!h.ok)
        throw SceneError("rank " + std::to_string(source) + " on " + h.host + ": " + h.message);
    }
    check_silence(nullptr);
    if (mine) {
      bool all = true;
      for (int r = 1; r < mpi_.size(); ++r) {
        const Peer& p = peers_[static_cast<size_t>(r)];
        if (p.alive && p.hello && p.hash != *mine) {
          char why[160];
          std::snprintf(why, sizeof why, " (scene hash %016llx, rank 0 has %016llx)",
                        static_cast<unsigned long long>(p.hash),
                        static_cast<unsigned long long>(*mine));
          throw SceneError("rank " + std::to_string(r) + " on " + p.host +
                           " loaded another scene than rank 0" + why +
                           ": every rank needs the same scene files and the same options");
        }
        all = all && (p.hello || !p.alive);
      }
      if (all) return;
    }
    beat();
    nap();
  }
}

std::optional<FarmResult> Farm::render(const FarmJob& job, const RenderTile& render_tile,
                                       const FrameDone& on_frame,
                                       const std::function<void(const FarmResult&)>& checkpoint) {
  if (mpi_.rank() == 0) return render_master(job, render_tile, on_frame, checkpoint);
  render_worker(render_tile);
  return std::nullopt;
}

void Farm::stop() {
  signals_.reset();  // rill-trace's own handlers again
  if (mpi_.rank() != 0 || stopped_) return;
  stopped_ = true;
  for (int r = 1; r < mpi_.size(); ++r)
    if (peers_[static_cast<size_t>(r)].responsive) mpi_.post(r, kStop);
  mpi_.flush(std::min(o_.rank_timeout, 5.0));
}

void Farm::render_worker(const RenderTile& render_tile) {
  // Every tile in hand is posted to the lane at once: the lane renders them back to back, so
  // it never waits for this loop's next poll between tiles (at tiles of 64 that wait was a
  // fifth of the time). Results come back in order; each job times its own render.
  struct Job {
    Tile tile;
    Background<std::pair<RenderResult, double>> result;
  };
  std::deque<Job> jobs;
  bool stopped = false, failed = !loaded_;
  while (!stopped || !jobs.empty()) {
    int source = 0, tag = 0;
    Bytes bytes;
    while (mpi_.receive(source, tag, bytes, o_.rank_timeout)) {
      heard0_ = now_s();
      if (tag == kStop) stopped = true;
      if (tag != kAssign) continue;
      auto a = std::make_shared<Assign>();  // shared: the lane's job is a copyable function
      unpack(bytes, *a);
      if (failed) {
        if (!loaded_) mpi_.post(0, kFailed, pack(Text{"got tiles without a scene"}));
        continue;
      }
      jobs.push_back(Job{a->tile, {}});
      jobs.back().result.start(*lane_, [render_tile, a] {
        const double start = now_s();
        RenderResult r = render_tile(*a);
        return std::make_pair(std::move(r), (now_s() - start) * 1e3);
      });
    }
    while (!jobs.empty() && jobs.front().result.ready()) {
      Job job = std::move(jobs.front());
      jobs.pop_front();
      // After a failure the rest only drain; after rank 0's stop too (an interrupted rank 0
      // takes no more tiles, and a tile it would not receive would keep this rank waiting).
      if (failed || stopped) continue;
      try {
        auto [pixels, ms] = job.result.take();
        TileDone d;
        d.pixels = std::move(pixels);
        d.id = job.tile.id;
        d.busy_ms = ms;
        mpi_.post(0, kTileDone, pack(d));
      } catch (const std::exception& e) {
        // The tiles go to the other ranks; this one stays to hear rank 0's stop.
        mpi_.post(0, kFailed, pack(Text{std::string("rendering failed: ") + e.what()}));
        failed = true;
      }
    }
    check_silence(nullptr);
    beat();
    // A tile on its way to rank 0 moves only while this thread calls MPI: poll often then.
    lane_->wait_for_a_job(mpi_.sending() ? kSendingPoll : kPoll);
  }
  if (!mpi_.flush(o_.rank_timeout))
    throw std::runtime_error("rank 0 did not take this rank's last messages within " +
                             seconds_text(o_.rank_timeout));
}

// Rank 0's frames in progress: each one's image from its first tile back to its last, when
// it goes to the caller and leaves.
struct Farm::Frames {
  int first = 0;                     // the job's first frame
  std::vector<int> begin, tiles;     // per frame (from first): its first tile's id, its tiles
  std::vector<int> done;             // tiles back, per frame
  std::map<int, RenderResult> open;  // frames begun and not complete
  int complete = 0;
};

void Farm::report(FarmResult& R, const TileQueue& queue, const Frames& frames) const {
  R.tiles_done = queue.done();
  R.frames_done = frames.complete;
  R.unfinished.clear();
  for (const auto& [frame, image] : frames.open) {
    FramePart part;
    part.frame = frame;
    part.image = image;
    const size_t f = static_cast<size_t>(frame - frames.first);
    part.tiles = frames.tiles[f];
    part.tiles_done = frames.done[f];
    for (int id = frames.begin[f]; id < frames.begin[f] + frames.tiles[f]; ++id)
      if (!queue.is_done(id)) part.missing.push_back(queue.tile(id));
    R.unfinished.push_back(std::move(part));
  }
  double busiest = 0, sum = 0;
  int counted = 0;
  R.ranks.clear();
  for (size_t r = 0; r < peers_.size(); ++r) {
    const Peer& p = peers_[r];
    R.ranks.push_back(RankReport{static_cast<int>(r), p.host, p.backend, p.tiles, p.busy_ms, p.lost,
                                 p.responsive});
    R.must_abort = R.must_abort || !p.responsive;
    if (!p.alive) continue;
    busiest = std::max(busiest, p.busy_ms);
    sum += p.busy_ms;
    ++counted;
  }
  R.imbalance = sum > 0 ? busiest / (sum / counted) - 1.0 : 0.0;
  R.warnings = warnings_;
}

FarmResult Farm::render_master(const FarmJob& job, const RenderTile& render_tile,
                               const FrameDone& on_frame,
                               const std::function<void(const FarmResult&)>& checkpoint) {
  const double t0 = now_s();
  FarmResult R;
  std::vector<Tile> tiles = make_tiles(job.width, job.height, o_.tile, job.first_frame, job.frames);
  // The tail of the job in small tiles: as many large tiles as the ranks hold at once (at most
  // half the job), so that they finish within a small tile's time of each other.
  if (o_.tail_tile > 0 && o_.tail_tile < o_.tile)
    split_tail(tiles, std::min(kAhead * mpi_.size(), static_cast<int>(tiles.size()) / 2),
               o_.tail_tile);
  Frames frames;
  frames.first = job.first_frame;
  frames.begin.assign(static_cast<size_t>(job.frames), 0);
  frames.tiles.assign(static_cast<size_t>(job.frames), 0);
  frames.done.assign(static_cast<size_t>(job.frames), 0);
  for (const Tile& t : tiles) {
    const size_t f = static_cast<size_t>(t.frame - frames.first);
    if (frames.tiles[f]++ == 0) frames.begin[f] = t.id;
  }
  TileQueue queue(std::move(tiles));
  R.tiles = queue.total();
  R.frames = job.frames;
  if (!signals_) signals_ = std::make_unique<Signals>();
  std::exception_ptr output_error;  // on_frame failed

  // The tile back from a rank: into its frame's image, once; a frame complete goes to the
  // caller at once, and its image is freed.
  auto accept = [&](int rank, int id, const RenderResult& pixels, double busy_ms) {
    if (id < 0 || id >= queue.total())
      return lose(rank, "sent tile " + std::to_string(id) + ", which does not exist", true, &queue);
    const Tile& t = queue.tile(id);
    if (const std::string why = misfit(pixels, t, job.outputs, job.spp); !why.empty())
      return lose(rank, "sent " + why, true, &queue);
    if (!queue.finish(rank, id)) return;
    auto [it, begun] = frames.open.try_emplace(t.frame);
    if (begun) it->second = blank_image(job.width, job.height, job.outputs);
    place(it->second, t, pixels);
    R.tile_times.push_back(FarmResult::TileTime{t, rank, busy_ms});
    Peer& p = peers_[static_cast<size_t>(rank)];
    ++p.tiles;
    p.busy_ms += busy_ms;
    const size_t f = static_cast<size_t>(t.frame - frames.first);
    if (++frames.done[f] == frames.tiles[f]) {
      ++frames.complete;
      RenderResult image = std::move(it->second);
      frames.open.erase(it);
      // A failure to take the frame (an output that cannot be written) ends the render below,
      // the normal way: every rank is told to stop.
      if (on_frame && !output_error) try {
          on_frame(t.frame, std::move(image));
        } catch (...) {
          output_error = std::current_exception();
        }
    }
  };
  // A tile as it is handed out: in a round, with its slice of the sums so far.
  auto assign = [&](const Tile& t) {
    auto a = std::make_shared<Assign>();
    a->tile = t;
    a->spp = job.spp;
    a->accumulation = job.outputs.accumulation;
    if (job.resume != nullptr) a->resume = slice_of(*job.resume, t);
    return a;
  };
  // Tiles for a worker, up to kAhead in hand.
  auto feed = [&](int rank) {
    Peer& p = peers_[static_cast<size_t>(rank)];
    while (p.alive && p.in_flight < kAhead) {
      std::optional<Tile> t = queue.next(rank);
      if (!t) return;
      if (p.in_flight++ == 0) p.progress_at = now_s();
      mpi_.post(rank, kAssign, pack(*assign(*t)));
    }
  };
  auto draw_progress = [&, last = 0.0](bool final) mutable {
    if (!o_.progress || (!final && now_s() - last < 0.1)) return;
    last = now_s();
    std::fprintf(stderr, "\rrill-trace: %s %d/%d tiles",
                 trace_cli::progress_bar(queue.done(), queue.total()).c_str(), queue.done(),
                 queue.total());
    if (job.frames > 1) std::fprintf(stderr, ", %d/%d frames", frames.complete, job.frames);
    if (!job.label.empty()) std::fprintf(stderr, ", %s", job.label.c_str());
    std::fprintf(stderr, "; per rank");
    for (size_t r = 0; r < peers_.size() && r < 16; ++r)
      std::fprintf(stderr, " %d%s", peers_[r].tiles, peers_[r].alive ? "" : "(lost)");
    std::fprintf(stderr, "%s%s", peers_.size() > 16 ? " ..." : "", final ? "\n" : "");
    std::fflush(stderr);
  };

  int saved = 0;  // tiles in the last checkpoint
  double saved_at = t0;
  // Rank 0's own tiles, up to kAhead posted to its lane at once (as a worker's, below): the
  // lane renders them back to back, never waiting for this loop's next poll. Each job times
  // its own render; the front one's deadline runs from when it became the front.
  struct OwnJob {
    Tile tile;
    Background<std::pair<RenderResult, double>> result;
  };
  std::deque<OwnJob> own;
  double own_front_since = t0;
  for (int r = 1; r < mpi_.size(); ++r) feed(r);
  while (!queue.complete() && !output_error) {
    if (g_signal != 0) {
      R.interrupted = true;
      R.signal = g_signal;
      R.by_launcher = g_from_launcher != 0;
      break;
    }
    while (!own.empty() && own.front().result.ready()) {
      OwnJob job = std::move(own.front());
      own.pop_front();
      own_front_since = now_s();
      if (!peers_[0].alive) continue;  // lost: its tiles went to the others
      try {
        auto [pixels, ms] = job.result.take();
        accept(0, job.tile.id, pixels, ms);
      } catch (const std::exception& e) {
        lose(0, std::string("rendering failed: ") + e.what(), true, &queue);
      }
    }
    if (!own.empty() && peers_[0].alive && o_.tile_timeout > 0 &&
        now_s() - own_front_since > o_.tile_timeout) {
      lose(0, "no tile back within --tile-timeout " + seconds_text(o_.tile_timeout), false, &queue);
      R.must_abort = true;  // its thread cannot be stopped
    }
    while (peers_[0].alive && own.size() < static_cast<size_t>(kAhead)) {
      std::optional<Tile> t = queue.next(0);
      if (!t) break;
      if (own.empty()) own_front_since = now_s();
      own.push_back(OwnJob{*t, {}});
      own.back().result.start(*lane_, [render_tile, a = assign(*t)] {
        const double start = now_s();
        RenderResult r = render_tile(*a);
        return std::make_pair(std::move(r), (now_s() - start) * 1e3);
      });
    }
    // The workers'.
    int source = 0, tag = 0;
    Bytes bytes;
    for (;;) {
      const double received_at = now_s();
      try {
        if (!mpi_.receive(source, tag, bytes, o_.rank_timeout)) break;
      } catch (const std::exception& e) {
        lose(source, e.what(), false, &queue);
        mpi_.forget(source);  // lost before, and its late message broke off
        continue;
      }
      Peer& p = peers_[static_cast<size_t>(source)];
      if (!p.alive) continue;  // a lost rank's late word: its tiles went to the others
      p.heard = now_s();
      if (tag == kTileDone) {
        TileDone d;
        unpack(bytes, d);
        p.in_flight = std::max(0, p.in_flight - 1);
        p.progress_at = now_s();
        accept(source, d.id, d.pixels, d.busy_ms);
        feed(source);
        ++R.gathered;
        R.gathered_bytes += static_cast<double>(bytes.size());
        R.gather_ms += (now_s() - received_at) * 1e3;
      } else if (tag == kFailed) {
        Text t;
        unpack(bytes, t);
        lose(source, t.message, true, &queue);
      }
    }
    check_silence(&queue);
    for (int r = 1; r < mpi_.size(); ++r) feed(r);
    bool anyone = false;
    for (const Peer& p : peers_) anyone = anyone || p.alive;
    if (!anyone) break;
    beat();
    draw_progress(false);
    if (checkpoint && o_.checkpoint > 0 && queue.done() > saved &&
        now_s() - saved_at >= o_.checkpoint && !queue.complete()) {
      report(R, queue, frames);
      checkpoint(R);
      saved = queue.done();
      saved_at = now_s();
    }
    // Rank 0's own messages are small (they go out whole at once): no fast polling here, which
    // a send to a rank that died would keep on for good.
    lane_->wait_for_a_job(kPoll);
  }
  draw_progress(true);
  R.wall_ms = (now_s() - t0) * 1e3;
  report(R, queue, frames);
  if (R.interrupted && R.by_launcher) {
    signals_.reset();  // the caller ignores the signals that follow while it writes
    return R;          // mpirun is ending the job: no time for goodbyes
  }
  if (R.interrupted) {
    // Rank 0 itself was interrupted: the workers are told to stop (they drop the tiles in
    // hand), and rank 0's own tiles in flight end, so that MPI_Finalize ends the job cleanly.
    // Those take a launch each (kAhead at most); further signals meanwhile are only noted.
    while (!own.empty() && own.front().result.ready()) own.pop_front();
    const double until = now_s() + std::min(o_.rank_timeout, 30.0);
    while (!own.empty() && now_s() < until) {
      lane_->wait_for_a_job(kPoll);
      while (!own.empty() && own.front().result.ready()) own.pop_front();
    }
    if (!own.empty()) R.must_abort = true;
    stop();
    return R;
  }
  if (!own.empty()) R.must_abort = true;  // rank 0's lane still has tiles of a lost rank 0
  // Complete, the workers wait for the next job (a round) or the caller's stop().
  if (!R.complete() || output_error) stop();
  if (output_error) std::rethrow_exception(output_error);
  return R;
}

}  // namespace rt::distributed
