// The OpenCL backend's device memory role (ClMemory.h).
#include "ClMemory.h"

#include <algorithm>
#include <cstring>

namespace rill::opencl {

namespace {

// Device memory for a stream or array.
struct ClBuffer : detail::DeviceBuffer {
  cl_mem mem = nullptr;
  size_t bytes = 0;
  ~ClBuffer() override {
    if (mem) clReleaseMemObject(mem);
  }
};

}  // namespace

cl_mem ClMemory::to_device(detail::Storage& s) {
  Device& d = device_;
  auto* buf = s.device_buffer<ClBuffer>(&owner_);
  if (buf && s.is_device_current(&owner_)) return buf->mem;
  const uint32_t* host = s.host_data_for_read();
  size_t bytes = std::max<size_t>(4, s.words() * 4);
  // A buffer that is stale in some words only gets just those (Storage::stale_words).
  auto [first, end] = s.stale_words();
  if (!buf || buf->bytes != bytes) {
    first = 0;
    end = s.words();
    auto fresh = std::make_unique<ClBuffer>();
    cl_int e = CL_SUCCESS;
    check_allocation(d, bytes);
    fresh->mem = clCreateBuffer(d.context, CL_MEM_READ_WRITE, bytes, nullptr, &e);
    check(e, "clCreateBuffer");
    fresh->bytes = bytes;
    buf = fresh.get();
    s.set_device_buffer(&owner_, std::move(fresh));
  }
  if (end > first)
    check(clEnqueueWriteBuffer(d.queue, buf->mem, CL_TRUE, first * 4, (end - first) * 4,
                               host + first, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
  s.mark_device_current(&owner_);
  return buf->mem;
}

void ClMemory::read_back(const detail::Storage& s, uint32_t* host) {
  auto* buf = s.device_buffer<ClBuffer>(&owner_);
  if (s.words() != 0)
    check(clEnqueueReadBuffer(device_.queue, buf->mem, CL_TRUE, 0, s.words() * 4, host, 0, nullptr,
                              nullptr),
          "clEnqueueReadBuffer");
}

std::unique_ptr<PendingReadBack> ClMemory::read_back_async(const detail::Storage& s,
                                                           uint32_t* host) {
  auto* buf = s.device_buffer<ClBuffer>(&owner_);
  if (s.words() == 0) return nullptr;
  return read_backs_.start(buf->mem, s.words() * 4, host);
}

cl_mem ClMemory::scratch(size_t bytes, const void* data) {
  Device& d = device_;
  cl_int e = CL_SUCCESS;
  // Kernels always get a buffer, even for an empty table; pad to 8 bytes.
  check_allocation(d, std::max<size_t>(bytes, 8));
  std::vector<unsigned char> copy(std::max<size_t>(bytes, 8), 0);
  if (bytes) std::memcpy(copy.data(), data, bytes);
  cl_mem m = clCreateBuffer(d.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, copy.size(),
                            copy.data(), &e);
  check(e, "clCreateBuffer");
  return m;
}

template <class T>
cl_mem ClMemory::table(ClTable<T>& t, const std::vector<T>& now) {
  const size_t bytes = now.size() * sizeof(T);
  if (!t.mem || bytes > t.bytes) {
    if (t.mem) clReleaseMemObject(t.mem);
    t.mem = nullptr;
    t.bytes = std::max<size_t>(bytes, 8);  // kernels always get a buffer, even for an empty table
    t.mem = scratch(bytes, now.data());
  } else if (now != t.uploaded && bytes != 0) {
    check(clEnqueueWriteBuffer(device_.queue, t.mem, CL_TRUE, 0, bytes, now.data(), 0, nullptr,
                               nullptr),
          "clEnqueueWriteBuffer");
  }
  t.uploaded = now;
  return t.mem;
}

template cl_mem ClMemory::table(ClTable<cl_long>&, const std::vector<cl_long>&);
template cl_mem ClMemory::table(ClTable<cl_uint>&, const std::vector<cl_uint>&);
template cl_mem ClMemory::table(ClTable<cl_int>&, const std::vector<cl_int>&);

}  // namespace rill::opencl
