// A read-back that returns at once (Stream::download_async): the device copies the stream's
// words into the caller's memory while the host and the device go on with other work, such as
// the next frame's kernels.
//
// The words are the stream's as they were at the call: a kernel launched afterwards that
// writes the stream does not change them. A backend that can read back while its kernels run
// (OpenCL: a snapshot on the device, then a transfer on a queue of its own) keeps them apart;
// the others copy at once and the ReadBack is done when it is made.
#pragma once

#include <memory>

namespace rill {

// What a backend's asynchronous read-back left to finish (Backend::read_back_async).
class PendingReadBack {
 public:
  virtual ~PendingReadBack() = default;
  // Returns once the words are in the caller's memory; throws rill::Error if the transfer
  // failed. Called once.
  virtual void wait() = 0;
};

// A read-back in flight into memory of the caller's, which must stay in place (not freed, not
// resized) until wait() returns. Destroying one waits for it first (an error is dropped
// there: call wait() to see it).
class ReadBack {
 public:
  ReadBack() = default;  // nothing in flight
  explicit ReadBack(std::unique_ptr<PendingReadBack> pending) : pending_(std::move(pending)) {}
  ReadBack(ReadBack&&) noexcept = default;
  ReadBack& operator=(ReadBack&& other) noexcept;  // waits for this one's first
  ReadBack(const ReadBack&) = delete;
  ReadBack& operator=(const ReadBack&) = delete;
  ~ReadBack();
  // Waits for the words (at once when none are in flight).
  void wait();
  bool in_flight() const { return pending_ != nullptr; }

 private:
  std::unique_ptr<PendingReadBack> pending_;
};

}  // namespace rill
