// The tile farm: one image, or a sequence of them, rendered by every rank of an MPI job
// (docs/distributed.md).
//
// The scene is replicated: every rank loads it and builds its grid itself, then rank 0
// checks that all of them hold the same scene (SceneHash.h) before a tile is handed out.
// Rank 0 keeps the tile queue (TileQueue.h) and renders tiles too, on a thread of its own;
// the other ranks ask for tiles, render them on their own backend and device, and send the
// pixels back. Rank 0 assembles each frame, which under strict is bitwise the single-process
// render (RenderSettings::window), and main writes it as it writes any render. A sequence's
// tiles are queued frame after frame (TileQueue.h); a rank moves its scene to a tile's frame
// when it gets one of another frame (main's render_tile), and each frame is written as soon as
// its last tile is back.
//
// Faults. Open MPI 4.1's mpirun, by default, ends the whole job when a rank dies: rank 0
// gets SIGTERM and SIGKILL within a second, at times within milliseconds. So rank 0 keeps the
// image so far on disk while it renders (checkpoints, every FarmOptions::checkpoint seconds),
// and answers SIGTERM (and SIGINT) by returning what it has at once
// (FarmResult::interrupted), for main to write as a partial image with a note if it still
// can. A signal sent to rank 0 by another process than its launcher (kill, a scheduler) is an
// interrupt: rank 0 stops the other ranks, waits for its own tiles in flight, and the job
// ends through MPI_Finalize (FarmResult::by_launcher tells the two apart). Started with `mpirun
// --enable-recovery`, the job goes on without the dead rank: rank 0 hears from every rank at least
// every half second (heartbeats from each rank's main thread, which never renders), declares a rank
// lost after rank_timeout of silence, or when a tile takes longer than tile_timeout (a hung
// device), or when it reports a failure, and hands its tiles to the others; the image completes
// with a warning. A lost rank may still be alive (hung), and MPI_Finalize would wait for it
// forever, so the job then ends with MPI_Abort once the outputs are written
// (FarmResult::must_abort). Workers time out on rank 0 the same way and end.
//
// Rounds. One start may be followed by several jobs before the workers' Stop: a progressive
// render (--time-limit, --save, --resume) runs in rounds, each a job over every tile that
// renders up to a sample count from the image's sums so far, which rank 0 keeps and sends
// with each tile (FarmJob::spp, resume; Messages.h). The workers do not know where one round
// ends: they render what they are assigned until rank 0 says stop (Farm::stop).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "JobThread.h"
#include "PartialName.h"
#include "distributed/Messages.h"
#include "distributed/MpiSession.h"
#include "distributed/TileQueue.h"
#include "rill/rt/Tracer.h"

namespace rt::distributed {

// The thread that loads the scene and renders every tile of this rank, one job at a time.
// One thread for all: a GL context is current on one thread at a time (EGL refuses to make it
// current on another while it is current on a thread that ended).
using Lane = trace_cli::JobThread;

struct FarmOptions {
  int tile = 128;            // tile size in pixels (square; smaller at the edges)
  int tail_tile = 0;         // the job's last tiles are cut to this size; 0: not cut
  double rank_timeout = 20;  // seconds of silence before a rank is lost
  double tile_timeout = 0;   // seconds a rank may take for a tile; 0: no limit
  double heartbeat = 0.5;    // seconds between heartbeats
  double checkpoint = 2;     // rank 0 hands out the image so far this often (0: never)
  bool progress = false;     // rank 0 draws a progress bar on stderr
};

// One rank's part, as rank 0 saw it.
struct RankReport {
  int rank = 0;
  std::string host, backend;
  int tiles = 0;           // tiles it rendered that are in the image
  double busy_ms = 0;      // time rendering them, measured on the rank
  std::string lost;        // why it was lost; empty if it was not
  bool responsive = true;  // false: lost without a word (died or hung)
};

// What rank 0 renders: frames first_frame .. first_frame + frames - 1 (one, for a still), each
// width x height with the outputs asked for. A round of a progressive render (one frame):
// samples up to `spp` (0: the scene's), going on from `resume` (the whole image's sums, of
// which each tile gets its slice; null: from the first sample), the image's sums back in
// RenderResult::accumulation when outputs.accumulation.
struct FarmJob {
  int width = 0, height = 0;
  int first_frame = 0, frames = 1;
  FrameOutputs outputs;
  int spp = 0;
  const Accumulation* resume = nullptr;
  std::string label;  // after the progress bar's tiles (a round: its samples)
};

// A frame that was begun and is not complete: the tiles so far, for checkpoints and partial
// outputs.
struct FramePart {
  int frame = 0;
  RenderResult image;  // tiles missing: black, depth +inf, prim -1
  int tiles = 0, tiles_done = 0;
  std::vector<Tile> missing;  // tiles not in the image
};

struct FarmResult {
  int tiles = 0, tiles_done = 0;      // over every frame
  int frames = 1, frames_done = 0;    // frames complete (each handed to the caller as it was)
  std::vector<FramePart> unfinished;  // frames begun and not complete, in frame order
  std::vector<RankReport> ranks;
  std::vector<std::string> warnings;
  bool interrupted = false;  // SIGTERM or SIGINT: a partial render
  int signal = 0;            // which
  // Sent by the launcher (rank 0's parent: mpirun ending the job, as when a rank dies), so
  // that rank 0 ends at once; otherwise rank 0 itself was interrupted, and stopped the others.
  bool by_launcher = false;
  bool must_abort = false;  // a lost rank may be alive: end with MpiSession::abort
  double wall_ms = 0;       // from the first tile handed out to the last one back
  double imbalance = 0;     // busiest rank's busy time over the mean, less 1 (ranks not lost)
  // Each tile done: its id, the rank that rendered it and that rank's time for it (the
  // tile-cost distribution, for models of larger farms).
  struct TileTime {
    Tile tile;
    int rank = 0;
    double ms = 0;
  };
  std::vector<TileTime> tile_times;
  // Rank 0's main thread on the workers' tiles: how many came back, their bytes, and the time
  // from receiving each to having placed it and handed out the next (the queue's service time,
  // for models of larger farms).
  int gathered = 0;
  double gathered_bytes = 0, gather_ms = 0;
  bool complete() const { return tiles_done == tiles; }
};

class Farm {
 public:
  Farm(MpiSession& mpi, const FarmOptions& options);
  ~Farm();

