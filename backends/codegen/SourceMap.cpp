// Source maps (SourceMap.h): numbering the generated text and reading drivers' messages
// against the user's lines.
#include "SourceMap.h"

#include <cctype>
#include <cstring>
#include <sstream>

namespace rill::codegen {

namespace {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

bool starts_with(const std::string& s, const char* prefix) {
  return s.compare(0, std::strlen(prefix), prefix) == 0;
}

// A line of the source map: sets `user` to the "file:line" it names ("" for the generated
// text) and returns true; false for any other line.
bool map_line(const std::string& line, std::string& user) {
  std::string s = line.substr(
      line.find_first_not_of(' ') == std::string::npos ? line.size() : line.find_first_not_of(' '));
  if (starts_with(s, kSourceComment)) {
    user = s.substr(std::strlen(kSourceComment));
    return true;
  }
  if (starts_with(s, kSourceLineRestore)) {
    user.clear();
    return true;
  }
  // #line N "file"
  if (!starts_with(s, "#line ")) return false;
  size_t num = 6, q = s.find('"', num);
  if (q == std::string::npos || s.size() < q + 2 || s.back() != '"') return false;
  std::string n = s.substr(num, q - num);
  while (!n.empty() && n.back() == ' ') n.pop_back();
  std::string file;
  for (size_t i = q + 1; i + 1 < s.size(); ++i) {
    if (s[i] == '\\' && i + 2 < s.size()) ++i;
    file += s[i];
  }
  user = file == kGeneratedFile ? std::string() : file + ":" + n;
  return true;
}

// The generated line number a driver's message line names, or 0: "F:L:C: " (gcc, clang,
// PoCL) or "N:L(C): " (Mesa).
int generated_line(const std::string& m) {
  for (size_t i = 0; i < m.size(); ++i) {
    if (m[i] != ':' || i + 1 >= m.size() || !std::isdigit(static_cast<unsigned char>(m[i + 1])))
      continue;
    size_t j = i + 1;
    int n = 0;
    while (j < m.size() && std::isdigit(static_cast<unsigned char>(m[j])) && n < 10000000)
      n = n * 10 + (m[j++] - '0');
    if (j < m.size() && (m[j] == ':' || m[j] == '(') && j + 1 < m.size() &&
        std::isdigit(static_cast<unsigned char>(m[j + 1])))
      return n;
  }
  return 0;
}

}  // namespace

std::string quoted_file(const SourceLoc& loc) {
  std::string out;
  for (char c : relative_path(loc.file)) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n' || c == '\r') c = ' ';
    out += c;
  }
  return out;
}

std::string finish_source_lines(const std::string& source) {
  std::string out;
  out.reserve(source.size());
  size_t start = 0;
  int line = 0;
  while (start < source.size()) {
    size_t nl = source.find('\n', start);
    if (nl == std::string::npos) nl = source.size() - 1;
    ++line;
    std::string text = source.substr(start, nl - start + 1);
    const size_t lead = text.find_first_not_of(' ');
    if (lead != std::string::npos &&
        text.compare(lead, std::strlen(kSourceLineRestore), kSourceLineRestore) == 0)
      text = text.substr(0, lead) + "#line " + std::to_string(line + 1) + " \"" + kGeneratedFile +
             "\"\n";
    out += text;
    start = nl + 1;
  }
  return out;
}

std::vector<std::string> user_lines(const std::string& shown, const std::string& mapped) {
  const std::vector<std::string> shown_lines = split_lines(shown);
  const std::vector<std::string> mapped_lines = split_lines(mapped);
  std::vector<std::string> out;
  std::string user;
  if (shown == mapped) {  // the driver saw the map: each line, its own included, as is
    for (const std::string& l : mapped_lines) {
      // After a #line the driver numbers lines as the user's file: nothing to read back.
      if (l.find_first_not_of(' ') != std::string::npos &&
          starts_with(l.substr(l.find_first_not_of(' ')), "#line "))
        return {};
      map_line(l, user);
      out.push_back(user);
    }
    return out;
  }
  for (const std::string& l : mapped_lines) {
    if (map_line(l, user)) continue;
    if (out.size() >= shown_lines.size() || shown_lines[out.size()] != l) return {};
    out.push_back(user);
  }
  if (out.size() != shown_lines.size()) return {};
  return out;
}

std::string with_user_lines(const std::string& what, const std::string& shown,
                            const std::function<std::string()>& regenerate) {
  std::vector<std::string> table;
  try {
    table = user_lines(shown, regenerate());
  } catch (const Error&) {
    return what;
  }
  if (table.empty()) return what;
  std::istringstream in(what);
  std::string line, out, first;
  int first_generated = 0;
  bool in_listing = false;  // the numbered source that ends the messages names no lines
  while (std::getline(in, line)) {
    if (line == "generated source:") in_listing = true;
    const int g = in_listing ? 0 : generated_line(line);
    out += line;
    if (g >= 1 && static_cast<size_t>(g) <= table.size() &&
        !table[static_cast<size_t>(g - 1)].empty()) {
      const std::string& user = table[static_cast<size_t>(g - 1)];
      out += "  [from " + user + "]";
      if (first.empty()) {
        first = user;
        first_generated = g;
      }
    }
    out += "\n";
  }
  if (first.empty()) return what;
  return first + " (generated line " + std::to_string(first_generated) + "): " + out;
}

}  // namespace rill::codegen
