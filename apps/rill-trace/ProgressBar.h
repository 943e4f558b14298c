// The bar both of rill-trace's progress lines draw: a frame sequence's ("frame 12/48
// [=======>      ] 25%") and a distributed render's tiles on rank 0.
#pragma once

#include <string>

namespace trace_cli {

// "[=======>      ]": `width` characters between brackets, filled in proportion to done of
// total (full when total is 0).
inline std::string progress_bar(int done, int total, int width = 30) {
  const int filled = total > 0 ? done * width / total : width;
  std::string bar(static_cast<size_t>(filled < 0 ? 0 : filled), '=');
  if (filled < width) bar += '>';
  bar.resize(static_cast<size_t>(width), ' ');
  return "[" + bar + "]";
}

}  // namespace trace_cli
