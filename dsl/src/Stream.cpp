#include "rill/Stream.h"

#include "rill/Backend.h"

#include <algorithm>

namespace rill::detail {

void Storage::init(ir::Type t, int64_t n) {
  type_ = t;
  count_ = n;
  host_.assign(static_cast<size_t>(n) * t.width, 0u);
  host_valid_ = true;
  device_valid_ = false;
  stale_all_ = true;
  ++version_;
}

void init_stream(StreamState& s, ir::Type t, int64_t w, int64_t h, int dims, std::string name) {
  if (w < 0 || h < 1)
    throw Error("stream '" + name + "': shape " + std::to_string(w) + " x " + std::to_string(h) +
                " (the width must be >= 0 and the height >= 1)");
  s.init(t, w * h);
  s.width = w;
  s.height = h;
  s.name = std::move(name);
  s.dims = dims;
  s.shape[0] = w;
  s.shape[1] = dims == 2 ? h : 1;
  s.shape[2] = 1;
}

void Storage::sync_to_host() {
  if (host_valid_) return;
  if (!device_owner_ || !device_) throw Error("internal: stream has no valid copy");
  device_owner_->read_back(*this, host_.data());
  host_valid_ = true;
}

const uint32_t* Storage::host_data_for_read() {
  sync_to_host();
  return host_.data();
}

void Storage::read_into(uint32_t* dst) {
  if (host_valid_) {
    if (!host_.empty()) std::memcpy(dst, host_.data(), host_.size() * 4);
    return;
  }
  if (!device_owner_ || !device_) throw Error("internal: stream has no valid copy");
  device_owner_->read_back(*this, dst);
}

std::unique_ptr<PendingReadBack> Storage::read_into_async(uint32_t* dst) {
  if (host_valid_) {
    read_into(dst);
    return nullptr;
  }
  if (!device_owner_ || !device_) throw Error("internal: stream has no valid copy");
  return device_owner_->read_back_async(*this, dst);
}

uint32_t* Storage::host_data_for_write() {
  sync_to_host();
  return host_data_for_overwrite();
}

uint32_t* Storage::host_data_for_overwrite() {
  host_valid_ = true;
  device_valid_ = false;
  stale_all_ = true;
  ++version_;
  return host_.data();
}

uint32_t* Storage::host_data_for_write_range(size_t first, size_t n) {
  sync_to_host();
  const size_t end = first + n;
  if (device_valid_) {  // current until now: stale in these words only
    stale_all_ = false;
    stale_first_ = first;
    stale_end_ = end;
  } else if (!stale_all_) {  // stale in a range already: in both
    stale_first_ = std::min(stale_first_, first);
    stale_end_ = std::max(stale_end_, end);
  }
  host_valid_ = true;
  device_valid_ = false;
  ++version_;
  return host_.data();
}

void Storage::require_device(const Backend* b, const char* what) const {
  if (!b || device_owner_ != b || !device_)
    throw Error(std::string("internal: ") + what +
                " by a backend that does not hold the device copy");
}

void Storage::set_device_buffer(Backend* b, std::unique_ptr<DeviceBuffer> buffer) {
  sync_to_host();
  device_ = std::move(buffer);
  device_owner_ = b;
  device_valid_ = false;
  stale_all_ = true;
}

void Storage::mark_device_current(const Backend* b) {
  require_device(b, "mark_device_current");
  if (!host_valid_) throw Error("internal: a device copy was filled from a stale host copy");
  device_valid_ = true;
  stale_all_ = false;
  stale_first_ = stale_end_ = 0;
}

void Storage::mark_device_written(const Backend* b) {
  require_device(b, "mark_device_written");
  host_valid_ = false;
  device_valid_ = true;
  stale_all_ = false;
  stale_first_ = stale_end_ = 0;
}

void Storage::release_device_copy() {
  sync_to_host();
  device_.reset();
  device_owner_ = nullptr;
  device_valid_ = false;
  stale_all_ = true;
}

}  // namespace rill::detail
