// The OpenCL backend's device memory role: the device buffers of streams and arrays (which
// move only when the host or another backend needs them, and then only their stale words),
// the scratch buffers of a launch, and the small tables a kernel reads, kept across launches.
#pragma once

#include <cstdint>
#include <vector>

#include "ClDevice.h"
#include "ClReadBack.h"
#include "rill/Backend.h"
#include "rill/Stream.h"

namespace rill::opencl {

// A small table a kernel reads (array shapes, uniform words, mask values), kept in one device
// buffer across launches and written again only when its contents change.
template <class T>
struct ClTable {
  cl_mem mem = nullptr;
  size_t bytes = 0;
  std::vector<T> uploaded;  // what the buffer holds
  ~ClTable() {
    if (mem) clReleaseMemObject(mem);
  }
};

class ClMemory {
 public:
  // owner: the backend whose buffers these are (Storage keeps one per backend).
  ClMemory(Backend& owner, Device& device) : owner_(owner), device_(device), read_backs_(device) {}
  Backend& owner() const { return owner_; }

  // Makes the device copy of s current and returns its buffer.
  cl_mem to_device(detail::Storage& s);
  // Copies s's device buffer to host (s.words() words).
  void read_back(const detail::Storage& s, uint32_t* host);
  // The same, returning at once (ClReadBack.h).
  std::unique_ptr<PendingReadBack> read_back_async(const detail::Storage& s, uint32_t* host);
  // A new buffer holding a copy of `bytes` bytes of data (at least 8 bytes: kernels always
  // get a buffer, even for an empty table); the caller releases it.
  cl_mem scratch(size_t bytes, const void* data);
  // The device buffer holding `now`, written only when it differs from the last upload.
  template <class T>
  cl_mem table(ClTable<T>& t, const std::vector<T>& now);

 private:
  Backend& owner_;
  Device& device_;
  ClReadBacks read_backs_;
};

}  // namespace rill::opencl
