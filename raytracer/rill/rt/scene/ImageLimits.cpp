#include "rill/rt/scene/ImageLimits.h"

#include "rill/rt/scene/Scene.h"

namespace rt {

bool image_size_fits(int64_t width, int64_t height) {
  // Each side first, so that the product cannot overflow.
  return width >= 1 && height >= 1 && width <= kMaxImageSide && height <= kMaxImageSide &&
         width * height <= kMaxImagePixels;
}

std::string image_size_limits() {
  return "1.." + std::to_string(kMaxImageSide) + " per side, at most " +
         std::to_string(kMaxImagePixels) + " pixels";
}

void check_declared_image(const std::string& file, const std::string& format, int64_t width,
                          int64_t height, int64_t channels) {
  if (!image_size_fits(width, height))
    throw SceneError(file + ": its header declares a " + std::to_string(width) + "x" +
                     std::to_string(height) + " " + format + " image, over the limits (" +
                     image_size_limits() + ")");
  if (channels > kMaxImageChannels)
    throw SceneError(file + ": its header declares " + std::to_string(channels) +
                     " channels, over " + "the limit of " + std::to_string(kMaxImageChannels) +
                     " for " + format + " images");
}

}  // namespace rt
