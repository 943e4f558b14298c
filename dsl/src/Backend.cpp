#include "rill/Backend.h"

#include <map>
#include <mutex>

namespace rill {

const char* origin_name(KernelOrigin o) {
  switch (o) {
    case KernelOrigin::Built:
      return "built";
    case KernelOrigin::ProcessCache:
      return "process cache";
    case KernelOrigin::DiskCache:
      return "disk cache";
    case KernelOrigin::DriverCache:
      return "driver cache";
  }
  return "unknown";
}

namespace detail {
// Defined by the library that bundles the backends (backends/Registry.cpp).
void register_builtin_backends();
}  // namespace detail

namespace {
// Owns every backend until exit. Backends are destroyed last-registered first (the reverse of
// the order they were made in), in the registry's destructor, not in whatever order the
// vector would choose. A backend holding driver state shuts it down explicitly before that
// (the GLSL backend from an exit handler, see GLSLBackend.cpp), so no backend's destructor
// depends on when the registry, a static, is destroyed relative to the drivers.
struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<Backend>> list;
  std::once_flag builtins;  // other threads wait until every built-in backend is registered
  ~Registry() {
    while (!list.empty()) list.pop_back();
  }
};
Registry& registry() {
  static Registry r;
  return r;
}
void ensure_builtins() {
  std::call_once(registry().builtins, detail::register_builtin_backends);
}
}  // namespace

void register_backend(std::unique_ptr<Backend> b) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (auto& existing : r.list)
    if (existing->name() == b->name())
      throw Error("backend '" + b->name() + "' is registered twice");
  r.list.push_back(std::move(b));
}

std::vector<Backend*> backends() {
  ensure_builtins();
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<Backend*> out;
  for (auto& b : r.list) out.push_back(b.get());
  return out;
}

Backend& backend(const std::string& name) {
  std::string known;
  for (Backend* b : backends()) {
    if (b->name() == name) return *b;
    known += (known.empty() ? "" : ", ") + b->name();
  }
  throw Error("unknown backend '" + name + "' (this build has: " + known + ")");
}

}  // namespace rill
