// The OpenCL backend's read-back that returns at once (ClReadBack.h).
#include "ClReadBack.h"

#include <cstddef>
#include <cstdlib>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace rill::opencl {

namespace {

// RILL_OPENCL_READBACK, read at each read-back (tests change it between frames).
bool late_read_backs() {
  const char* v = std::getenv("RILL_OPENCL_READBACK");
  if (v == nullptr || *v == '\0' || std::string(v) == "overlap") return false;
  if (std::string(v) == "late") return true;
  throw Error(std::string("RILL_OPENCL_READBACK='") + v + "' is not one of overlap, late");
}

}  // namespace

// Staging buffers free for the next read-back, by size, and the queue the transfers run on.
struct ClReadBacks::Staging {
  explicit Staging(Device& d) : device(d) {}
  ~Staging() {
    for (auto& kept : free) clReleaseMemObject(kept.first);
    if (transfers) clReleaseCommandQueue(transfers);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  // A staging buffer of `bytes` bytes: a free one of that size, else a new one.
  cl_mem take(size_t bytes) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      for (size_t i = 0; i < free.size(); ++i)
        if (free[i].second == bytes) {
          cl_mem m = free[i].first;
          free.erase(free.begin() + static_cast<std::ptrdiff_t>(i));
          return m;
        }
    }
    check_allocation(device, bytes);
    cl_int e = CL_SUCCESS;
    cl_mem m = clCreateBuffer(device.context, CL_MEM_READ_WRITE, bytes, nullptr, &e);
    check(e, "clCreateBuffer (read-back staging)");
    return m;
  }
  // Back for a later read-back. A frame's outputs, two frames in flight: a few buffers; the
  // oldest go beyond that (sizes change with the image's).
  void give_back(cl_mem m, size_t bytes) {
    std::lock_guard<std::mutex> lock(mutex);
    free.emplace_back(m, bytes);
    if (free.size() > kKept) {
      clReleaseMemObject(free.front().first);
      free.erase(free.begin());
    }
  }
  // The transfer queue, made at the first read-back.
  cl_command_queue queue() {
    std::lock_guard<std::mutex> lock(mutex);
    if (!transfers) {
      cl_int e = CL_SUCCESS;
      transfers = clCreateCommandQueue(device.context, device.id, 0, &e);
      check(e, "clCreateCommandQueue (read-backs)");
    }
    return transfers;
  }

  static constexpr size_t kKept = 16;
  Device& device;
  std::mutex mutex;
  std::vector<std::pair<cl_mem, size_t>> free;
  cl_command_queue transfers = nullptr;
};

namespace {

// One read-back in flight: its staging buffer and the events of its two steps.
class ClPendingReadBack : public PendingReadBack {
 public:
  ClPendingReadBack(std::shared_ptr<ClReadBacks::Staging> staging, cl_mem buffer, size_t bytes,
                    void* host)
      : staging_(std::move(staging)), buffer_(buffer), bytes_(bytes), host_(host) {}
  ~ClPendingReadBack() override {
    // Waited for by ReadBack; the buffer waits for its commands in any case (OpenCL frees a
    // released buffer once they are done).
    if (read_) clWaitForEvents(1, &read_);
    release();
  }
  ClPendingReadBack(const ClPendingReadBack&) = delete;
  ClPendingReadBack& operator=(const ClPendingReadBack&) = delete;

  // Copies the source on the launch queue, then (unless late) reads the copy on the transfer
  // queue once the copy is done.
  void start(cl_mem from, bool late) {
    Device& d = staging_->device;
    check(clEnqueueCopyBuffer(d.queue, from, buffer_, 0, 0, bytes_, 0, nullptr, &copied_),
          "clEnqueueCopyBuffer (read-back)");
    check(clFlush(d.queue), "clFlush");
    if (!late) transfer(CL_FALSE);
  }

  void wait() override {
    if (!read_) transfer(CL_TRUE);  // late: only now
    const cl_int e = clWaitForEvents(1, &read_);
    release();
    check(e, "reading back (clWaitForEvents)");
  }

 private:
  void transfer(cl_bool blocking) {
    cl_command_queue q = staging_->queue();
    check(clEnqueueReadBuffer(q, buffer_, blocking, 0, bytes_, host_, 1, &copied_, &read_),
          "clEnqueueReadBuffer (read-back)");
    check(clFlush(q), "clFlush");
  }
  void release() {
    if (copied_) clReleaseEvent(std::exchange(copied_, nullptr));
    if (read_) clReleaseEvent(std::exchange(read_, nullptr));
    if (buffer_) staging_->give_back(std::exchange(buffer_, nullptr), bytes_);
  }

  std::shared_ptr<ClReadBacks::Staging> staging_;
  cl_mem buffer_;
  size_t bytes_;
  void* host_;
  cl_event copied_ = nullptr, read_ = nullptr;
};

}  // namespace

ClReadBacks::ClReadBacks(Device& device) : staging_(std::make_shared<Staging>(device)) {}

std::unique_ptr<PendingReadBack> ClReadBacks::start(cl_mem from, size_t bytes, void* host) {
  const bool late = late_read_backs();
  auto pending = std::make_unique<ClPendingReadBack>(staging_, staging_->take(bytes), bytes, host);
  pending->start(from, late);
  return pending;
}

}  // namespace rill::opencl
