// The simd backend: the lockstep form of a kernel (LockstepEmitter.h, VectorDialect.h), groups
// of kLockstepLanes elements in vector registers with masks for divergent control flow, compiled
// like cpu's C and run on the same host launcher (backends/cpu/HostKernel.h). Its results are
// bit for bit those of `cpu` in strict. The double mode, the accuracy reference rather than a
// speed mode, runs cpu's scalar C and says so (Backend::accuracy_note, CompileInfo::execution).
#pragma once

#include <memory>

#include "rill/Backend.h"

namespace rill::simd {

std::unique_ptr<Backend> make_backend();  // "simd"

}  // namespace rill::simd
