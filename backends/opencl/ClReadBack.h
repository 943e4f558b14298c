// The OpenCL backend's read-back that returns at once (Backend::read_back_async,
// rill/ReadBack.h). The stream's buffer is first copied on the device, in the launch queue's
// order, into a staging buffer of the backend's: the kernels launched next may write the
// stream at once. The staging buffer then goes to the caller's memory on a queue of its own,
// which a GPU's copy engine runs beside the launch queue's kernels. The staging buffers are
// the second set of outputs that overlapping a frame's read-back with the next frame's trace
// needs, for any stream, at the price of a copy at the device memory's speed.
//
//   RILL_OPENCL_READBACK=overlap|late   overlap (default): the transfer starts at once; late:
//                                       it starts only when waited for, after whatever ran
//                                       meanwhile. Tests use late: a read-back that did not
//                                       keep its own copy would then show later kernels' words.
#pragma once

#include <memory>

#include "ClDevice.h"
#include "rill/ReadBack.h"

namespace rill::opencl {

class ClReadBacks {
 public:
  explicit ClReadBacks(Device& device);
  // Starts copying `bytes` bytes of `from` (written by kernels of the device's queue) into
  // `host`; the result's wait() returns once they are there.
  std::unique_ptr<PendingReadBack> start(cl_mem from, size_t bytes, void* host);

  struct Staging;  // the staging buffers and the transfer queue, shared with reads in flight

 private:
  std::shared_ptr<Staging> staging_;
};

}  // namespace rill::opencl
