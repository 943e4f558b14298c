// A read-back in flight (ReadBack.h): waited for before it goes.
#include "rill/ReadBack.h"

namespace rill {

ReadBack& ReadBack::operator=(ReadBack&& other) noexcept {
  if (this != &other) {
    try {
      wait();        // the memory of the one in flight may be reused next
    } catch (...) {  // dropped, as the destructor does
    }
    pending_ = std::move(other.pending_);
  }
  return *this;
}

ReadBack::~ReadBack() {
  try {
    wait();
  } catch (...) {  // dropped, as documented: wait() reports it
  }
}

void ReadBack::wait() {
  // Taken first: a transfer that fails is not waited for again.
  std::unique_ptr<PendingReadBack> p = std::move(pending_);
  if (p) p->wait();
}

}  // namespace rill
