// Program algebra (after Sh): building new programs out of captured ones, without re-running
// their bodies.
//
//   Program shade = program("shade", [&] { Input<Float3> n("n"); Output<Float3> rgb("rgb"); ... });
//   Program tone  = program("tone",  [&] { Input<Float3> rgb("rgb"); Output<Int> pixel("pixel");
//   ... }); Program both  = connect(shade, tone);   // or shade >> tone: inputs n, outputs pixel
//   Program pair  = combine(shade, other);  // or shade & other: both on the same element
//
// connect(a, b) feeds a's outputs into b's inputs *by name* and fuses the two into one
// program: a's body runs, then b's, and b reads a's results from locals, so no intermediate
// stream is written or read.
//   - Inputs: a's inputs, then b's inputs that no output of a feeds. An unfed input of b named
//     like an input of a is the same input (one stream feeds both; the types must match).
//   - Outputs: b's outputs, then a's outputs that no input of b reads. Sh drops those; Rill
//     keeps them, so that connecting never loses a result. An output of b and a kept output of
//     a with the same name are therefore an error.
//   - Meaning: the fused kernel writes the same bits as launching a, then b on a's outputs.
//     For that, every output of a that b reads must be written on every path through a: where
//     a leaves it unwritten, the second launch would read the intermediate stream's old value,
//     which the fused kernel does not have. connect detects this (per component, through ifs
//     and loops, conservatively) and throws.
//   - Discards: a discard in a is rejected: where a discards, two launches still run b (on
//     the stale intermediate element), the fused kernel would skip it. A discard in b is fine
//     when b reads every output of a; otherwise it is rejected too, because it would also
//     unwrite a's kept outputs, which a's own launch writes.
//
// combine(a, b) runs both programs on the same element as one kernel: inputs are the union by
// name (the same name is one input; the types must match), outputs a's then b's (the same
// name in both is an error), a's body then b's. The result writes what the two launches
// write. A discard in either is rejected: one in a would skip b's body, one in b would
// unwrite a's outputs, where separate launches write them.
//
// For both: uniforms and arrays are merged, the same Uniform or Array used by both programs
// becomes one entry (two different uniforms with one name are an error, as within one
// program). Variable names are kept; a's variables keep their ids and b's follow them. If a
// assigns to an input that b shares, b gets a copy of the input's value taken before a runs.
// Errors throw rill::Error naming both programs, the input or output, the types involved
// and the caller's source location. The result is an ordinary Program: it passes the
// verifier, has its own hash, and can be printed, compiled, connected and combined again.
#pragma once

#include <string>

#include "rill/Error.h"
#include "rill/Program.h"

namespace rill {

// One program computing b(a(...)); `name` defaults to "a>>b".
Program connect(const Program& a, const Program& b, std::string name = {},
                SourceLoc loc = RILL_HERE);
// One program computing a and b side by side on each element; `name` defaults to "a&b".
Program combine(const Program& a, const Program& b, std::string name = {},
                SourceLoc loc = RILL_HERE);

// Sh's spellings. Operators cannot take the caller's location, so their errors name only the
// programs; call connect / combine to get file:line in messages.
inline Program operator>>(const Program& a, const Program& b) {
  return connect(a, b, {}, {});
}
inline Program operator&(const Program& a, const Program& b) {
  return combine(a, b, {}, {});
}

}  // namespace rill
