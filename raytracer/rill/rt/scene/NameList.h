// Names in a message, bounded: an error or a warning that lists what a file defines (its
// textures, its meshes) names a few and counts the rest, so that a file of 20,000 textures
// gives a line, not 148 KB: "a, b, c, d, e and 19,995 more".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rt {

// How many names a list shows before it counts the rest.
inline constexpr size_t kNamesShown = 5;

// The first `shown` names (each clipped, Scene.h: clipped), comma-separated, then " and N
// more" when there are others; "" for none.
std::string name_list(const std::vector<std::string>& names, size_t shown = kNamesShown);

// n with its thousands grouped by commas, as counts are written in messages: "19,995".
std::string grouped(uint64_t n);

}  // namespace rt
