// What Kernel needs from Print.cpp: formatting the print slots a launch filled.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "rill/Capture.h"

namespace rill::detail {

// The host words of output slot i (a hidden output's stream, read back).
using SlotReader = std::function<const uint32_t*(int slot)>;

// The printed text of a launch over `count` elements: element by element, the sites in
// capture order, at most `limit` elements, then a line counting those left out.
std::string format_prints(const std::vector<PrintSite>& sites, const SlotReader& slot,
                          int64_t count, int64_t limit, const std::string& kernel);

// Whether an output is one of Rill's own (print slots, debug reports): named "rill$...".
inline bool is_hidden_output(const std::string& name) {
  return name.rfind("rill$", 0) == 0;
}

}  // namespace rill::detail
