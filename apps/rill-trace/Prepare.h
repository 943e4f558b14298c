// Everything a render needs before its first frame (rill-trace render): the scene loaded with
// the command line's changes, its grid, the tracer and the render settings.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "RenderOptions.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

// Everything a render needs before its first frame: the scene with the command line's changes,
// its grid, the tracer and the settings. Each rank of a distributed render makes its own.
// Built in place and never moved (the tracer was made from the scene and grid beside it).
struct Prepared {
  rt::Scene scene;
  rt::Grid grid;
  std::unique_ptr<rt::Tracer> tracer;
  rt::RenderSettings rs;
  std::string out;                  // the PNG: --out, or a default name when no output is named
  std::vector<std::string> inputs;  // the files loading read (scene, OBJ, MTL, textures)
  double load_ms = 0, setup_ms = 0;
};

// Loads and checks the scene, builds its grid and the tracer. Warnings go to stderr when
// `say` (rank 0 of a distributed render; every single process). Throws rt::SceneError naming
// a bad option or input.
std::unique_ptr<Prepared> prepare(const RenderOptions& o, bool say = true);

}  // namespace trace_cli
