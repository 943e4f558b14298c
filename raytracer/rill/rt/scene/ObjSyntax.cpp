// OBJ and MTL line checks (ObjSyntax.h).
#include "rill/rt/scene/ObjSyntax.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <map>

#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// Splits text into lines the way tinyobjloader does (\n, \r\n or a lone \r) and each line into
// blank-separated words; calls f(line number, words, the line).
void for_each_line(
    const std::string& text,
    const std::function<void(size_t, const std::vector<std::string>&, const std::string&)>& f) {
  size_t pos = 0, line = 0;
  std::vector<std::string> words;
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    ++line;
    const std::string s = text.substr(pos, end - pos);
    words.clear();
    // A UTF-8 byte order mark before the first line is not part of it.
    const size_t from = line == 1 && s.compare(0, 3, "\xef\xbb\xbf") == 0 ? 3 : 0;
    for (size_t i = from; i < s.size();) {
      while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
      const size_t start = i;
      while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
      if (i == start) continue;
      if (s[start] == '#') break;  // a comment ends the line's words ("v 1 2 3 # tip")
      words.push_back(s.substr(start, i - start));
    }
    if (!words.empty()) f(line, words, s);
    pos = end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1);
  }
}

bool is_number(const std::string& w, double& v) {
  if (w.empty()) return false;
  errno = 0;
  char* end = nullptr;
  v = std::strtod(w.c_str(), &end);
  return end == w.c_str() + w.size();  // inf and nan are numbers (non-finite: handled later)
}

bool is_int(const std::string& w, long long& v) {
  if (w.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtoll(w.c_str(), &end, 10);
  return end == w.c_str() + w.size() && errno == 0;
}

// Whether words[1..] are numbers, and how many; the line quoted for messages.
bool all_numbers(const std::vector<std::string>& words, std::vector<double>& out) {
  out.clear();
  for (size_t i = 1; i < words.size(); ++i) {
    double v;
    if (!is_number(words[i], v)) return false;
    out.push_back(v);
  }
  return true;
}

// The rest of the line from word 1 on, without trailing blanks (a material's name may hold
// spaces).
std::string rest(const std::string& line, const std::vector<std::string>& w) {
  std::string r = line.substr(line.find(w[1], line.find(w[0]) + w[0].size()));
  while (!r.empty() && (r.back() == ' ' || r.back() == '\t')) r.pop_back();
  return r;
}

std::string quoted(const std::string& line) {
  return "'" + clipped(line, 60) + "'";
}

// Finite once read as a float (1e39 is a finite double but an infinite float).
bool finite_float(double v) {
  return std::fabs(v) <= 3.4028234663852886e38;
}

bool one_of(const std::string& w, std::initializer_list<const char*> list) {
  for (const char* s : list)
    if (w == s) return true;
  return false;
}

}  // namespace

