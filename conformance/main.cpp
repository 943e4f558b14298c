// rill-conformance: runs the backend conformance suite on this machine's backends.
//
//   rill-conformance [--backend B]... [--accuracy A]... [--markdown FILE] [--csv FILE]
//                    [--seed N] [--elements N] [--filter TEXT]...
//   rill-conformance --measure-strict-math [--samples N] [--backend B]
//   rill-conformance --specials-table
//
// Exits 0 when every check passes (unavailable backends and modes are skipped, with the
// reason), 1 on any failure, 2 on a usage error.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include <rill/Kernel.h>

#include "Conformance.h"

namespace {

const char* kUsage = R"(usage: rill-conformance [options]

Runs Rill's backend conformance suite: every operation and control-flow construct on each
backend, in each accuracy mode, against the reference (see docs/conformance.md).

  --backend B        cpu, simd, opencl, glsl, glsl-compute, vulkan (repeat or comma-separate;
                     default: every backend)
  --accuracy A       strict, fast, double (repeat or comma-separate; default: all three)
  --markdown FILE    write the result tables as Markdown
  --csv FILE         write the result tables as CSV
  --seed N           seed of the random inputs (default 20240601)
  --elements N       elements per operation kernel (default 4096)
  --filter TEXT      only cases whose name contains TEXT (repeatable; see --list)
  --list             list the cases and exit
  --verbose          print every table, not only the summary
  --measure-strict-math
                     measure Rill's strict math routines against double precision
                     (docs/accuracy.md); uses --backend (default cpu) and --samples
  --samples N        samples per function and domain (default 1000000)
  --specials-table   print the documented results of the hard inputs and exit
  --help             this text
)";

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

bool write_file(const std::string& path, const std::string& text) {
  std::ofstream f(path);
  f << text;
  if (!f) {
    std::cerr << "rill-conformance: cannot write " << path << "\n";
    return false;
  }
  return true;
}

int run(int argc, char** argv) {
  std::vector<std::string> backends, accuracies;
  std::string markdown_file, csv_file;
  rill::conformance::Options options;
  bool measure = false, list = false, verbose = false, specials_table = false;
  int64_t samples = 1000000;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      return 0;
    } else if (a == "--backend") {
      for (auto& b : split(value())) backends.push_back(b);
    } else if (a == "--accuracy") {
      for (auto& b : split(value())) accuracies.push_back(b);
    } else if (a == "--markdown") {
      markdown_file = value();
    } else if (a == "--csv") {
      csv_file = value();
    } else if (a == "--seed") {
      options.seed = std::stoull(value());
    } else if (a == "--elements") {
      options.elements = std::stoll(value());
      if (options.elements < 64) throw std::invalid_argument("--elements must be at least 64");
    } else if (a == "--filter") {
      options.filter.push_back(value());
    } else if (a == "--list") {
      list = true;
    } else if (a == "--verbose") {
      verbose = true;
    } else if (a == "--measure-strict-math") {
      measure = true;
    } else if (a == "--samples") {
      samples = std::stoll(value());
      if (samples < 1) throw std::invalid_argument("--samples must be positive");
    } else if (a == "--specials-table") {
      specials_table = true;
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  if (list) {
    for (const auto& n : rill::conformance::case_names()) std::cout << n << "\n";
    return 0;
  }
  if (specials_table) {
    std::cout << rill::conformance::specials_markdown();
    return 0;
  }
  if (measure) {
    std::string b = backends.empty() ? "cpu" : backends[0];
    auto m = rill::conformance::measure_strict_math(b, options.seed, samples);
    std::string md = rill::conformance::markdown(m);
    std::cout << md;
    if (!markdown_file.empty() && !write_file(markdown_file, md)) return 1;
    return 0;
  }
  std::vector<std::string> known;
  for (rill::Backend* b : rill::backends()) known.push_back(b->name());
  if (backends.empty()) backends = known;
  for (const auto& b : backends)
    if (std::find(known.begin(), known.end(), b) == known.end()) {
      std::string list;
      for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
      throw std::invalid_argument("this build has no backend named '" + b + "' (it has " + list +
                                  ")");
    }
  // A filter that matches no case would run nothing and report success.
  if (!options.filter.empty()) {
    bool any = false;
    for (const auto& n : rill::conformance::case_names())
      for (const auto& f : options.filter) any = any || n.find(f) != std::string::npos;
    if (!any) {
      std::string list;
      for (const auto& f : options.filter) list += (list.empty() ? "'" : ", '") + f + "'";
      throw std::invalid_argument("--filter " + list + " matches no case (--list shows them)");
    }
  }
  if (accuracies.empty()) accuracies = {"strict", "fast", "double"};
  std::vector<rill::Accuracy> modes;
  for (const auto& a : accuracies) {
    if (a != "strict" && a != "fast" && a != "double")
      throw std::invalid_argument("unknown accuracy mode '" + a + "' (strict, fast, double)");
    modes.push_back(rill::parse_accuracy(a));
  }

  std::vector<rill::conformance::Report> reports;
  for (const auto& b : backends)
    for (rill::Accuracy m : modes) {
      reports.push_back(rill::conformance::run(b, m, options));
      const auto& r = reports.back();
      if (verbose) std::cout << rill::conformance::markdown({r});
      std::cout << rill::conformance::summary({r}) << std::flush;
    }
  bool ok = true;
  for (const auto& r : reports) ok = ok && r.passed();
  if (!markdown_file.empty())
    ok = write_file(markdown_file, rill::conformance::markdown(reports)) && ok;
  if (!csv_file.empty()) ok = write_file(csv_file, rill::conformance::csv(reports)) && ok;
  std::cout << (ok ? "conformance: all checks passed\n" : "conformance: FAILURES (see above)\n");
  return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  int rc;
  try {
    rc = run(argc, argv);
  } catch (const std::invalid_argument& e) {
    std::cerr << "rill-conformance: " << e.what() << "\n" << kUsage;
    rc = 2;
  } catch (const std::exception& e) {
    std::cerr << "rill-conformance: " << e.what() << "\n";
    rc = 1;
  }
  // Release compiled kernels while every backend is still alive (the GL context in
  // particular), not from static destructors at exit.
  rill::clear_kernel_cache();
  return rc;
}
