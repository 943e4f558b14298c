// Streams and arrays: the data kernels run over.
//
// A Stream<V> holds n elements of a DSL type V (Float, Float3, Int2, ...). Kernels read
// streams as inputs and write them as outputs, one element per kernel instance. A stream
// may have a 2D shape (width x height), which element_coord() reports; its size is
// width * height either way.
//
// An Array<V> is read-only data that a kernel gathers from at any index: arr[i], or arr(x, y)
// and arr(x, y, z) for 2D and 3D shapes. Its data is laid out x fastest, then y, then z:
// element (x, y, z) of an nx x ny x nz array is data[x + nx * (y + ny * z)]. An index outside
// the array reads what the array's boundary mode says (Boundary: clamped to the nearest
// element by default, else wrapped, mirrored or a constant), the same on every backend; reads
// never fault.
//
// Both keep a host copy and, per backend, a device copy; upload() and download() move data
// between host and whichever backend last wrote it, only when needed.
#pragma once

#include <array>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rill/ReadBack.h"
#include "rill/Value.h"

namespace rill {

class Backend;

namespace detail {

// Device-side storage a backend keeps for a stream or array.
struct DeviceBuffer {
  virtual ~DeviceBuffer() = default;
};

// Element data of a stream or array: `count` elements of `type`, 4 bytes per component, with
// a host copy and at most one device copy (held by one backend at a time).
//
// Its methods keep the copies coherent, so no backend has to:
//   - at least one copy is current: the host copy, or the device copy of owner();
//   - reading the host (host_data_for_read) first reads the device copy back if it is newer;
//   - writing the host (host_data_for_write / _for_overwrite) makes the device copy stale;
//   - a backend that writes its device copy says so (mark_device_written), which makes the
//     host copy stale until the next host read;
//   - version() grows on every host write, so a backend can tell whether its copy is old.
// A backend gets its own buffer back with device_buffer<T>(this): null when another backend
// (or none) holds the device copy.
class Storage {
 public:
  ir::Type type() const { return type_; }
  int64_t count() const { return count_; }
  // Words (4-byte components) of the host copy: count() * type().width.
  size_t words() const { return host_.size(); }
  uint64_t version() const { return version_; }

  // Sizes the data to n elements of t, all zero on the host; a device copy becomes stale.
  void init(ir::Type t, int64_t n);

  // The host copy, current (read back from the device first if the device copy is newer).
  const uint32_t* host_data_for_read();
  // Copies the current data (words() words) into dst: straight from the device copy when it
  // is the newer one (one transfer, nothing through the host copy, which stays as it was),
  // else from the host copy.
  void read_into(uint32_t* dst);
  // The same, returning at once where the device copy is the newer one and its backend can
  // read back asynchronously (ReadBack.h): the words are those of now, even if a kernel writes
  // the stream before the transfer ends. dst must stay in place until the result's wait().
  std::unique_ptr<PendingReadBack> read_into_async(uint32_t* dst);
  // The host copy, current, for changing in place (a kernel writing some elements and
  // keeping the others): the device copy becomes stale.
  uint32_t* host_data_for_write();
  // The host copy for replacing every word: nothing is read back, the device copy becomes
  // stale.
  uint32_t* host_data_for_overwrite();
  // The host copy, current, for changing words [first, first + n) in place: a device copy
  // that was current becomes stale in those words only (stale_words), so that a backend can
  // upload just them (an animation's moving triangles among the static ones).
  uint32_t* host_data_for_write_range(size_t first, size_t n);
  // The words [first, end) in which the device copy differs from the host copy when it is
  // stale: every word unless only host_data_for_write_range wrote since it was current.
  std::pair<size_t, size_t> stale_words() const {
    return stale_all_ ? std::pair<size_t, size_t>{0, words()}
                      : std::pair<size_t, size_t>{stale_first_, stale_end_};
  }

  // Backend b's buffer if b holds the device copy (current or stale), else null.
  template <class T>
  T* device_buffer(const Backend* b) const {
    return device_owner_ == b ? static_cast<T*>(device_.get()) : nullptr;
  }
  // The backend holding the device copy (current or stale), or null.
  Backend* device_owner() const { return device_ ? device_owner_ : nullptr; }
  // Whether the device copy is the current one (the host copy is stale until read back).
  bool device_is_newer() const { return !host_valid_; }
  // Whether b holds the device copy and it is current.
  bool is_device_current(const Backend* b) const {
    return device_owner_ == b && device_ && device_valid_;
  }
  // b's new (not yet filled) buffer takes the place of any device copy; the host copy is
  // made current first, since the copy replaced may have been the only current one.
  void set_device_buffer(Backend* b, std::unique_ptr<DeviceBuffer> buffer);
  // b filled its buffer from the host copy: both copies are current.
  void mark_device_current(const Backend* b);
  // b's kernel wrote its buffer: the host copy is stale until read back.
  void mark_device_written(const Backend* b);
  // Makes the host copy current and drops the device copy (its buffer is destroyed).
  void release_device_copy();

