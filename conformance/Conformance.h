// Rill's backend conformance suite (library rill_conformance, program rill-conformance).
//
// The suite runs every DSL operation and every control-flow construct as kernels on a
// backend, in one accuracy mode, over a few thousand elements per kernel (hard values such
// as signed zeros, denormals, infinities, NaN, FLT_MAX, INT_MIN and shift counts >= 32,
// then seeded random values), and compares the outputs with a reference:
//
//   strict  bit for bit with the exact reference interpreter (rill::ir::interpret) running
//           the same program after passes::optimize(..., Accuracy::Strict); any NaN matches
//           any NaN; a backend that flushes denormals (found by a probe kernel) is compared
//           after flushing (the denormal rule in docs/conformance.md).
//   fast    error in ulps against a double-precision host reference, over each operation's
//           documented domain, checked against the per-operation bound of the backend
//           (fast_bound(), documented in docs/accuracy.md).
//   double  against the double-precision reference rounded once to float.
//
// Control-flow programs (if / else-if, while, do-until, for, break, continue, discard,
// arrays, uniforms, swizzles) use only operations that are exact in every mode, so they
// are compared bit for bit with the interpreter in every mode.
//
//   rill::conformance::Options o;
//   auto report = rill::conformance::run("opencl", rill::Accuracy::Fast, o);
//   std::cout << rill::conformance::markdown({report});
#pragma once

#include <rill/Backend.h>

#include <cstdint>
#include <string>
#include <vector>

namespace rill::conformance {

enum class Status : uint8_t {
  Pass,   // within the mode's contract
  Fail,   // outside it: a finding
  Skip,   // not applicable in this mode / on this backend (the note says why)
  Error,  // the kernel did not compile or run (the note has the message)
};
const char* status_name(Status s);

// One row of a result table: one operation (or control-flow program) on one backend in one
// accuracy mode. An operation's forms (float4, float, vector op scalar, ...) are merged.
struct Row {
  std::string op;        // "add", "sin", "int.div", "control.while", "special: sqrt(-1)"...
  std::string category;  // "float", "transcendental", "int", "bool", "compare", ...
  std::string backend;
  std::string accuracy;
  int64_t elements = 0;    // result components compared
  int64_t mismatches = 0;  // components outside the contract
  // strict: informative error of the strict result against the double reference, over
  // the operation's fast-mode domain; fast: error in ulps against the double reference;
  // double: distance in ulps from the double reference rounded to float. -1: not measured
  // (integer and boolean results, control programs).
  double max_ulp = -1;
  double bound = -1;            // the bound max_ulp is checked against (-1: none, bitwise)
  int64_t nan_bits_differ = 0;  // strict: elements where both sides are NaN but bits differ
  Status status = Status::Pass;
  std::string note;  // the first mismatches, an error message, or why it was skipped
};

// A run of the suite on one backend in one accuracy mode.
struct Report {
  std::string backend;
  std::string accuracy;
  std::string device;    // Backend::description()
  bool skipped = false;  // the backend or mode is not available here
  std::string skip_reason;
  bool flushes_denormals = false;  // found by the probe kernel (then the denormal rule applies)
  std::string denormal_probe;      // what the probe saw, in words
  std::vector<Row> rows;
  double seconds = 0;

  int count(Status s) const;
  bool passed() const { return count(Status::Fail) == 0 && count(Status::Error) == 0; }
};

struct Options {
  uint64_t seed = 20240601;  // seeds every case's random inputs (with the case's name)
  int64_t elements = 4096;   // elements per operation kernel (vectors of 4 components)
  // Only run cases whose name contains one of these substrings (empty: all).
  std::vector<std::string> filter;
  // Only run the cases with exactly these names (empty: all; see case_names()).
  std::vector<std::string> cases;
  // Which parts to run.
  bool operations = true;
  bool control = true;
  bool specials = true;
};

// The names of the cases (operation groups, control programs, "specials"), in run order.
std::vector<std::string> case_names();

// Runs the suite on `backend` in accuracy mode `a`. Never throws for a backend problem: an
// unavailable backend or mode gives a skipped report, a kernel that fails to build gives
// rows with Status::Error.
Report run(const std::string& backend, Accuracy a, const Options& options = {});

// The fast-mode bound (in ulps) for an operation on a backend and device (the backend's
// description()): the drivers the suite was measured on (gcc + glibc, PoCL, Mesa llvmpipe)
// get their measured bounds, any other driver the "other drivers" column of
// docs/accuracy.md. -1: the operation is exact (integer / boolean results, compared for
// equality).
double fast_bound(const std::string& op, const std::string& backend, const std::string& device);
// Whether fast_bound() holds a measurement for this backend and device.
bool measured_driver(const std::string& backend, const std::string& device);
// The double-mode bound (distance in float ulps from the double reference rounded once).
double double_bound(const std::string& op);

// Tables: one section per report, one line per row.
std::string markdown(const std::vector<Report>& reports, bool only_failures = false);
std::string csv(const std::vector<Report>& reports);
// One line per report: "cpu strict: 97 pass, 0 fail, 2 skip, 0 error (12.3 s)".
std::string summary(const std::vector<Report>& reports);

// The measurement behind docs/accuracy.md: the error of Rill's strict routines (exp, exp2,
// log, log2, pow, sin, cos, tan, atan, atan2) against a double-precision reference, over
// stated domains, computed by running the routines as strict kernels on `backend`.
struct MathMeasurement {
  std::string function;
  std::string domain;
  int64_t samples = 0;
  double max_ulp = 0;
  double mean_ulp = 0;
  double worst_x = 0, worst_y = 0;  // an input with the largest error
};
std::vector<MathMeasurement> measure_strict_math(const std::string& backend, uint64_t seed,
                                                 int64_t samples);
std::string markdown(const std::vector<MathMeasurement>& m);

// The hard-input table of docs/conformance.md: every special case, its documented result,
// and whether the reference interpreter agrees. (The suite checks each backend against it.)
std::string specials_markdown();

}  // namespace rill::conformance
