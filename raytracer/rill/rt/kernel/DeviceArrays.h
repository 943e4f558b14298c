// Filling the kernels' Rill arrays from host vectors. An array holds at least one element
// (Rill arrays cannot be empty), so empty data gets a dummy element the kernels never read.
#pragma once

#include <rill/rill.h>

#include <vector>

namespace rt {

template <class V>
std::vector<typename V::host_type> padded(std::vector<typename V::host_type> v) {
  if (v.empty()) v.emplace_back();
  return v;
}

template <class V>
void upload_padded(rill::Array<V>& a, std::vector<typename V::host_type> v) {
  v = padded<V>(std::move(v));
  a.resize(static_cast<int64_t>(v.size()));
  a.upload(v);
}

}  // namespace rt