 private:
  // Makes the host copy current, reading the device copy back if it is newer.
  void sync_to_host();
  // Throws an internal error unless b holds the device copy.
  void require_device(const Backend* b, const char* what) const;

  ir::Type type_;
  int64_t count_ = 0;
  std::vector<uint32_t> host_;  // count_ * type_.width words
  bool host_valid_ = true;
  // The backend holding the device copy, its buffer, and whether that copy is current.
  Backend* device_owner_ = nullptr;
  std::unique_ptr<DeviceBuffer> device_;
  bool device_valid_ = false;
  uint64_t version_ = 0;  // bumped on every host write, so backends can cache uploads
  // The device copy's stale words, when only some are (stale_all_ false).
  bool stale_all_ = true;
  size_t stale_first_ = 0, stale_end_ = 0;
};

// Data a kernel can gather from at any index: an Array, or a Stream (a stream is an array
// whose shape is fixed when it is made). `dims` is how many indices a gather takes.
struct ArrayState : Storage {
  std::string name;
  int dims = 1;
  int64_t shape[3] = {0, 1, 1};
};

// A stream: the elements a kernel runs over. Stream(n) is 1D (gathered as s[i]); Stream(w, h)
// is 2D (gathered as s(x, y)), even when h is 1.
struct StreamState : ArrayState {
  int64_t width = 0, height = 1;  // shape; width * height == count
};

template <class V>
using HostOf = typename V::host_type;

// Shapes s as a stream of w x h elements of t (dims 1: gathered as s[i]; 2: as s(x, y)).
void init_stream(StreamState& s, ir::Type t, int64_t w, int64_t h, int dims, std::string name);

template <class V>
void copy_in(Storage& s, std::span<const HostOf<V>> data) {
  if (static_cast<int64_t>(data.size()) != s.count())
    throw Error("upload of " + std::to_string(data.size()) + " elements into a stream of " +
                std::to_string(s.count()));
  uint32_t* host = s.host_data_for_overwrite();
  if (s.words() != 0) std::memcpy(host, data.data(), s.words() * 4);
}

template <class V>
void copy_in_range(Storage& s, int64_t first, std::span<const HostOf<V>> data) {
  const int64_t n = static_cast<int64_t>(data.size());
  if (first < 0 || n > s.count() - first)
    throw Error("upload of elements " + std::to_string(first) + ".." +
                std::to_string(first + n - 1) + " into a stream of " + std::to_string(s.count()));
  if (n == 0) return;
  const size_t w = static_cast<size_t>(s.type().width);
  uint32_t* host =
      s.host_data_for_write_range(static_cast<size_t>(first) * w, static_cast<size_t>(n) * w);
  std::memcpy(host + static_cast<size_t>(first) * w, data.data(), static_cast<size_t>(n) * w * 4);
}

template <class V>
void copy_out(Storage& s, std::span<HostOf<V>> out) {
  if (static_cast<int64_t>(out.size()) != s.count())
    throw Error("download of a stream of " + std::to_string(s.count()) + " elements into " +
                std::to_string(out.size()));
  if (s.words() != 0) s.read_into(reinterpret_cast<uint32_t*>(out.data()));
}

template <class V>
ReadBack copy_out_async(Storage& s, std::span<HostOf<V>> out) {
  if (static_cast<int64_t>(out.size()) != s.count())
    throw Error("download of a stream of " + std::to_string(s.count()) + " elements into " +
                std::to_string(out.size()));
  if (s.words() == 0) return ReadBack();
  return ReadBack(s.read_into_async(reinterpret_cast<uint32_t*>(out.data())));
}

template <class V>
std::vector<HostOf<V>> copy_out(Storage& s) {
  std::vector<HostOf<V>> out(static_cast<size_t>(s.count()));
  copy_out<V>(s, std::span<HostOf<V>>(out));
  return out;
}

}  // namespace detail

// How gathers read outside an array; ir::Boundary (rill/ir/IR.h) defines each mode exactly.
using Boundary = ir::Boundary;

namespace detail {
// What a gather with `mode` reads outside an array or stream of V (kind "array" or "stream"):
// `outside`, which only Boundary::Constant may set.
template <class V>
ir::Constant border_of(Boundary mode, const HostOf<V>& outside, const std::string& kind,
                       const std::string& name) {
  if (mode != Boundary::Constant && !(outside == HostOf<V>{}))
    throw Error(kind + " '" + name + "': only Boundary::Constant takes a value for outside the " +
                kind + " (the mode given is " + ir::boundary_name(mode) + ")");
  ir::Constant c{};
  c.type = V::type();
  std::memcpy(c.bits.data(), &outside, sizeof outside);
  return c;
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
  static_assert(sizeof(detail::HostOf<V>) == 4 * V::width ||
                    std::is_same_v<typename V::scalar_type, bool>,
                "rill: unexpected host layout");
  static_assert(!std::is_same_v<typename V::scalar_type, bool>,
                "rill: streams hold Float or Int elements (store a Bool as an Int)");

 public:
  using host_type = detail::HostOf<V>;

  explicit Stream(int64_t n, std::string name = "stream")
      : s_(std::make_shared<detail::StreamState>()) {
    init(n, 1, 1, std::move(name));
  }
  Stream(int64_t width, int64_t height, std::string name = "stream")
      : s_(std::make_shared<detail::StreamState>()) {
    init(width, height, 2, std::move(name));
  }
  Stream(std::span<const host_type> data) : Stream(static_cast<int64_t>(data.size())) {
    upload(data);
  }
  Stream(const std::vector<host_type>& data) : Stream(std::span<const host_type>(data)) {}
  // Another handle on an existing stream (a field of a record stream, a stream bound
  // elsewhere), checked to hold elements of V.
  explicit Stream(const StreamRef& r) : s_(r.shared()) {
    if (s_->type() != V::type())
      throw Error("stream '" + s_->name + "' holds " + s_->type().str() + " elements, not " +
                  V::type().str());
  }

  int64_t size() const { return s_->count(); }
  int64_t width() const { return s_->width; }
  int64_t height() const { return s_->height; }

  void upload(std::span<const host_type> data) { detail::copy_in<V>(*s_, data); }
  void upload(const std::vector<host_type>& data) { upload(std::span<const host_type>(data)); }
  // The elements, from whichever copy is newer (a device copy is read straight into the
  // result; the stream's host copy is left as it was).
  std::vector<host_type> download() const { return detail::copy_out<V>(*s_); }
  // The same into memory of the caller's (size() elements), for frames that reuse it.
  void download_into(std::span<host_type> out) const { detail::copy_out<V>(*s_, out); }
  // The same, returning at once (ReadBack.h): `out` holds the elements of now once the
  // result's wait() returns, whatever kernels write the stream meanwhile; it must stay in
  // place until then. Backends that cannot overlap a read-back copy before returning.
  ReadBack download_async(std::span<host_type> out) const {
    return detail::copy_out_async<V>(*s_, out);
  }
  // Sets every element to v.
  void fill(const host_type& v) { upload(std::vector<host_type>(static_cast<size_t>(size()), v)); }

  const std::string& name() const { return s_->name; }

  // Gathers inside a kernel, from what an earlier launch wrote (no host round trip): s[i] on a
  // 1D stream, s(x, y) on a 2D one. Indices outside are clamped, as for arrays. A launch may
  // not gather from a stream it writes (Kernel checks); reading the element's own value
  // through an Input stays the way to update in place.
  V operator[](const Int& i) const { return gather({i.operand()}, 1); }
  V operator()(const Int& i) const { return gather({i.operand()}, 1); }
  V operator()(const Int& x, const Int& y) const { return gather({x.operand(), y.operand()}, 2); }
  V operator()(const Int2& xy) const { return (*this)(Int(xy.x()), Int(xy.y())); }
  // How this handle's gathers read outside the stream, as Array::boundary (clamp by default):
  //   Stream<Float> h(w, h); h.boundary(Boundary::Wrap);  // h(-1, y) reads h(w - 1, y)
  Stream& boundary(Boundary mode, const host_type& outside = host_type{}) {
    border_ = detail::border_of<V>(mode, outside, "stream", s_->name);
    boundary_ = mode;
    return *this;
  }

  operator StreamRef() const { return StreamRef(s_); }

 private:
  void init(int64_t w, int64_t h, int dims, std::string name) {
    detail::init_stream(*s_, V::type(), w, h, dims, std::move(name));
  }
  V gather(std::vector<ir::Operand> idx, int dims) const {
    if (dims != s_->dims)
      throw Error("stream '" + s_->name + "' is " + std::to_string(s_->dims) +
                      "D but was gathered with " + std::to_string(dims) + " indices" +
                      (s_->dims == 2 ? " (gather a 2D stream as s(x, y))"
                                     : " (a 1D stream is gathered as s[i])"),
                  detail::nearest_location());
    return V(detail::emit_gather(s_, std::move(idx), boundary_, border_), detail::AdoptTag{});
  }
  std::shared_ptr<detail::StreamState> s_;
  Boundary boundary_ = Boundary::Clamp;
  ir::Constant border_{};
};

template <class V>
class Array {
  static_assert(!std::is_same_v<typename V::scalar_type, bool>,
                "rill: arrays hold Float or Int elements");

