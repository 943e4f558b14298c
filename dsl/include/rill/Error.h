// Error reporting for Rill.
//
// Every misuse of the library (an unbalanced control-flow macro, a value used in the wrong
// program, a stream of the wrong size at launch, a kernel a backend cannot compile) throws
// rill::Error. The message names the problem; where C++ can tell us, it also names the place
// in the user's source (file:line) that caused it.
#pragma once

#include <version>
#if defined(__cpp_lib_source_location)
#include <source_location>
#endif
#include <stdexcept>
#include <string>

namespace rill {

// A place in the user's source code, captured with std::source_location at the macro or
// function call that recorded an IR statement.
//
// Statements keep their SourceLoc beside the IR (ir::Stmt::loc): it is not part of the
// printed form that the kernel caches hash, nor of any comparison, so where a statement was
// written never changes which kernel it is or the code generated for it.
struct SourceLoc {
  const char* file = nullptr;
  unsigned line = 0;
  // C++ operators (=, +, ...) cannot take a location argument: a statement one of them
  // records gets the nearest located statement recorded before it, marked here, and
  // messages then say "near file:line".
  bool nearest = false;
  // Inside a function the user marked with rill::CallSite (Capture.h): where that function
  // was called from, and so on outwards; null at the program body's own level. Interned:
  // the chain lives as long as the process.
  const SourceLoc* caller = nullptr;

#if defined(__cpp_lib_source_location)
  static SourceLoc from(const std::source_location& l) {
    return {l.file_name(), l.line()};
  }
#else
  // clang 14 with libstdc++ 12 (Debian 12's pair) has no std::source_location. clang's
  // __builtin_FILE/__builtin_LINE, as default arguments of a function that is itself called
  // in a default argument, give the outermost call site, as std::source_location does.
  static SourceLoc current(const char* file = __builtin_FILE(), unsigned line = __builtin_LINE()) {
    return {file, line};
  }
#endif
  bool known() const {
    return file != nullptr && line != 0;
  }
  // "dir/file.cpp:42", the file relative to the project where that can be told (see
  // relative_path), or "" when unknown.
  std::string str() const;
  // What messages print: str(), "near " before it for a nearest location, and the chain of
  // calls: "a.cpp:12, called from b.cpp:40, called from b.cpp:71". "" when unknown.
  std::string describe() const;
  // Same place and chain (the nearest flag aside).
  bool same_place(const SourceLoc& o) const;
};

// The file name messages show: the path relative to Rill's source tree for files inside it,
// else relative to the working directory for files under it, with leading "./" and "../"
// (left by build tools that pass relative paths, such as ccache's base_dir) removed.
std::string relative_path(const char* file);

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  // "file:line: what"; a nearest location (SourceLoc::nearest) says so after the message.
  Error(const std::string& what, SourceLoc where)
      : std::runtime_error(text(what, where)), where_(where) {}

  SourceLoc where() const { return where_; }

 private:
  static std::string text(const std::string& what, SourceLoc where);
  SourceLoc where_;
};

}  // namespace rill

// The caller's source location; used as a default argument so errors point at user code.
#if defined(__cpp_lib_source_location)
#define RILL_HERE ::rill::SourceLoc::from(std::source_location::current())
#else
#define RILL_HERE ::rill::SourceLoc::current()
#endif
