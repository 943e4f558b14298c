// The benchmarks' list options ("cpu,opencl", "1,4,8"): comma-separated, empty items dropped;
// and back.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace rill::bench {

inline std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) v.push_back(item);
  return v;
}

inline std::string join_list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& item : v) s += (s.empty() ? "" : ",") + item;
  return s;
}

}  // namespace rill::bench