 public:
  using host_type = detail::HostOf<V>;

  explicit Array(int64_t n, std::string name = "array") : Array(1, {n, 1, 1}, std::move(name)) {}
  Array(int64_t nx, int64_t ny, std::string name = "array")
      : Array(2, {nx, ny, 1}, std::move(name)) {}
  Array(int64_t nx, int64_t ny, int64_t nz, std::string name = "array")
      : Array(3, {nx, ny, nz}, std::move(name)) {}
  Array(const std::vector<host_type>& data, std::string name = "array")
      : Array(static_cast<int64_t>(data.size()), std::move(name)) {
    upload(data);
  }
  // A 2D or 3D array with its data, laid out x fastest: element (x, y, z) is
  // data[x + nx * (y + ny * z)]. data must hold exactly nx * ny (* nz) elements.
  Array(int64_t nx, int64_t ny, const std::vector<host_type>& data, std::string name = "array")
      : Array(2, {nx, ny, 1}, std::move(name)) {
    upload_shaped(data);
  }
  Array(int64_t nx, int64_t ny, int64_t nz, const std::vector<host_type>& data,
        std::string name = "array")
      : Array(3, {nx, ny, nz}, std::move(name)) {
    upload_shaped(data);
  }

  // How this array's gathers read outside it, captured into programs as they read it (a
  // program keeps the mode it was captured with; changing it affects programs captured
  // afterwards). Constant reads `outside` (zero by default) wherever any index is out of
  // range. The mode belongs to this Array object: a copy shares the data and may read it with
  // another mode, even in the same program.
  //
  //   Array<Float> a(data, "a");
  //   a.boundary(Boundary::Wrap);               // a[-1] reads the last element
  //   a.boundary(Boundary::Constant, 0.5f);     // a[-1] reads 0.5
  Array& boundary(Boundary mode) { return boundary(mode, host_type{}); }
  Array& boundary(Boundary mode, const host_type& outside) {
    border_ = detail::border_of<V>(mode, outside, "array", s_->name);
    boundary_ = mode;
    return *this;
  }
  Boundary boundary() const { return boundary_; }
  // What Boundary::Constant reads outside the array.
  host_type outside() const {
    host_type v;
    std::memcpy(&v, border_.bits.data(), sizeof v);
    return v;
  }

