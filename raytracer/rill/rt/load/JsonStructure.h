// A scene file's JSON structure, checked in one pass that builds nothing, before the document
// is parsed: its syntax, a key given twice in one object (JSON parsers keep the last, so a
// repeated "builtin" silently replaced the first) and objects and arrays nested deeper than a
// limit (a small hostile file of brackets would otherwise become a document of millions of
// levels). The pass holds one entry per open object or array, at most the limit's, and is
// linear in the text: the parser's callback that did this before rescanned each object's
// members at every member's end, seconds for an object of 20,000 members.
#pragma once

#include <string>

namespace rt {

// "" when the text is one JSON value with no key twice in an object and at most max_depth
// levels of objects and arrays (the outermost is level 1); otherwise the first problem, as a
// message to follow the file's name: "invalid JSON: parse error at line 1, column 9: ...",
// "key 'reflect' appears twice in materials.m", "meshes: JSON nested deeper than 256 levels
// (objects and arrays), the most a scene file may nest". Paths name the outermost object "scene",
// then keys with dots and array elements with "[]".
std::string json_structure_problem(const std::string& text, int max_depth);

}  // namespace rt
