// PLY structure checks (PlyCheck.h): the header parsed line by line, then the body walked
// element by element, property by property, as a PLY reader would read it, without keeping
// any value.
#include "rill/rt/scene/PlyCheck.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

struct Property {
  std::string name;
  int size = 0;        // bytes of a scalar (or of a list's items)
  int count_size = 0;  // a list: bytes of its count; 0 for a scalar
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

// The size in bytes of a PLY scalar type, or 0 for an unknown name.
int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

bool blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

bool has_prop(const Element& e, const char* name) {
  for (const Property& p : e.props)
    if (p.name == name) return true;
  return false;
}

// Where the walk is, for messages: "element 'face' number 3 (of 12 declared)".
std::string at(const Element& e, uint64_t i) {
  return "element '" + clipped(e.name) + "' number " + std::to_string(i) + " (of " +
         std::to_string(e.count) + " declared, counting from 0)";
}

}  // namespace

PlyLayout check_ply(const std::string& bytes, const std::string& path) {
  auto fail = [&](const std::string& what) { throw SceneError(path + ": " + what); };
  // The header: lines up to "end_header", ended by \n (or \r\n).
  size_t pos = 0;
  int line_no = 0;
  auto next_line = [&](std::string& line) {
    if (pos >= bytes.size()) return false;
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    line = bytes.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    ++line_no;
    return true;
  };
  std::string line;
  if (!next_line(line) || line != "ply") fail("not a PLY file (its first line is not \"ply\")");
  PlyLayout layout;
  bool big_endian = false, have_format = false, ended = false;
  std::vector<Element> elements;
  while (!ended && next_line(line)) {
    std::istringstream words(line);
    std::string word;
    words >> word;
    auto bad = [&](const std::string& what) {
      fail("line " + std::to_string(line_no) + " of the header: " + what);
    };
    if (word.empty() || word == "comment" || word == "obj_info") continue;
    if (word == "end_header") {
      ended = true;
    } else if (word == "format") {
      std::string kind, version;
      words >> kind >> version;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
        bad("format '" + clipped(kind) +
            "' is not ascii, binary_little_endian or binary_big_endian");
      if (version != "1.0") bad("format version '" + clipped(version) + "' is not 1.0");
      layout.binary = kind != "ascii";
      big_endian = kind == "binary_big_endian";
      have_format = true;
    } else if (word == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      e.count = std::strtoull(count.c_str(), &end, 10);
      if (e.name.empty() || count.empty() || end != count.c_str() + count.size() || count[0] == '-')
        bad("an element needs a name and a count (\"element vertex 8\")");
      elements.push_back(e);
    } else if (word == "property") {
      if (elements.empty()) bad("a property before any element");
      Property p;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type >> p.name;
        p.count_size = type_size(count_type);
        p.size = type_size(item_type);
        if (p.count_size == 0 || p.size == 0 || count_type == "float" || count_type == "double")
          bad("list property types '" + clipped(count_type) + " " + clipped(item_type) +
              "': the count must be an integer type, the items a PLY type");
      } else {
        words >> p.name;
        p.size = type_size(type);
        if (p.size == 0) bad("unknown property type '" + clipped(type) + "'");
      }
      if (p.name.empty()) bad("a property without a name");
      elements.back().props.push_back(p);
    } else {
      bad("unknown header keyword '" + clipped(word) + "'");
    }
  }
  if (!ended) fail("the header has no end_header line: truncated, or not a PLY file");
  if (!have_format) fail("the header has no format line");

  const Element* vertex = nullptr;
  for (const Element& e : elements) {
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") {
      bool list = false;
      for (const Property& p : e.props)
        list = list || ((p.name == "vertex_indices" || p.name == "vertex_index") && p.count_size);
      if (!list) fail("the face element has no vertex_indices list");
      layout.faces = e.count;
    }
  }
  if (vertex == nullptr || !has_prop(*vertex, "x") || !has_prop(*vertex, "y") ||
      !has_prop(*vertex, "z"))
    fail("no vertex element with x, y and z properties");
  layout.vertices = vertex->count;
  layout.normals = has_prop(*vertex, "nx") && has_prop(*vertex, "ny") && has_prop(*vertex, "nz");
  layout.colors = has_prop(*vertex, "red") || has_prop(*vertex, "r");

  // The body. Counts come from the file, so the walk never trusts them beyond its bytes:
  // each value consumes at least one byte, so a count larger than what is left fails at once.
  const uint64_t body = bytes.size() - std::min(pos, bytes.size());
  for (const Element& e : elements)
    if (e.count > body)
      fail("the header declares " + std::to_string(e.count) + " of element '" + clipped(e.name) +
           "' but only " + std::to_string(body) + " bytes follow it: truncated, or a wrong count");
  auto truncated = [&](const Element& e, uint64_t i) {
    fail("the file ends in " + at(e, i) + ": truncated, or the header's counts are wrong");
  };
  if (layout.binary) {
    auto read_count = [&](int size, uint64_t& value) {
      if (pos + static_cast<size_t>(size) > bytes.size()) return false;
      unsigned char b[4] = {0, 0, 0, 0};
      std::memcpy(b, bytes.data() + pos, static_cast<size_t>(size));
      pos += static_cast<size_t>(size);
      uint32_t v = 0;
      for (int k = 0; k < size; ++k) v |= uint32_t{b[big_endian ? size - 1 - k : k]} << (8 * k);
      // A negative count of a signed type reads as a large number, and fails as one.
      value = v;
      return true;
    };
    for (const Element& e : elements)
      for (uint64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          uint64_t n = 1;
          if (p.count_size && !read_count(p.count_size, n)) truncated(e, i);
          if (n > (bytes.size() - pos) / static_cast<uint64_t>(p.size)) truncated(e, i);
          pos += static_cast<size_t>(n) * static_cast<size_t>(p.size);
        }
  } else {
    // ASCII: values separated by blanks (space, tab, line ends: what assimp's reader takes
    // too, so that both split a line the same way); each a number.
    auto token = [&](std::string& t) {
      while (pos < bytes.size() && blank(bytes[pos])) ++pos;
      const size_t start = pos;
      while (pos < bytes.size() && !blank(bytes[pos])) ++pos;
      t.assign(bytes, start, pos - start);
      return !t.empty();
    };
    std::string t;
    auto number = [&](const Element& e, uint64_t i, const Property& p) {
      if (!token(t)) truncated(e, i);
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      // The whole token, not up to a NUL byte inside it ("1\0" or a lone "\0" is no number).
      if (end != t.c_str() + t.size())
        fail(at(e, i) + ", property '" + clipped(p.name) + "': '" + clipped(t) +
             "' is not a number");
      return v;
    };
    for (const Element& e : elements)
      for (uint64_t i = 0; i < e.count; ++i)
        for (const Property& p : e.props) {
          if (p.count_size == 0) {
            number(e, i, p);
            continue;
          }
          const double n = number(e, i, p);
          // The range check comes first: converting a double beyond uint64_t's range (a
          // count like 1e30) is undefined behaviour.
          if (!(n >= 0) || n > static_cast<double>(bytes.size()) ||
              n != static_cast<double>(static_cast<uint64_t>(n)))
            fail(at(e, i) + ", property '" + clipped(p.name) + "': list count '" + clipped(t) +
                 "' is not a count");
          for (uint64_t k = 0; k < static_cast<uint64_t>(n); ++k) number(e, i, p);
        }
  }
  // What follows the last element: blanks only (a writer's final newline).
  for (; pos < bytes.size(); ++pos)
    if (!blank(bytes[pos]))
      fail("data after the last element (at byte " + std::to_string(pos) +
           "): the header's counts are wrong");
  return layout;
}

}  // namespace rt
