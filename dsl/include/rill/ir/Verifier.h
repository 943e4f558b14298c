// Checks that a Function is well formed: every operand's type matches its variable and its
// op, masks are valid, break/continue sit inside loops, conditions are scalar bools, every
// output is written. Passes run it after themselves in debug builds and in the tests, so a
// broken pass is caught where it broke, not in a backend compiler.
#pragma once

#include <string>
#include <vector>

#include "rill/ir/IR.h"

namespace rill::ir {

// All problems found, each naming the statement (and its source location when known).
// `outputs_written`: every output must be assigned somewhere (true for captured programs;
// after optimization an output whose only write was unreachable keeps its previous value).
std::vector<std::string> verify(const Function& f, bool outputs_written = true);
// Throws rill::Error listing the problems, prefixed with `context`, if there are any.
void verify_or_throw(const Function& f, const std::string& context, bool outputs_written = true);

}  // namespace rill::ir
