// A thread of its own that runs the jobs posted to it, one at a time, in order: the farm's
// render thread (distributed/Farm.cpp) and the writer of finished frames (FrameWriter).
//
// Detached, not joined: a rank that must end while its tile still renders (a hung device)
// ends the process instead of waiting for it. drain() waits for the jobs posted so far
// instead, for a caller that must see them done (the frames written).
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>

namespace trace_cli {

class JobThread {
 public:
  JobThread();
  // Lets the thread end after the jobs already posted; does not wait for them.
  ~JobThread();
  JobThread(const JobThread&) = delete;
  JobThread& operator=(const JobThread&) = delete;

  // Runs job after the jobs posted before it.
  void post(std::function<void()> job);
  // Waits until a job has finished since the last call, or for `poll`, whichever is first:
  // a caller's polling loop hears of a finished job at once instead of at its next poll.
  void wait_for_a_job(std::chrono::microseconds poll);
  // Waits until every job posted so far has run.
  void drain();

 private:
  struct State;
  std::shared_ptr<State> s_;  // shared with the thread, which may outlive this object
  uint64_t seen_ = 0;         // jobs finished at the last wait_for_a_job
};

}  // namespace trace_cli
