// The messages as bytes (Messages.h).
#include "distributed/Messages.h"

namespace rt::distributed {

namespace {

class Writer {
 public:
  template <class T>
  requires std::is_trivially_copyable_v<T> Writer& put(const T& v) {
    const char* p = reinterpret_cast<const char*>(&v);
    b_.insert(b_.end(), p, p + sizeof v);
    return *this;
  }
  Writer& put(const std::string& s) {
    put(static_cast<uint64_t>(s.size()));
    b_.insert(b_.end(), s.begin(), s.end());
    return *this;
  }
  template <class T>
  Writer& put(const std::vector<T>& v) {
    put(static_cast<uint64_t>(v.size()));
    const char* p = reinterpret_cast<const char*>(v.data());
    b_.insert(b_.end(), p, p + v.size() * sizeof(T));
    return *this;
  }
  Writer& put(const Tile& t) {
    return put(t.id).put(t.frame).put(t.x).put(t.y).put(t.width).put(t.height);
  }
  // Running sums (a round's slice): size, samples, then the sum, carry and squares.
  Writer& put(const Accumulation& a) {
    return put(a.width).put(a.height).put(a.samples).put(a.sum).put(a.carry).put(a.squares);
  }
  Bytes take() { return std::move(b_); }

 private:
  Bytes b_;
};

class Reader {
 public:
  explicit Reader(const Bytes& b) : b_(b) {}
  template <class T>
  requires std::is_trivially_copyable_v<T> Reader& get(T& v) {
    std::memcpy(&v, take(sizeof v), sizeof v);
    return *this;
  }
  Reader& get(std::string& s) {
    const size_t n = count(1);
    const char* p = take(n);
    s.assign(p, n);
    return *this;
  }
  template <class T>
  Reader& get(std::vector<T>& v) {
    const size_t n = count(sizeof(T));
    v.resize(n);
    if (n > 0) std::memcpy(v.data(), take(n * sizeof(T)), n * sizeof(T));
    return *this;
  }
  Reader& get(Tile& t) {
    return get(t.id).get(t.frame).get(t.x).get(t.y).get(t.width).get(t.height);
  }
  Reader& get(Accumulation& a) {
    return get(a.width).get(a.height).get(a.samples).get(a.sum).get(a.carry).get(a.squares);
  }
  void end() const {
    if (at_ != b_.size()) throw std::runtime_error("distributed: a message has trailing bytes");
  }

 private:
  size_t count(size_t element) {
    uint64_t n = 0;
    get(n);
    if (n > (b_.size() - at_) / element)
      throw std::runtime_error("distributed: a message is shorter than it says");
    return static_cast<size_t>(n);
  }
  const char* take(size_t n) {
    if (n > b_.size() - at_) throw std::runtime_error("distributed: a message is cut short");
    const char* p = b_.data() + at_;
    at_ += n;
    return p;
  }
  const Bytes& b_;
  size_t at_ = 0;
};

}  // namespace

const char* tag_name(int tag) {
  switch (tag) {
    case kHello:
      return "hello";
    case kAbort:
      return "abort";
    case kAssign:
      return "assign";
    case kTileDone:
      return "tile done";
    case kFailed:
      return "failed";
    case kStop:
      return "stop";
    case kHeartbeat:
      return "heartbeat";
  }
  return "unknown";
}

Bytes pack(const Hello& m) {
  return Writer().put(m.ok).put(m.scene_hash).put(m.host).put(m.backend).put(m.message).take();
}
void unpack(const Bytes& b, Hello& m) {
  Reader(b).get(m.ok).get(m.scene_hash).get(m.host).get(m.backend).get(m.message).end();
}

Bytes pack(const Assign& m) {
  return Writer().put(m.tile).put(m.spp).put(m.accumulation).put(m.resume).take();
}
void unpack(const Bytes& b, Assign& m) {
  Reader(b).get(m.tile).get(m.spp).get(m.accumulation).get(m.resume).end();
}

Bytes pack(const TileDone& m) {
  const RenderResult& p = m.pixels;
  return Writer()
      .put(m.id)
      .put(m.busy_ms)
      .put(p.width)
      .put(p.height)
      .put(p.rays)
      .put(p.rgb8)
      .put(p.color)
      .put(p.depth)
      .put(p.prim)
      .put(p.normal)
      .put(p.albedo)
      .put(p.variance)
      .put(p.spp)
      .put(p.accumulation)
      .take();
}
void unpack(const Bytes& b, TileDone& m) {
  RenderResult& p = m.pixels;
  Reader(b)
      .get(m.id)
      .get(m.busy_ms)
      .get(p.width)
      .get(p.height)
      .get(p.rays)
      .get(p.rgb8)
      .get(p.color)
      .get(p.depth)
      .get(p.prim)
      .get(p.normal)
      .get(p.albedo)
      .get(p.variance)
      .get(p.spp)
      .get(p.accumulation)
      .end();
}

Bytes pack(const Text& m) {
  return Writer().put(m.message).take();
}
void unpack(const Bytes& b, Text& m) {
  Reader(b).get(m.message).end();
}

}  // namespace rt::distributed
