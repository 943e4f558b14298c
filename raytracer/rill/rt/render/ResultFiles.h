// A render's image written to files from a program, as rill-trace writes them (docs/cli.md,
// "Output files"): a PNG, 8-bit sRGB, and an OpenEXR file of the linear colour with every
// AOV the render read back. Each is written whole or not at all (scene/OutputFile.h) and
// throws SceneError naming the file when it cannot be, or when the render did not read back
// what the file needs (RenderSettings::outputs).
//
//   rt::RenderResult r = tracer.render(rt::RenderSettings{}, scene.camera);
//   rt::save(r, "image.png");  // or .pfm, .exr: the format by the extension
//   rt::write_png("image.png", r);
//   rt::write_exr("image.exr", r);
#pragma once

#include <string>

#include "rill/rt/render/RenderResult.h"

namespace rt {

// The 8-bit image (RenderResult::rgb8, encoded on the device) where the render read it back,
// else the colour encoded here the same way (scene/Image.h: to_srgb8): the same bytes.
void write_png(const std::string& path, const RenderResult& r);

// Channels R, G, B (the linear colour, FLOAT) and, for each AOV the render read back, those of
// rill-trace's --exr: Z (depth), N.X N.Y N.Z (normal), prim (UINT, a miss 4294967295),
// var.R var.G var.B (variance), albedo.R albedo.G albedo.B.
void write_exr(const std::string& path, const RenderResult& r);

// The linear colour as a 3-channel PFM (scene/Image.h: write_pfm), rill-trace's --pfm.
void write_pfm(const std::string& path, const RenderResult& r);

// The render saved in the format its extension names, in any case: .png (write_png), .pfm
// (write_pfm) or .exr (write_exr). Another extension, or none, throws SceneError naming it and
// the three formats before anything is written: a name is never written in a format it does
// not name (a PNG behind out.jpg).
void save(const RenderResult& r, const std::string& path);

}  // namespace rt
