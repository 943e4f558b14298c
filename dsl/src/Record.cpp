// The non-template parts of records (Record.h): host leaf conversion and the field makers.
#include "rill/Record.h"

namespace rill::detail {

void leaf_to_words(ir::Type t, const void* host, uint32_t* words) {
  if (t.kind == ir::ScalarKind::Bool) {
    const auto* b = static_cast<const bool*>(host);
    for (int c = 0; c < t.width; ++c) words[c] = b[c] ? 1u : 0u;
  } else {
    std::memcpy(words, host, 4 * static_cast<size_t>(t.width));
  }
}

void words_to_leaf(ir::Type t, const uint32_t* words, void* host) {
  if (t.kind == ir::ScalarKind::Bool) {
    auto* b = static_cast<bool*>(host);
    for (int c = 0; c < t.width; ++c) b[c] = words[c] != 0;
  } else {
    std::memcpy(host, words, 4 * static_cast<size_t>(t.width));
  }
}

Ref UniformMaker::leaf(const std::string& path, ir::Type t) const {
  Ref r;
  r.kind = Ref::Kind::Uniform;
  r.uniform = std::make_shared<UniformState>();
  r.uniform->name = path;
  r.uniform->type = t;
  return r;
}

Ref GatherMaker::leaf(const std::string& path, ir::Type t) const {
  for (const auto& [p, state] : leaves_)
    if (p == path) {
      if (state->type() != t) break;
      return emit_gather(state, index_);
    }
  throw Error("internal: record gather found no " + t.str() + " field '" + path + "'");
}

Ref ListMaker::leaf(const std::string& path, ir::Type t) const {
  if (next_ >= refs_.size())
    throw Error("internal: record has more fields than given ('" + path + "')");
  (void)t;
  return refs_[next_++];
}

}  // namespace rill::detail
