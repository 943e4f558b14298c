// A dynamic scene at one time (scene/Animation.h): where its animated objects are and where
// its camera is. The renderer poses the scene each frame; bake() makes the static scene of the
// same instant, which the tests render through the static grid alone and compare bit for bit.
#pragma once

#include "rill/rt/scene/Scene.h"

namespace rt {

// The camera at `time`: the scene's, or its keys' where it has some.
Camera camera_at(const Scene& s, double time);

// Writes the positions and vertex normals of `rest`'s animated objects at `time` into
// `posed`, which holds the same triangles (a copy of `rest`, posed before or not); the other
// triangles and everything else are left as they are.
void pose_objects(const Scene& rest, double time, Scene& posed);

// The static scene of `time`: `s` with its animated objects posed and its camera there, and
// no animation left. Rendering it gives the bits a frame of `s` at `time` gives.
Scene bake(const Scene& s, double time);

}  // namespace rt
