// Small helpers for showing generated source to people (compile errors, dumps).
#pragma once

#include <cstdio>
#include <sstream>
#include <string>

namespace rill::codegen {

// The text with a line number before every line, as compilers' messages refer to them.
inline std::string numbered(const std::string& source) {
  std::istringstream in(source);
  std::ostringstream out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    char num[16];
    std::snprintf(num, sizeof num, "%5d  ", ++n);
    out << num << line << "\n";
  }
  return out.str();
}

// Text safe inside a /* */ or // comment of generated code (a kernel's name, say).
inline std::string comment_safe(std::string text) {
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n' || text[i] == '\r') text[i] = ' ';
    if (text[i] == '*' && i + 1 < text.size() && text[i + 1] == '/') text[i + 1] = '|';
  }
  return text;
}

}  // namespace rill::codegen
