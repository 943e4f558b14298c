// Source maps: generated code that names the user's lines, and driver messages read back
// against them.
//
// With CompileOptions::source_map (or RILL_SOURCE_MAP=1) the C-family printer puts a line
// naming the user's statement before each line it generates from it (Dialect::source_line:
// `#line 12 "shade.cpp"` in C, lockstep C and OpenCL C, whose compilers then report that
// line; a comment `// rill: shade.cpp:12` in GLSL). Without it the text is exactly what it
// was without source maps, and a compile error is still reported against the user's line:
// the backend prints the kernel again with the map (regenerate), whose lines, less the
// map's own, are the text the driver saw, and reads the driver's line numbers through it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "rill/Error.h"

namespace rill::codegen {

// What a `#line` directive calls the generated code, where a block of mapped lines ends
// and the numbering of the generated text resumes (as shown by numbered()).
inline constexpr const char* kGeneratedFile = "generated";
// The printer's placeholder for that directive, which finish_source_lines() numbers once the
// backend has the whole text.
inline constexpr const char* kSourceLineRestore = "#line rill-restore";
// The prefix of GLSL's source-map comments.
inline constexpr const char* kSourceComment = "// rill: ";

// loc's file as messages show it (relative_path), escaped for a C string literal.
std::string quoted_file(const SourceLoc& loc);

// Numbers the placeholders of a whole translation unit: each becomes `#line N "generated"`,
// N the number of the line after it, so that lines outside the kernel's statements are
// numbered as the text is.
std::string finish_source_lines(const std::string& source);

// For each line of `shown` (the text a driver compiled), the user's "file:line" it was
// generated from, or "" where unknown. `mapped` is the same kernel printed with the source
// map: either `shown` itself (comments: GLSL; with #line directives the driver's numbers
// are the user's already, and the result is empty), or its version with map lines added
// (then every other line must equal shown's, else nothing is mapped and the result is
// empty).
std::vector<std::string> user_lines(const std::string& shown, const std::string& mapped);

// A driver's error, `e`, about the text `shown`, reported against the user's lines: every
// message line that names a generated line number (gcc, clang and PoCL "F:L:C: ", Mesa
// "0:L(C): ") gets "[from file:line]" after it, and the message starts with the first such
// user line and the generated line beside it. `regenerate` prints the kernel with the
// source map; it runs only here, on the error path. Returns e's text unchanged where
// nothing maps.
std::string with_user_lines(const std::string& what, const std::string& shown,
                            const std::function<std::string()>& regenerate);

// Runs `compile`; a rill::Error it throws comes back as with_user_lines says.
template <class F>
auto reporting_user_lines(const std::string& shown, const std::function<std::string()>& regenerate,
                          F&& compile) -> decltype(compile()) {
  try {
    return compile();
  } catch (const Error& e) {
    throw Error(with_user_lines(e.what(), shown, regenerate));
  }
}

}  // namespace rill::codegen
