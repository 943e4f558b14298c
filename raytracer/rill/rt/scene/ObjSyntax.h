// Line-by-line checks of OBJ and MTL text, by Rill's reading of the formats, run before
// tinyobjloader parses them. tinyobjloader reads what it can and skips or zero-fills the rest
// without a word ("v abc def" becomes a vertex at the origin, an unknown statement vanishes);
// these checks find such lines so that the loader can name them with file and line: as
// warnings (the first few, then a count), or as errors with --strict-input. Values that would
// render wrongly whatever the mode (a face index 0, a negative colour, a non-finite shininess)
// are errors, also naming the line and the field.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace rt {

struct LineIssue {
  size_t line = 0;     // 1-based
  std::string what;    // "'v' expects numbers ('v abc def')"
  bool value = false;  // a bad value (always an error), not a malformed line
  // What the parser reads instead of the line: nothing, or for a malformed v, vt or vn line a
  // placeholder that keeps the later lines' indices as written (faces that use it are
  // malformed too, so the placeholder is never rendered).
  std::string placeholder;
  // An empty `what`: not an issue, only a line the parser must read as `placeholder` (a
  // position written as nan or inf, rewritten so that it stays non-finite).
  bool rewrite_only() const { return what.empty(); }
};

struct ObjLines {
  std::vector<LineIssue> issues;
  size_t lines = 0, vertices = 0, faces = 0;  // what the text holds, for messages
  // Whether the file has an `s` (smoothing group) line: only then is group 0 (`s off`, or
  // no `s` yet) a flat face.
  bool smoothing_groups = false;
  // Each usemtl's line and name, in file order.
  std::vector<std::pair<size_t, std::string>> usemtl;
};
ObjLines check_obj_lines(const std::string& text);

struct MtlLines {
  std::vector<LineIssue> issues;
};
MtlLines check_mtl_lines(const std::string& text);

// The text with the lines of `issues` (in line order) replaced by their placeholders, and
// every other line without its trailing comment (and the first without a byte order mark),
// line ends kept: what tinyobjloader reads, with the file's line numbers.
std::string without_lines(const std::string& text, const std::vector<LineIssue>& issues);

}  // namespace rt
