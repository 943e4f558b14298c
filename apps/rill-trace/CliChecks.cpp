#include "CliChecks.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

// A number option's check. CLI::Range says "Value x not in range 0 to 64" for a word, as if x
// were a number: this says that it is not one, and else whether it is out of range.
CLI::Validator number_in(double lo, double hi, bool integer) {
  auto text = [](double v) {
    std::ostringstream s;
    if (v == static_cast<double>(static_cast<long long>(v)))
      s << static_cast<long long>(v);  // 1048576, not 1.04858e+06
    else
      s << v;
    return s.str();
  };
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        if (s.empty()) return "an empty value";  // as every option's (refuse_empty_values)
        char* end = nullptr;
        errno = 0;
        const double v = integer ? static_cast<double>(std::strtoll(s.c_str(), &end, 10))
                                 : std::strtod(s.c_str(), &end);
        if (s.empty() || end == s.c_str() || *end != '\0' || errno == ERANGE || v != v)
          return "'" + rt::clipped(s) + "' is not " + (integer ? "an integer" : "a number");
        if (v < lo || v > hi) return s + " is out of range (" + text(lo) + " to " + text(hi) + ")";
        return {};
      },
      std::string(integer ? "INT" : "NUMBER") + " in [" + text(lo) + " - " + text(hi) + "]");
}

// A file option's check: an empty name would otherwise read as the option not given.
CLI::Validator file_name() {
  return CLI::Validator(
      [](std::string& s) -> std::string { return s.empty() ? "an empty file name" : ""; }, "FILE");
}

// A setting's check where an empty value would otherwise read as the option not given.
CLI::Validator non_empty() {
  return CLI::Validator(
      [](std::string& s) -> std::string { return s.empty() ? "an empty value" : ""; }, "");
}

void refuse_empty_values(CLI::App& app) {
  for (CLI::Option* opt : app.get_options())
    if (opt->get_type_size_max() > 0) opt->check(non_empty());
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    refuse_empty_values(*sub);
}

void parse_size(const std::string& s, int& w, int& h) {
  char x = 0;
  long a = 0, b = 0;
  char tail[2];
  if (std::sscanf(s.c_str(), "%ld%c%ld%1s", &a, &x, &b, tail) != 3 || (x != 'x' && x != 'X'))
    throw rt::SceneError("--size expects WxH, e.g. 512x512 (got '" + s + "')");
  if (a < 1 || b < 1 || a > 16384 || b > 16384 || a * b > (1l << 25))
    throw rt::SceneError("--size " + s +
                         " is out of range (1..16384 per side, at most 33554432 pixels)");
  w = static_cast<int>(a);
  h = static_cast<int>(b);
}

std::string checked_size(const std::string& s) {
  int w = 0, h = 0;
  parse_size(s, w, h);
  return s;
}

int parse_grid(const std::string& s) {
  return rt::parse_grid_resolution(s, "--grid");
}

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) v.push_back(item);
  return v;
}

}  // namespace trace_cli