ObjLines check_obj_lines(const std::string& text) {
  ObjLines r;
  std::vector<double> nums;
  // v, vt and vn lines so far (placeholders of malformed ones included: they keep their
  // index), and the line of each malformed one by its 1-based index.
  long long count[3] = {0, 0, 0};
  std::map<long long, size_t> bad[3];
  const char* kinds[3] = {"v", "vt", "vn"};
  const char* placeholders[3] = {"v 0 0 0", "vt 0 0", "vn 0 0 1"};
  bool colours = false;  // some v line has a colour
  for_each_line(text, [&](size_t line, const std::vector<std::string>& w, const std::string& s) {
    r.lines = line;
    auto malformed = [&](const std::string& what) {
      r.issues.push_back({line, what + " (" + quoted(s) + ")", false, ""});
    };
    const std::string& key = w[0];
    const size_t n = w.size() - 1;
    if (key == "v" || key == "vt" || key == "vn") {
      const int k = key == "v" ? 0 : key == "vt" ? 1 : 2;
      const long long index = ++count[k];
      auto bad_line = [&](const std::string& what) {
        bad[k][index] = line;
        r.issues.push_back({line, what + " (" + quoted(s) + ")", false, placeholders[k]});
      };
      if (!all_numbers(w, nums)) return bad_line("'" + key + "' expects numbers");
      if (k == 0 && n != 3 && n != 4 && n != 6 && n != 7)
        return bad_line("'v' expects x y z, x y z w or x y z r g b (got " + std::to_string(n) +
                        " numbers)");
      if (k == 1 && (n < 1 || n > 3))
        return bad_line("'vt' expects 1 to 3 numbers (got " + std::to_string(n) + ")");
      if (k == 2 && n != 3)
        return bad_line("'vn' expects 3 numbers (got " + std::to_string(n) + ")");
      if (k == 0) ++r.vertices;
      if (k == 0 && n >= 6) colours = true;
      // Values that would render wrongly are errors naming the line: texture coordinates and
      // normals must be finite floats, vertex colours finite and >= 0.
      auto bad_value = [&](const std::string& what) {
        r.issues.push_back({line, "'" + key + "' " + what + " (" + quoted(s) + ")", true, ""});
      };
      if (k == 1 || k == 2) {
        for (double v : nums)
          if (!finite_float(v))
            return bad_value(k == 1 ? "texture coordinates must be finite numbers"
                                    : "normals must be finite numbers");
      } else if (n >= 6) {
        for (size_t c = 3; c < 6; ++c)
          if (!finite_float(nums[c]) || nums[c] < 0)
            return bad_value("vertex colours must be finite numbers >= 0");
      }
      // A position written as nan or inf: tinyobjloader would read it as 0, a vertex that
      // renders. Rewritten as a number too large for a float, it reaches the loader as the
      // non-finite vertex it is (never hit, counted in the scene's note), like 1e39 does.
      if (k == 0) {
        std::string fixed = "v";
        bool rewritten = false;
        for (size_t i = 1; i < w.size(); ++i) {
          const bool position = i <= 3;
          const bool nonfinite = !std::isfinite(nums[i - 1]);
          fixed += " ";
          fixed += position && nonfinite ? (nums[i - 1] < 0 ? "-1e999" : "1e999") : w[i];
          rewritten = rewritten || (position && nonfinite);
        }
        if (rewritten) r.issues.push_back({line, "", false, fixed});
      }
    } else if (key == "f") {
      if (n < 3)
        return malformed("a face needs at least 3 vertices (got " + std::to_string(n) + ")");
      for (size_t i = 1; i < w.size(); ++i) {
        // v, v/t, v//n or v/t/n, each a non-zero integer (negative counts back).
        const std::string& ref = w[i];
        const size_t a = ref.find('/');
        const size_t b = a == std::string::npos ? std::string::npos : ref.find('/', a + 1);
        if (b != std::string::npos && ref.find('/', b + 1) != std::string::npos)
          return malformed("face vertex '" + clipped(ref, 30) + "' has more than 3 indices");
        std::vector<std::string> parts;
        parts.push_back(ref.substr(0, a));
        if (a != std::string::npos)
          parts.push_back(ref.substr(a + 1, b == std::string::npos ? b : b - a - 1));
        if (b != std::string::npos) parts.push_back(ref.substr(b + 1));
        for (size_t k = 0; k < parts.size(); ++k) {
          if (parts[k].empty() && k == 1 && parts.size() == 3) continue;  // v//n
          long long v;
          if (!is_int(parts[k], v))
            return malformed("face vertex '" + clipped(ref, 30) +
                             "' is not v, v/t, v//n or v/t/n with integer indices");
          if (v == 0) {
            r.issues.push_back({line,
                                "face vertex '" + clipped(ref, 30) +
                                    "' has index 0 (OBJ indices start at 1; negative ones count "
                                    "back from the last) (" +
                                    quoted(s) + ")",
                                true, ""});
            return;
          }
          // tinyobjloader keeps indices in 32 bits: a larger one would wrap and be reported
          // as some other, wrong number.
          if (v > 2147483647LL || v < -2147483647LL) {
            r.issues.push_back({line,
                                "face vertex '" + clipped(ref, 30) + "' has an index out of " +
                                    "range (the file has " + std::to_string(count[k]) + " " +
                                    kinds[k] + " lines before it) (" + quoted(s) + ")",
                                true, ""});
            return;
          }
          // A face that uses a malformed v, vt or vn line is skipped with it.
          const long long index = v > 0 ? v : count[k] + 1 + v;
          if (auto it = bad[k].find(index); it != bad[k].end())
            return malformed("face vertex '" + clipped(ref, 30) + "' uses the " + kinds[k] +
                             " of malformed line " + std::to_string(it->second));
        }
      }
      ++r.faces;  // well formed
    } else if (key == "usemtl" || key == "mtllib") {
      if (n == 0) return malformed("'" + key + "' expects a name");
      // tinyobjloader looks up usemtl's first word (newmtl keeps the rest of the line).
      if (key == "usemtl") r.usemtl.emplace_back(line, w[1]);
    } else if (one_of(key, {"o",     "g",        "s",        "l",          "p",         "vp",
                            "mg",    "cstype",   "deg",      "bmat",       "step",      "curv",
                            "curv2", "surf",     "parm",     "trim",       "hole",      "scrv",
                            "sp",    "end",      "con",      "lod",        "usemap",    "maplib",
                            "bevel", "c_interp", "d_interp", "shadow_obj", "trace_obj", "ctech",
                            "stech", "call",     "csh",      "t",          "vw"})) {
      // Names, smoothing groups (noted for the vertex normals), lines and points, and the
      // free-form statements: valid OBJ that a triangle renderer leaves out.
      if (key == "s") r.smoothing_groups = true;
    } else {
      malformed("unknown statement '" + clipped(key, 20) + "'");
    }
  });
  // A placeholder without a colour in a file with vertex colours would make tinyobjloader drop
  // every vertex's colour.
  if (colours)
    for (LineIssue& i : r.issues)
      if (i.placeholder == placeholders[0]) i.placeholder = "v 0 0 0 1 1 1";
  return r;
}

