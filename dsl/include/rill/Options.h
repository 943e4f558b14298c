// The options a compile takes: the accuracy mode and which optimizer passes run.
//
// Kept apart from Backend.h so that the passes (rill/passes/Passes.h) and the emitters can
// name an accuracy mode without pulling in streams, storage and GLM.
#pragma once

#include <cstdint>
#include <string>

namespace rill {

enum class Accuracy : uint8_t {
  Strict,  // IEEE binary32, no contraction, same bits on every backend
  Fast,    // native builtins, contraction and relaxed math allowed
  Double,  // binary64 arithmetic where the backend has it (the reference)
};
const char* accuracy_name(Accuracy a);
Accuracy parse_accuracy(const std::string& s);  // "strict" | "fast" | "double"

// Which optimizer passes run; each can be switched off (for debugging or comparison).
struct PassOptions {
  bool constant_folding = true;
  bool copy_propagation = true;
  bool common_subexpressions = true;
  bool dead_code = true;
  bool operator==(const PassOptions&) const = default;
};

struct CompileOptions {
  Accuracy accuracy = Accuracy::Strict;
  PassOptions passes;
  // The debug mode (docs/debugging.md): gathers check their indices and a launch that read
  // outside an array throws, naming the element, index and array; with debug_nonfinite too,
  // the first statement that produced a NaN or infinity. Never changes a result in range.
  // RILL_DEBUG=1 (or =nonfinite) in the environment turns it on for every compile.
  bool debug = false;
  bool debug_nonfinite = false;
  // Source maps: the generated C, lockstep C and OpenCL C carry #line directives naming the
  // user's lines, and GLSL comments (docs/programming-model.md#source-maps). Also on with
  // RILL_SOURCE_MAP=1. Off, the generated code is as it was without the option.
  bool source_map = false;
  bool operator==(const CompileOptions&) const = default;
  uint64_t hash() const;
};

}  // namespace rill
