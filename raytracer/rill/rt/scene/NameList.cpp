#include "rill/rt/scene/NameList.h"

#include "rill/rt/scene/Scene.h"

namespace rt {

std::string name_list(const std::vector<std::string>& names, size_t shown) {
  std::string out;
  for (size_t i = 0; i < names.size() && i < shown; ++i)
    out += (i == 0 ? "" : ", ") + clipped(names[i]);
  if (names.size() > shown) out += " and " + grouped(names.size() - shown) + " more";
  return out;
}

std::string grouped(uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

}  // namespace rt
