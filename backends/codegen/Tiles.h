// The tiled launch order of the GPU backends (opencl, glsl-compute): a 2D launch runs
// invocations 32k..32k+31 on the 8 x 4 elements of tile k (tiles in rows of the domain), so
// the 32 elements of a warp or subgroup are neighbours in both directions, not 32 along a
// row. Each element computes the same as in row order; only which invocation runs it changes.
// Stated once here; each emitter prints it in its own language.
#pragma once

#include <cstdint>
#include <string>

namespace rill::codegen {

constexpr int kTileWidth = 8, kTileHeight = 4;  // 32: one NVIDIA warp

// Invocations a tiled launch of a width x height domain spans (whole tiles).
inline int64_t tiled_invocations(int64_t width, int64_t height) {
  return (width + kTileWidth - 1) / kTileWidth * ((height + kTileHeight - 1) / kTileHeight) *
         kTileWidth * kTileHeight;
}

// C-family statements (OpenCL C, GLSL) that turn invocation number `index` (a variable of
// integer type `int_type`) into the element it runs, in place, over a domain `width` wide;
// `outside` is the statement for an invocation right of the last column (its tile sticks
// out). Rows below the last are past the element count, which the caller checks.
inline std::string tiled_element(const std::string& int_type, const std::string& index,
                                 const std::string& width, const std::string& outside,
                                 const std::string& indent) {
  const std::string w = std::to_string(kTileWidth), h = std::to_string(kTileHeight),
                    n = std::to_string(kTileWidth * kTileHeight);
  return indent + "{\n" + indent + "  const " + int_type + " rill_tile = " + index + " / " + n +
         ", rill_lane = " + index + " % " + n + ", rill_tiles_x = (" + width + " + " + w +
         " - 1) / " + w + ";\n" + indent + "  const " + int_type +
         " rill_x = (rill_tile % rill_tiles_x) * " + w + " + rill_lane % " + w + ";\n" + indent +
         "  if (rill_x >= " + width + ") " + outside + "\n" + indent + "  " + index +
         " = ((rill_tile / rill_tiles_x) * " + h + " + rill_lane / " + w + ") * " + width +
         " + rill_x;\n" + indent + "}\n";
}

}  // namespace rill::codegen
