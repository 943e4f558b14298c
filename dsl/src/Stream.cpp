#include "rill/Stream.h"

#include "rill/Backend.h"

namespace rill::detail {

void Storage::init(ir::Type t, int64_t n) {
  type = t;
  count = n;
  host.assign(static_cast<size_t>(n) * t.width, 0u);
  host_valid = true;
  device_valid = false;
  ++version;
}

void Storage::sync_to_host() {
  if (host_valid) return;
  if (!device_owner) throw Error("internal: stream has no valid copy");
  device_owner->read_back(*this);
  host_valid = true;
}

void Storage::host_written() {
  host_valid = true;
  device_valid = false;
  ++version;
}

}  // namespace rill::detail
