#include "rill/ir/Hash.h"

#include <cstdio>

#include "rill/ir/Printer.h"

namespace rill::ir {

uint64_t hash_bytes(std::string_view bytes, uint64_t h) {
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ull;
  }
  return h;
}

uint64_t hash(const Function& f) {
  // The printed form is complete (types, interface, body, every constant's exact bits) and
  // independent of pointers and process state, which makes the hash stable. The kernel's
  // name and its arrays' names are left out: renaming does not change what it computes, and
  // the generated code refers to arrays by position. (Library kernels such as reductions
  // gather from streams of any name and must not recompile for each.)
  Function unnamed = f;
  unnamed.name.clear();
  for (ArrayDecl& a : unnamed.arrays) a.name.clear();
  return hash_bytes(print(unnamed));
}

std::string hex(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace rill::ir
