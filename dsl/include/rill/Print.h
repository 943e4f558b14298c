// Printing from kernels: rill::print and rill::print_if.
//
//   auto k = rill::program("k", [&] {
//     rill::Input<Float> x("x");
//     rill::Output<Float> y("y");
//     rill::print("x = {} at {}", x, rill::element_index());
//     rill::print_if(x < 0.0f, "negative x {}", x);
//     y = x;
//   });
//
// A print writes nothing while the kernel runs but the raw bits of its arguments, into
// per-element slots (hidden outputs of the kernel, which Kernel binds and reads back itself);
// after the launch the host formats them. So every backend prints the same text in the same
// order: element by element, and within an element the prints in the order the program
// captured them. Each print statement gives one line per element: its arguments the first
// time it ran there, and "[ran N times]" after the line when it ran more often (in a loop).
// Elements that are discarded keep no slots, and print nothing.
//
// Only the first Kernel::print_limit() elements that printed are shown (16 unless changed,
// or RILL_PRINT_LIMIT in the environment); a last line counts the elements left out. The
// text goes to print_output() (standard output unless changed), and Kernel::last_print()
// returns it. A kernel without print compiles to exactly the code it had without this file.
//
// Formats use "{}" for each argument ("{{" and "}}" for braces). Floats print as the
// shortest decimal that reads back as the same binary32 (std::to_chars), so the text is as
// exact, and as backend-independent, as the bits; vectors print as "(1, 2.5, -0)", bools as
// true / false.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "rill/Value.h"

namespace rill {

// A print's format string, with the place it was written (for errors).
struct PrintFormat {
  std::string text;
  SourceLoc loc;
  PrintFormat(const char* t, SourceLoc l = RILL_HERE) : text(t), loc(l) {}
  PrintFormat(std::string t, SourceLoc l = RILL_HERE) : text(std::move(t)), loc(l) {}
};

namespace detail {
struct PrintArg {
  ir::Operand operand;
  ir::Type type;
};
template <class T, int N>
PrintArg print_arg(const Value<T, N>& v) {
  return {v.operand(), Value<T, N>::type()};
}
// Records a print whose line is shown where `cond` holds (a constant true for print).
void record_print(const Bool& cond, const PrintFormat& format, const std::vector<PrintArg>& args);

// The text a print's argument gives, from its raw bits (Print.cpp; tests use it).
std::string format_value(ir::Type t, const uint32_t* bits);
// Replaces each "{}" of `format` by the next of `values`; "{{" and "}}" are braces.
std::string format_line(const std::string& format, const std::vector<std::string>& values);
}  // namespace detail

// Prints one line per element (see above).
template <class... A>
void print(PrintFormat format, const A&... args) {
  detail::record_print(Bool(true), format, {detail::print_arg(args)...});
}
// Prints only in the elements where `cond` holds.
template <class... A>
void print_if(const Bool& cond, PrintFormat format, const A&... args) {
  detail::record_print(cond, format, {detail::print_arg(args)...});
}

// Where kernels' printed text goes (standard output by default); returns the stream it
// replaces. nullptr silences printing (Kernel::last_print() still has the text).
std::ostream* set_print_output(std::ostream* os);
std::ostream* print_output();

}  // namespace rill
