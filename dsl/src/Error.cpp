#include "rill/Error.h"

#include <cstring>

namespace rill {

std::string SourceLoc::str() const {
  if (!known()) return {};
  // Shorten to the file name: full build paths make messages hard to read.
  const char* slash = std::strrchr(file, '/');
  return std::string(slash ? slash + 1 : file) + ":" + std::to_string(line);
}

}  // namespace rill
