// Error reporting for Rill.
//
// Every misuse of the library (an unbalanced control-flow macro, a value used in the wrong
// program, a stream of the wrong size at launch, a kernel a backend cannot compile) throws
// rill::Error. The message names the problem; where C++ can tell us, it also names the place
// in the user's source (file:line) that caused it.
#pragma once

#include <source_location>
#include <stdexcept>
#include <string>

namespace rill {

// A place in the user's source code, captured with std::source_location at the macro or
// function call that recorded an IR statement.
struct SourceLoc {
  const char* file = nullptr;
  unsigned line = 0;

  static SourceLoc from(const std::source_location& l) { return {l.file_name(), l.line()}; }
  bool known() const { return file != nullptr && line != 0; }
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
#define RILL_HERE ::rill::SourceLoc::from(std::source_location::current())
