// A hash of the scene as a rank loaded it, compared by rank 0 before any tile is handed out.
//
// Every rank loads the scene itself (the scene is replicated, not sent), so a rank can end up
// with another scene than rank 0: a file that differs on its host, another version of a mesh,
// a texture missing there, another command line. Its tiles would then not belong in the
// image, and nothing else would notice. The hash covers what decides the pixels: geometry,
// materials and textures, lights, camera, animation and scene options, and the render
// settings main passes as text (size, samples, depth, accuracy, knobs). It leaves out what may
// differ per rank without changing a pixel under strict: the backend, the device, the thread count,
// the scene's name and its load warnings.
#pragma once

#include <cstdint>
#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt::distributed {

// 64-bit FNV-1a over the scene's contents and `settings`; the same on every host (the bytes
// of floats and integers as little-endian x86-64 and AArch64 hold them).
uint64_t scene_hash(const Scene& scene, const std::string& settings);
// The same with the samples per pixel taken as 1: the key of a saved render
// (film/AccumulationFile.h), which a resume takes on to another count.
uint64_t accumulation_hash(const Scene& scene, const std::string& settings);

}  // namespace rt::distributed
