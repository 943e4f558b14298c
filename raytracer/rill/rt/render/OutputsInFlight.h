// A render's read-backs in flight (RenderSettings::read_back_later): what the film started
// (Film::finish) and what RenderResult::wait_outputs() waits for and finishes.
#pragma once

#include <rill/rill.h>

#include <cstddef>
#include <vector>

namespace rt {

struct OutputsInFlight {
  std::vector<rill::ReadBack> reads;  // into the result's image vectors
  // The 8-bit image is read in groups of 4 pixels: its size once read, without the padding
  // of the last group (0: no 8-bit image).
  size_t rgb8_bytes = 0;
};

}  // namespace rt