  int64_t size() const { return s_->count(); }
  void upload(std::span<const host_type> data) { detail::copy_in<V>(*s_, data); }
  // Replaces elements first .. first + data.size() - 1 and keeps the others: a backend then
  // uploads only what changed (an animation's moving triangles).
  void upload(int64_t first, std::span<const host_type> data) {
    detail::copy_in_range<V>(*s_, first, data);
  }
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
      throw Error("array '" + s_->name + "' is " + std::to_string(s_->dims) +
                      "D but was indexed with " + std::to_string(dims) + " indices",
                  detail::nearest_location());
    return V(detail::emit_gather(s_, std::move(idx), boundary_, border_), detail::AdoptTag{});
  }
  void upload_shaped(const std::vector<host_type>& data) {
    if (static_cast<int64_t>(data.size()) != size()) {
      std::string shape = std::to_string(s_->shape[0]) + " x " + std::to_string(s_->shape[1]);
      if (s_->dims == 3) shape += " x " + std::to_string(s_->shape[2]);
      throw Error("array '" + s_->name + "': " + std::to_string(data.size()) +
                  " elements given for a " + shape + " array, which holds " +
                  std::to_string(size()) +
                  " (laid out x fastest: element (x, y, z) at x + nx * (y + ny * z))");
    }
    upload(data);
  }
  std::shared_ptr<detail::ArrayState> s_;
  Boundary boundary_ = Boundary::Clamp;
  ir::Constant border_{V::type(), {}};  // for Boundary::Constant
};

}  // namespace rill
