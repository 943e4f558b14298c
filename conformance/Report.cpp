// Markdown and CSV tables of the suite's results.
#include <cstdio>
#include <sstream>

#include "Suite.h"

namespace rill::conformance {

namespace {

std::string number(double v, int digits = 2) {
  if (v < 0) return "-";
  if (std::isinf(v)) return "inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string md_escape(std::string s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  if (out.size() > 400) out = out.substr(0, 400) + "...";
  return out;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"')
      out += "\"\"";
    else if (c == '\n')
      out += ' ';
    else
      out += c;
  }
  return out + "\"";
}

}  // namespace

std::string markdown(const std::vector<Report>& reports, bool only_failures) {
  std::ostringstream o;
  for (const Report& r : reports) {
    o << "### " << r.backend << ", " << r.accuracy << "\n\n";
    if (r.skipped) {
      o << "Skipped: " << r.skip_reason << "\n\n";
      continue;
    }
    o << "Device: " << r.device << "  \n";
    if (r.accuracy == "fast")
      o << "Fast-mode bounds: "
        << (measured_driver(r.backend, r.device)
                ? "measured on this driver"
                : "the contract for drivers not measured here (\"other\" in docs/accuracy.md)")
        << "  \n";
    o << "Denormals: " << r.denormal_probe
      << (r.flushes_denormals ? " (compared with the denormal rule)" : "") << "  \n";
    o << "Result: " << r.count(Status::Pass) << " pass, " << r.count(Status::Fail) << " fail, "
      << r.count(Status::Skip) << " skip, " << r.count(Status::Error) << " error, in "
      << number(r.seconds, 1) << " s\n\n";
    o << "| op | category | elements | mismatches | max ulp | bound | status | note |\n";
    o << "| --- | --- | ---: | ---: | ---: | ---: | --- | --- |\n";
    for (const Row& row : r.rows) {
      if (only_failures && (row.status == Status::Pass || row.status == Status::Skip)) continue;
      o << "| " << md_escape(row.op) << " | " << row.category << " | " << row.elements << " | "
        << row.mismatches << " | " << number(row.max_ulp) << " | " << number(row.bound) << " | "
        << status_name(row.status) << " | " << md_escape(row.note) << " |\n";
    }
    o << "\n";
  }
  return o.str();
}

std::string csv(const std::vector<Report>& reports) {
  std::ostringstream o;
  o << "op,category,backend,accuracy,elements,mismatches,max_ulp,bound,status,note\n";
  for (const Report& r : reports) {
    if (r.skipped) {
      o << "*,*," << r.backend << "," << r.accuracy << ",0,0,,,skip," << csv_field(r.skip_reason)
        << "\n";
      continue;
    }
    for (const Row& row : r.rows) {
      o << csv_field(row.op) << "," << row.category << "," << row.backend << "," << row.accuracy
        << "," << row.elements << "," << row.mismatches << ","
        << (row.max_ulp < 0 ? "" : number(row.max_ulp, 3)) << ","
        << (row.bound < 0 ? "" : number(row.bound, 3)) << "," << status_name(row.status) << ","
        << csv_field(row.note) << "\n";
    }
  }
  return o.str();
}

std::string summary(const std::vector<Report>& reports) {
  std::ostringstream o;
  for (const Report& r : reports) {
    o << r.backend << " " << r.accuracy << ": ";
    if (r.skipped) {
      o << "skipped (" << r.skip_reason << ")\n";
      continue;
    }
    o << r.count(Status::Pass) << " pass, " << r.count(Status::Fail) << " fail, "
      << r.count(Status::Skip) << " skip, " << r.count(Status::Error) << " error ("
      << number(r.seconds, 1) << " s" << (r.flushes_denormals ? ", flushes denormals" : "")
      << ")\n";
    for (const Row& row : r.rows)
      if (row.status == Status::Fail || row.status == Status::Error)
        o << "  " << status_name(row.status) << " " << row.op << ": " << row.mismatches << " of "
          << row.elements << (row.max_ulp >= 0 ? ", max " + number(row.max_ulp) + " ulp" : "")
          << (row.bound >= 0 ? " (bound " + number(row.bound) + ")" : "") << ": "
          << md_escape(row.note) << "\n";
  }
  return o.str();
}

std::string markdown(const std::vector<MathMeasurement>& m) {
  std::ostringstream o;
  o << "| function | domain | samples | max ulp | mean ulp | worst input |\n";
  o << "| --- | --- | ---: | ---: | ---: | --- |\n";
  for (const MathMeasurement& r : m) {
    char worst[96];
    if (r.function == "pow" || r.function == "atan2")
      std::snprintf(worst, sizeof worst, "(%.9g, %.9g)", r.worst_x, r.worst_y);
    else
      std::snprintf(worst, sizeof worst, "%.9g", r.worst_x);
    o << "| " << r.function << " | " << md_escape(r.domain) << " | " << r.samples << " | "
      << number(r.max_ulp, 3) << " | " << number(r.mean_ulp, 3) << " | " << worst << " |\n";
  }
  return o.str();
}

std::string specials_markdown() {
  std::ostringstream o;
  o << "| category | expression | result | modes |\n";
  o << "| --- | --- | --- | --- |\n";
  for (const Special& s : specials()) {
    std::string modes = s.strict_only ? "strict" : s.category == "int" ? "all" : "strict, double";
    o << "| " << s.category << " | `" << md_escape(s.label) << "` | " << md_escape(s.expected_text)
      << " | " << modes << " |\n";
  }
  return o.str();
}

}  // namespace rill::conformance
