// Streams and arrays: the data kernels run over.
//
// A Stream<V> holds n elements of a DSL type V (Float, Float3, Int2, ...). Kernels read
// streams as inputs and write them as outputs, one element per kernel instance. A stream
// may have a 2D shape (width x height), which element_coord() reports; its size is
// width * height either way.
//
// An Array<V> is read-only data that a kernel gathers from at any index: arr[i], or arr(x, y)
// and arr(x, y, z) for 2D and 3D shapes. An index outside the array is clamped to the
// nearest element on every backend (reads never fault).
//
// Both keep a host copy and, per backend, a device copy; upload() and download() move data
// between host and whichever backend last wrote it, only when needed.
#pragma once

#include <array>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rill/Value.h"

namespace rill {

class Backend;

namespace detail {

// Device-side storage a backend keeps for a stream or array.
struct DeviceBuffer {
  virtual ~DeviceBuffer() = default;
};

// Element data of a stream or array: `count` elements of `type`, 4 bytes per component.
struct Storage {
  ir::Type type;
  int64_t count = 0;
  std::vector<uint32_t> host;  // count * width words
  bool host_valid = true;
  // The backend holding the freshest copy when !host_valid, and its buffer.
  Backend* device_owner = nullptr;
  std::unique_ptr<DeviceBuffer> device;
  bool device_valid = false;
  uint64_t version = 0;  // bumped on every host write, so backends can cache uploads

  void init(ir::Type t, int64_t n);
  // Makes the host copy current (reading back from the device if it is newer).
  void sync_to_host();
  // The host copy is about to be written: device copies become stale.
  void host_written();
};

struct StreamState : Storage {
  int64_t width = 0, height = 1;  // shape; width * height == count
};

struct ArrayState : Storage {
  std::string name;
  int dims = 1;
  int64_t shape[3] = {0, 1, 1};
};

template <class V>
using HostOf = typename V::host_type;

template <class V>
void copy_in(Storage& s, std::span<const HostOf<V>> data) {
  if (static_cast<int64_t>(data.size()) != s.count)
    throw Error("upload of " + std::to_string(data.size()) + " elements into a stream of " +
                std::to_string(s.count));
  s.host.resize(static_cast<size_t>(s.count) * V::width);
  if (!s.host.empty()) std::memcpy(s.host.data(), data.data(), s.host.size() * 4);
  s.host_written();
}

template <class V>
std::vector<HostOf<V>> copy_out(Storage& s) {
  s.sync_to_host();
  std::vector<HostOf<V>> out(static_cast<size_t>(s.count));
  if (!out.empty()) std::memcpy(out.data(), s.host.data(), s.host.size() * 4);
  return out;
}

}  // namespace detail

// A type-erased reference to a stream, for binding to kernels.
class StreamRef {
 public:
  explicit StreamRef(std::shared_ptr<detail::StreamState> s) : s_(std::move(s)) {}
  detail::StreamState& state() const { return *s_; }
  const std::shared_ptr<detail::StreamState>& shared() const { return s_; }

 private:
  std::shared_ptr<detail::StreamState> s_;
};

template <class V>
class Stream {
  static_assert(sizeof(detail::HostOf<V>) == 4 * V::width || std::is_same_v<typename V::scalar_type, bool>,
                "rill: unexpected host layout");
  static_assert(!std::is_same_v<typename V::scalar_type, bool>,
                "rill: streams hold Float or Int elements (store a Bool as an Int)");

 public:
  using host_type = detail::HostOf<V>;

  explicit Stream(int64_t n) : s_(std::make_shared<detail::StreamState>()) { init(n, 1); }
  Stream(int64_t width, int64_t height) : s_(std::make_shared<detail::StreamState>()) {
    init(width, height);
  }
  Stream(std::span<const host_type> data) : Stream(static_cast<int64_t>(data.size())) {
    upload(data);
  }
  Stream(const std::vector<host_type>& data) : Stream(std::span<const host_type>(data)) {}

  int64_t size() const { return s_->count; }
  int64_t width() const { return s_->width; }
  int64_t height() const { return s_->height; }

  void upload(std::span<const host_type> data) { detail::copy_in<V>(*s_, data); }
  void upload(const std::vector<host_type>& data) { upload(std::span<const host_type>(data)); }
  std::vector<host_type> download() const { return detail::copy_out<V>(*s_); }
  // Sets every element to v.
  void fill(const host_type& v) { upload(std::vector<host_type>(static_cast<size_t>(size()), v)); }

  operator StreamRef() const { return StreamRef(s_); }

 private:
  void init(int64_t w, int64_t h) {
    if (w < 0 || h < 1) throw Error("stream shape must be non-negative");
    s_->init(V::type(), w * h);
    s_->width = w;
    s_->height = h;
  }
  std::shared_ptr<detail::StreamState> s_;
};

template <class V>
class Array {
  static_assert(!std::is_same_v<typename V::scalar_type, bool>,
                "rill: arrays hold Float or Int elements");

 public:
  using host_type = detail::HostOf<V>;

  explicit Array(int64_t n, std::string name = "array") : Array(1, {n, 1, 1}, std::move(name)) {}
  Array(int64_t nx, int64_t ny, std::string name = "array") : Array(2, {nx, ny, 1}, std::move(name)) {}
  Array(int64_t nx, int64_t ny, int64_t nz, std::string name = "array")
      : Array(3, {nx, ny, nz}, std::move(name)) {}
  Array(const std::vector<host_type>& data, std::string name = "array")
      : Array(static_cast<int64_t>(data.size()), std::move(name)) {
    upload(data);
  }

  int64_t size() const { return s_->count; }
  void upload(std::span<const host_type> data) { detail::copy_in<V>(*s_, data); }
  void upload(const std::vector<host_type>& data) { upload(std::span<const host_type>(data)); }
  std::vector<host_type> download() const { return detail::copy_out<V>(*s_); }
  // Changes the shape (and size); the data must be uploaded again. Kernels need no recompile.
  void resize(int64_t nx, int64_t ny = 1, int64_t nz = 1) {
    s_->shape[0] = nx;
    s_->shape[1] = ny;
    s_->shape[2] = nz;
    s_->init(V::type(), nx * ny * nz);
  }

  // Gathers, inside a kernel.
  V operator[](const Int& i) const { return gather({i.operand()}, 1); }
  V operator()(const Int& i) const { return gather({i.operand()}, 1); }
  V operator()(const Int& x, const Int& y) const { return gather({x.operand(), y.operand()}, 2); }
  V operator()(const Int& x, const Int& y, const Int& z) const {
    return gather({x.operand(), y.operand(), z.operand()}, 3);
  }

  const std::shared_ptr<detail::ArrayState>& state() const { return s_; }

 private:
  Array(int dims, std::array<int64_t, 3> shape, std::string name)
      : s_(std::make_shared<detail::ArrayState>()) {
    for (int64_t d : shape)
      if (d < 1) throw Error("array '" + name + "': every dimension must be at least 1");
    s_->name = std::move(name);
    s_->dims = dims;
    resize(shape[0], shape[1], shape[2]);
  }
  V gather(std::vector<ir::Operand> idx, int dims) const {
    if (dims != s_->dims)
      throw Error("array '" + s_->name + "' is " + std::to_string(s_->dims) + "D but was indexed with " +
                  std::to_string(dims) + " indices");
    return V(detail::emit_gather(s_, std::move(idx)), detail::AdoptTag{});
  }
  std::shared_ptr<detail::ArrayState> s_;
};

}  // namespace rill
