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
struct SourceLoc {
  const char* file = nullptr;
  unsigned line = 0;

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
  // "file.cpp:42", or "" when unknown.
  std::string str() const;
};

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
  Error(const std::string& what, SourceLoc where)
      : std::runtime_error(where.known() ? where.str() + ": " + what : what), where_(where) {}

  SourceLoc where() const { return where_; }

 private:
  SourceLoc where_;
};

}  // namespace rill

// The caller's source location; used as a default argument so errors point at user code.
#if defined(__cpp_lib_source_location)
#define RILL_HERE ::rill::SourceLoc::from(std::source_location::current())
#else
#define RILL_HERE ::rill::SourceLoc::current()
#endif
