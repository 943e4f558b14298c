// SourceLoc's text: project-relative file names and the "near" and "called from" parts.
#include "rill/Error.h"

#include <unistd.h>

#include <cstring>
#include <string_view>

namespace rill {

namespace {

// The root of Rill's source tree as this file was compiled: __FILE__ less
// "dsl/src/Error.cpp" ("" when the build passed the path in a form that does not end so).
std::string_view source_root() {
  constexpr std::string_view self = __FILE__, tail = "dsl/src/Error.cpp";
  if (self.size() < tail.size() || self.substr(self.size() - tail.size()) != tail) return {};
  return self.substr(0, self.size() - tail.size());
}

bool strip_prefix(std::string_view& s, std::string_view prefix) {
  if (prefix.empty() || s.substr(0, prefix.size()) != prefix) return false;
  s.remove_prefix(prefix.size());
  return true;
}

}  // namespace

std::string relative_path(const char* file) {
  if (!file) return {};
  std::string_view s = file;
  if (!strip_prefix(s, source_root()) && !s.empty() && s[0] == '/') {
    char cwd[4096];
    if (getcwd(cwd, sizeof cwd)) {
      std::string dir = std::string(cwd) + "/";
      strip_prefix(s, dir);
    }
  }
  while (strip_prefix(s, "./") || strip_prefix(s, "../")) {
  }
  return std::string(s);
}

std::string SourceLoc::str() const {
  if (!known()) return {};
  return relative_path(file) + ":" + std::to_string(line);
}

std::string SourceLoc::describe() const {
  if (!known()) return {};
  std::string s = (nearest ? "near " : "") + str();
  for (const SourceLoc* c = caller; c && c->known(); c = c->caller)
    s += ", called from " + c->str();
  return s;
}

bool SourceLoc::same_place(const SourceLoc& o) const {
  if (line != o.line || caller != o.caller) return false;
  if (file == o.file) return true;
  return file && o.file && std::strcmp(file, o.file) == 0;
}

std::string Error::text(const std::string& what, SourceLoc where) {
  if (!where.known()) return what;
  std::string s = where.describe() + ": " + what;
  if (where.nearest)
    s += " (the line is that of the nearest statement with a location: operators such as = "
         "and + cannot record one)";
  return s;
}

}  // namespace rill
