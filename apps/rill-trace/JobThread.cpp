// A thread that runs posted jobs in order (JobThread.h).
#include "JobThread.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace trace_cli {

struct JobThread::State {
  std::mutex mutex;
  std::condition_variable wake, finished_cv;
  std::deque<std::function<void()>> jobs;
  uint64_t posted = 0, finished = 0;
  bool quit = false;
  void run() {
    for (;;) {
      std::function<void()> job;
      {
        std::unique_lock<std::mutex> lock(mutex);
        wake.wait(lock, [&] { return quit || !jobs.empty(); });
        if (jobs.empty()) return;
        job = std::move(jobs.front());
        jobs.pop_front();
      }
      job();
      {
        std::lock_guard<std::mutex> lock(mutex);
        ++finished;
      }
      finished_cv.notify_all();
    }
  }
};

JobThread::JobThread() : s_(std::make_shared<State>()) {
  std::thread([s = s_] { s->run(); }).detach();
}

JobThread::~JobThread() {
  {
    std::lock_guard<std::mutex> lock(s_->mutex);
    s_->quit = true;
  }
  s_->wake.notify_one();
}

void JobThread::post(std::function<void()> job) {
  {
    std::lock_guard<std::mutex> lock(s_->mutex);
    s_->jobs.push_back(std::move(job));
    ++s_->posted;
  }
  s_->wake.notify_one();
}

void JobThread::wait_for_a_job(std::chrono::microseconds poll) {
  std::unique_lock<std::mutex> lock(s_->mutex);
  s_->finished_cv.wait_for(lock, poll, [&] { return s_->finished != seen_; });
  seen_ = s_->finished;
}

void JobThread::drain() {
  std::unique_lock<std::mutex> lock(s_->mutex);
  s_->finished_cv.wait(lock, [&] { return s_->finished == s_->posted; });
}

}  // namespace trace_cli
