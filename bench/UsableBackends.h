// The benchmarks' backend lists: which of the backends asked for can run here; the others are
// printed once, as skipped, with the reason.
#pragma once

#include <rill/rill.h>

#include <cstdio>
#include <string>
#include <vector>

namespace rill::bench {

inline bool has(const std::vector<std::string>& v, const std::string& s) {
  for (const auto& x : v)
    if (x == s) return true;
  return false;
}

inline std::vector<std::string> usable_backends(const std::vector<std::string>& wanted) {
  std::vector<std::string> out;
  for (const auto& name : wanted) {
    Backend* b = nullptr;
    for (Backend* c : backends())
      if (c->name() == name) b = c;
    if (!b) {
      std::printf("  %-8s skipped: not built into this Rill\n", name.c_str());
    } else if (std::string why = b->unavailable_reason(); !why.empty()) {
      std::printf("  %-8s skipped: %s\n", name.c_str(), why.c_str());
    } else {
      out.push_back(name);
    }
  }
  return out;
}

}  // namespace rill::bench
