#include "rill/Options.h"

#include "rill/Error.h"
#include "rill/ir/Hash.h"

namespace rill {

const char* accuracy_name(Accuracy a) {
  switch (a) {
    case Accuracy::Strict:
      return "strict";
    case Accuracy::Fast:
      return "fast";
    case Accuracy::Double:
      return "double";
  }
  return "?";
}

Accuracy parse_accuracy(const std::string& s) {
  if (s == "strict") return Accuracy::Strict;
  if (s == "fast") return Accuracy::Fast;
  if (s == "double") return Accuracy::Double;
  throw Error("unknown accuracy mode '" + s + "' (expected strict, fast or double)");
}

uint64_t CompileOptions::hash() const {
  std::string key = accuracy_name(accuracy);
  key += passes.constant_folding ? 'F' : 'f';
  key += passes.copy_propagation ? 'P' : 'p';
  key += passes.common_subexpressions ? 'C' : 'c';
  key += passes.dead_code ? 'D' : 'd';
  if (debug) key += debug_nonfinite ? "+debug+nonfinite" : "+debug";  // absent: keys as before
  if (source_map) key += 'S';  // only when on: the keys of kernels without it stay as they were
  return ir::hash_bytes(key);
}

}  // namespace rill
