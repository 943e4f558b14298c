#include "rill/ir/Type.h"

namespace rill::ir {

const char* kind_name(ScalarKind k) {
  switch (k) {
    case ScalarKind::Float: return "float";
    case ScalarKind::Int: return "int";
    case ScalarKind::Bool: return "bool";
  }
  return "?";
}

std::string Type::str() const {
  std::string s = kind_name(kind);
  if (width > 1) s += std::to_string(width);
  return s;
}

}  // namespace rill::ir