MtlLines check_mtl_lines(const std::string& text) {
  MtlLines r;
  std::string current;  // the material being defined
  std::vector<double> nums;
  for_each_line(text, [&](size_t line, const std::vector<std::string>& w, const std::string& s) {
    auto malformed = [&](const std::string& what) {
      r.issues.push_back({line, what + " (" + quoted(s) + ")", false, ""});
    };
    const std::string& key = w[0];
    const size_t n = w.size() - 1;
    auto field = [&] {
      return "'" + key + "'" + (current.empty() ? "" : " of material '" + clipped(current) + "'");
    };
    auto bad_value = [&](const std::string& what) {
      r.issues.push_back({line, field() + " " + what + " (" + quoted(s) + ")", true, ""});
    };
    if (key == "newmtl") {
      if (n == 0) return malformed("'newmtl' expects a name");
      current = rest(s, w);
    } else if (one_of(key, {"Kd", "Ks", "Ka", "Ke", "Tf", "Kt"})) {
      // A colour: r [g b], or the "spectral"/"xyz" forms, which Rill does not read.
      if (n >= 1 && (w[1] == "spectral" || w[1] == "xyz"))
        return malformed("'" + key + " " + w[1] + "' is not supported (only r g b)");
      if (!all_numbers(w, nums) || (n != 1 && n != 3))
        return malformed("'" + key + "' expects 1 or 3 numbers");
      for (double v : nums)
        if (!finite_float(v)) return bad_value("must be finite numbers");
      // Rill renders Kd, Ks and Ke; a negative one would give negative radiance.
      if (key == "Kd" || key == "Ks" || key == "Ke")
        for (double v : nums)
          if (v < 0) return bad_value("is negative; colours must be >= 0");
    } else if (one_of(key, {"Ns", "Ni", "d", "Tr", "illum", "sharpness", "Pr", "Pm", "Ps", "Pc",
                            "Pcr", "aniso", "anisor"})) {
      if (!all_numbers(w, nums) || n != 1) return malformed("'" + key + "' expects one number");
      if (!finite_float(nums[0])) return bad_value("must be a finite number");
      if (key == "Ns" && nums[0] < 0) return bad_value("is negative; shininess must be >= 0");
      if ((key == "d" || key == "Tr") && (nums[0] < 0 || nums[0] > 1))
        return bad_value("must be in 0..1");
      if (key == "illum" && (nums[0] != std::floor(nums[0]) || nums[0] < 0 || nums[0] > 10))
        return bad_value("must be an integer in 0..10");
    } else if (key.rfind("map_", 0) == 0 ||
               one_of(key, {"bump", "disp", "decal", "refl", "norm"})) {
      if (n == 0) return malformed("'" + key + "' expects a file name");
    } else {
      malformed("unknown statement '" + clipped(key, 20) + "'");
    }
  });
  return r;
}

std::string without_lines(const std::string& text, const std::vector<LineIssue>& issues) {
  std::string out;
  out.reserve(text.size());
  size_t pos = 0, line = 0, next = 0;
  while (pos < text.size()) {
    size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string::npos) end = text.size();
    ++line;
    const size_t after = std::min(text.size(), end + (text.compare(end, 2, "\r\n") == 0 ? 2 : 1));
    while (next < issues.size() && issues[next].line < line) ++next;
    if (next < issues.size() && issues[next].line == line) {
      out.append(issues[next].placeholder);
    } else {
      // Without a byte order mark and a trailing comment, which tinyobjloader reads as part
      // of the line ("f 1 2 3 # x" fails on '#').
      size_t from = pos;
      if (line == 1 && text.compare(0, 3, "\xef\xbb\xbf") == 0) from += 3;
      size_t cut = end;
      for (size_t k = from; k < end; ++k)
        if (text[k] == '#' && (k == from || text[k - 1] == ' ' || text[k - 1] == '\t')) {
          cut = k;
          break;
        }
      out.append(text, from, cut - from);
    }
    out.append(text, end, after - end);
    pos = after;
  }
  return out;
}

}  // namespace rt
