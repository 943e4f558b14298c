// The largest images Rill makes and reads: 16384 pixels a side and 2^25 (33,554,432) pixels
// in all, as docs/robustness.md ("Images and textures") documents them. A scene's image size
// and RenderSettings' are checked against them, and so is the size an image file's header
// declares (a PNG texture, a PFM, an EXR), before anything of that size is allocated: a
// 69-byte PNG may claim 16384x16384 pixels, a gigabyte once decoded.
#pragma once

#include <cstdint>
#include <string>

namespace rt {

inline constexpr int kMaxImageSide = 16384;
inline constexpr int64_t kMaxImagePixels = int64_t{1} << 25;
// An EXR file's channels read at most (Rill writes 8 to 14).
inline constexpr int kMaxImageChannels = 64;

// Whether a width x height image is within the limits (both sides 1 or more).
bool image_size_fits(int64_t width, int64_t height);
// The limits in words, for messages: "1..16384 per side, at most 33554432 pixels".
std::string image_size_limits();
// Throws SceneError when the size an image file's header declares is over the limits:
// "FILE: its header declares a WxH FORMAT image, over the limits (1..16384 per side, at most
// 33554432 pixels)"; `channels` (0: not checked) over kMaxImageChannels the same way.
void check_declared_image(const std::string& file, const std::string& format, int64_t width,
                          int64_t height, int64_t channels = 0);

}  // namespace rt
