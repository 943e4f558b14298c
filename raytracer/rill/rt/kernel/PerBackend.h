// What a tracer keeps per backend and accuracy: the key it is kept under, and frame buffers
// that later frames of the same size reuse. Buffers are never shared between backends: a
// stream's device copy lives on one backend, and sharing would move it every frame.
#pragma once

#include <rill/rill.h>

#include <map>
#include <memory>
#include <string>

namespace rt {

// "backend/accuracy": the key of kernels and buffers kept per backend and accuracy.
inline std::string backend_key(const std::string& backend, rill::Accuracy a) {
  return backend + "/" + rill::accuracy_name(a);
}

// The buffers kept under `key` when they are width x height (B(width, height) has members
// `width` and `height`), else new ones in their place: the old streams go before the new
// ones are made.
template <class B>
B& buffers_for(std::map<std::string, std::unique_ptr<B>>& kept, const std::string& key, int width,
               int height) {
  std::unique_ptr<B>& b = kept[key];
  if (!b || b->width != width || b->height != height) {
    b.reset();
    b = std::make_unique<B>(width, height);
  }
  return *b;
}

}  // namespace rt