  // Every rank: load() loads the scene and builds what renders it (on another thread, while
  // this one keeps in touch with the other ranks) and returns the scene hash. On rank 0,
  // throws the first rank's failure or a scene mismatch, naming the rank and its host (main
  // then ends the job); a worker waits for rank 0's verdict.
  void start(const std::function<uint64_t()>& load, const std::string& backend);

  // Every rank: renders tiles with render_tile (on another thread). Rank 0 runs one job until
  // every frame of it is complete, hands each frame to on_frame as soon as it is complete (on
  // this thread, which hands out no tiles meanwhile: on_frame should be quick; frames may
  // complete out of order) and returns the report; it may then run another job (a round), and
  // calls stop() after the last. A render that ends incomplete (interrupted, every rank lost,
  // on_frame failed) has stopped the workers already. A worker renders every job's tiles and
  // returns nothing once rank 0 says stop, and throws if rank 0 is lost. Only rank 0 reads the
  // job. Rank 0 calls checkpoint with the frames begun so far every options.checkpoint seconds
  // while tiles come in, for main to keep on disk: mpirun may kill rank 0 at once when another
  // rank dies, with no time to write anything then.
  using FrameDone = std::function<void(int frame, RenderResult&& image)>;
  using RenderTile = std::function<RenderResult(const Assign&)>;
  std::optional<FarmResult> render(const FarmJob& job, const RenderTile& render_tile,
                                   const FrameDone& on_frame,
                                   const std::function<void(const FarmResult&)>& checkpoint = {});
  // Rank 0, after the last job: tells the workers to stop (once; later calls do nothing).
  void stop();

 private:
  struct Peer;
  void start_master(const std::function<uint64_t()>& load);
  void start_worker(const std::function<uint64_t()>& load);
  struct Frames;  // rank 0: the frames begun and not complete
  FarmResult render_master(const FarmJob& job, const RenderTile& render_tile,
                           const FrameDone& on_frame,
                           const std::function<void(const FarmResult&)>& checkpoint);
  // Rank 0: the counts, unfinished frames and per-rank report of R, as they are now.
  void report(FarmResult& R, const TileQueue& queue, const Frames& open) const;
  void render_worker(const RenderTile& render_tile);
  // Rank 0: the rank is lost; its tiles go back to the queue (if there is one).
  void lose(int rank, const std::string& why, bool responsive, TileQueue* queue);
  // Rank 0: ranks silent for too long are lost. Workers: throws if rank 0 is.
  void check_silence(TileQueue* queue);
  // Sends a heartbeat to the ranks this one hears from, when one is due.
  void beat();

  MpiSession& mpi_;
  FarmOptions o_;
  std::string backend_;
  std::vector<Peer> peers_;  // rank 0: every rank, itself included
  double heard0_ = 0;        // workers: when rank 0 was last heard
  double last_beat_ = 0;
  bool loaded_ = false;
  bool stopped_ = false;  // rank 0: the workers were told to stop
  std::vector<std::string> warnings_;
  std::unique_ptr<Lane> lane_;
  // Rank 0's SIGTERM and SIGINT handlers, from the first job to stop(): a signal between two
  // rounds interrupts the next one at its start.
  struct Signals;
  std::unique_ptr<Signals> signals_;
};

using trace_cli::partial_name;  // PartialName.h

}  // namespace rt::distributed
