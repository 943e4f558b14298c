// A stable 64-bit hash of a Function: the same program text always hashes the same, in any
// process, on any machine. The kernel caches use it as their key.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "rill/ir/IR.h"

namespace rill::ir {

uint64_t hash(const Function& f);
// FNV-1a, 64-bit; exposed because the backends hash their generated sources with it too.
uint64_t hash_bytes(std::string_view bytes, uint64_t seed = 0xcbf29ce484222325ull);
std::string hex(uint64_t h);

}  // namespace rill::ir
