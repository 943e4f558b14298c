// What Kernel needs from DebugReport.cpp: the debug mode's report after a launch.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "PrintSlots.h"
#include "rill/passes/Passes.h"

namespace rill::detail {

// "" when no element failed a check; else one line per kind of failure, naming the lowest
// failing element, what it did and where. `shapes` are the bound arrays' shapes, by slot.
std::string debug_report(const passes::DebugTable& t, const SlotReader& slot, int64_t count,
                         const std::vector<std::array<int64_t, 3>>& shapes,
                         const std::string& kernel);

}  // namespace rill::detail
