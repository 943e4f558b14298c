// A readable text form of the IR, for users (Kernel::ir()), error messages and tests.
//
//   kernel mandelbrot(in float2 c_0) -> (out float n_1)
//     t3 = mul(z_2.x, z_2.x)
//     if t9 {
//       ...
//
// The text is also what Hash.h hashes, so it is complete: two functions with the same text
// compute the same thing.
#pragma once

#include <string>

#include "rill/ir/IR.h"

namespace rill::ir {

std::string print(const Function& f);
// What print() adds for people: with `locations`, each statement's source location
// (Stmt::loc) after its line, "  @ shade.cpp:12, called from main.cpp:40". The hashed form
// is print(f) alone, which never shows them.
struct PrintOptions {
  bool locations = false;
};
std::string print(const Function& f, const PrintOptions& options);
std::string print(const Function& f, const Block& b, int indent = 0);
std::string print_operand(const Function& f, const Operand& o);
std::string print_constant(const Constant& c);

}  // namespace rill::ir
