// The debug mode's report after a launch: reads the hidden outputs InstrumentDebug.cpp added
// and, when an element read outside an array or made a NaN or infinity, says which.
#include "DebugReport.h"

#include <bit>
#include <charconv>
#include <cstdio>
#include <utility>

namespace rill::detail {

namespace {

std::string where(const passes::DebugSite& site) {
  // The statement's line from the capture's locations (rill/Error.h SourceLoc): its own, or
  // for a statement an operator made (a gather by `a[i]`) the nearest located one, which
  // describe() says ("near file:line").
  return site.loc.known() ? " at " + site.loc.describe() : "";
}

std::string float_text(uint32_t bits) {
  char buf[32];
  auto r = std::to_chars(buf, buf + sizeof buf, std::bit_cast<float>(bits));
  char hex[16];
  std::snprintf(hex, sizeof hex, "0x%08x", bits);
  return std::string(buf, r.ptr) + " (bits " + hex + ")";
}

// The lowest element whose report is set (-1: none), and how many are.
std::pair<int64_t, int64_t> first_failure(const uint32_t* code, int64_t count) {
  int64_t first = -1, elements = 0;
  for (int64_t e = 0; e < count; ++e)
    if (code[e] != 0) {
      if (first < 0) first = e;
      ++elements;
    }
  return {first, elements};
}

}  // namespace

std::string debug_report(const passes::DebugTable& t, const SlotReader& slot, int64_t count,
                         const std::vector<std::array<int64_t, 3>>& shapes,
                         const std::string& kernel) {
  std::string out;
  if (t.code_slot >= 0) {
    const uint32_t* code = slot(t.code_slot);
    const auto [first, elements] = first_failure(code, count);
    if (first >= 0) {
      const passes::DebugSite& site = t.sites.at(code[first] - 1);
      const auto& shape = shapes.at(static_cast<size_t>(site.array_slot));
      std::string index, size;
      for (int d = 0; d < site.dims; ++d) {
        const uint32_t i = slot(t.index_slots[static_cast<size_t>(d)])[first];
        index += (d ? ", " : "") + std::to_string(static_cast<int32_t>(i));
        size += (d ? " x " : "") + std::to_string(shape[static_cast<size_t>(d)]);
      }
      if (site.dims > 1) index = "(" + index + ")";
      out += "kernel '" + kernel + "' (debug mode): element " + std::to_string(first) +
             " read array '" + site.array + "' at index " + index + ", outside its " + size +
             " elements" + where(site) + " (statement: " + site.statement + ")";
      if (elements > 1)
        out += "; " + std::to_string(elements) + " elements read outside an array in all";
      out += "\n";
    }
  }
  if (t.nonfinite_slot >= 0) {
    const uint32_t* code = slot(t.nonfinite_slot);
    const auto [first, elements] = first_failure(code, count);
    if (first >= 0) {
      const passes::DebugSite& site = t.sites.at(code[first] - 1);
      const uint32_t bits = slot(t.value_slot)[first];
      const bool nan = (bits & 0x007fffffu) != 0;
      out += "kernel '" + kernel + "' (debug mode): element " + std::to_string(first) +
             " produced " + (nan ? "a NaN " : "an infinity ") + float_text(bits) + where(site) +
             " (statement: " + site.statement + ")";
      if (elements > 1)
        out += "; " + std::to_string(elements) + " elements produced a NaN or infinity in all";
      out += "\n";
    }
  }
  return out;
}

}  // namespace rill::detail
