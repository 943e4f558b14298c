// Paths with a frame number (FramePattern.h).
#include "rill/rt/scene/FramePattern.h"

#include <cstdio>
#include <cstdlib>

#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// The frame number's conversion in `pattern`: its position and length, or npos; throws for
// a second one or any other conversion.
size_t conversion(const std::string& pattern, const std::string& option, size_t& len) {
  size_t at = std::string::npos;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    size_t j = i + 1;
    while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9') ++j;
    if (j >= pattern.size() || pattern[j] != 'd' || j - i - 1 > 2 ||
        (j > i + 1 && std::atoi(pattern.c_str() + i + 1) > 20))
      throw SceneError(option + " '" + clipped(pattern) +
                       "': the only conversion allowed is the frame number, as %d or "
                       "%04d (a width of at most 20; write a percent sign as %%)");
    if (at != std::string::npos)
      throw SceneError(option + " '" + clipped(pattern) +
                       "' has two frame numbers; give one, such as frame-%04d.png");
    at = i;
    len = j + 1 - i;
    i = j;
  }
  return at;
}

}  // namespace

bool has_frame_number(const std::string& pattern, const std::string& option) {
  size_t len = 0;
  return conversion(pattern, option, len) != std::string::npos;
}

std::string frame_path(const std::string& pattern, int frame) {
  size_t len = 0;
  const size_t at = conversion(pattern, "the output", len);
  std::string out;
  for (size_t i = 0; i < pattern.size(); ++i) {
    if (i == at) {
      char buf[32];
      std::snprintf(buf, sizeof buf, pattern.substr(at, len).c_str(), frame);
      out += buf;
      i += len - 1;
    } else if (pattern[i] == '%' && i + 1 < pattern.size() && pattern[i + 1] == '%') {
      out += '%';
      ++i;
    } else {
      out += pattern[i];
    }
  }
  return out;
}

}  // namespace rt
