// rill-trace render's progressive path rendering (docs/path-tracing.md): the samples in passes
// of one sample per pixel, with a progress bar (samples per second and time left), a time
// limit that stops after the pass crossing it, the running sums saved every N passes and at
// the end (--save), and a render resumed from them (--resume). Saving every N passes renders
// in chunks, each resumed from the last: by the film's construction the image is bitwise the
// one rendered at once.
#pragma once

#include "Prepare.h"
#include "RenderOptions.h"
#include "rill/rt/film/AccumulationFile.h"

namespace trace_cli {

// Whether the render is progressive (the path integrator with a time limit, --save or
// --resume, or enough samples for a progress bar to help).
bool progressive(const RenderOptions& o, const Prepared& p);

// What a saved render belongs to (--save, --resume; one process or under mpirun): the scene
// as loaded with the command line's changes, the accuracy and knobs, and the seed.
rt::AccumulationKey accumulation_key(const RenderOptions& o, const Prepared& p);

// --resume's file, read and checked against the render: its scene, settings, seed and size,
// no more samples than the scene's spp (--spp), and the squares when --variance is asked for.
// Throws SceneError naming the file.
rt::Accumulation read_resume(const RenderOptions& o, const Prepared& p);

// Renders p's frame through camera progressively; returns the result of the whole render
// (its trace time and ray count summed over the chunks, r.spp the samples reached).
rt::RenderResult render_progressive(const RenderOptions& o, Prepared& p, const rt::Camera& camera);

}  // namespace trace_cli
