// The work items of the tracer's kernels, as Rill records (rill/Record.h): what a ray is,
// what it hit, the shading state at a hit, and a ray's grid traversal between kernels. The
// megakernel keeps them in loop variables; the multipass strategy keeps them in streams of
// records between its kernels (one stream per field, bound by name).
#pragma once

#include <rill/Record.h>
#include <rill/rill.h>

namespace rt {

using rill::Bool;
using rill::Bool3;
using rill::Float;
using rill::Float2;
using rill::Float3;
using rill::Float4;
using rill::Int;
using rill::Int2;
using rill::Int3;
using rill::Int4;

constexpr float kBig = 3.0e38f;  // "no limit" for ray extents (finite on every backend)

// A ray: origin, direction and extent (kBig for camera and reflected rays).
RILL_STRUCT(Ray, (Float3, o), (Float3, d), (Float, tmax));

// The closest hit so far: distance, barycentrics, triangle id (-1: none).
RILL_STRUCT(Hit, (Float, t), (Float2, uv), (Int, id));

// The shading state at a hit, what a surface shader (Shader.h) reads: the point, the
// shading normal as stored (ns, for the normal AOV), the shading and geometric normals
// turned towards the incoming ray (nf, ngf), the direction back along the ray (V), the
// texture coordinates, whether the ray enters the surface (it hit the front side), the
// vertex colour (white without one) and the material's index.
RILL_STRUCT(Surface, (Float3, P), (Float3, ns), (Float3, nf), (Float3, ngf), (Float3, V),
            (Float2, uv), (Bool, entering), (Float3, vertex_color), (Int, material));

// The camera ray's AOVs as the multi-kernel strategies keep them in a stream: its hit's
// distance (+inf: none), primitive (-1: none) and shading normal as stored (0: none).
RILL_STRUCT(Aov, (Float, depth), (Int, prim), (Float3, normal));

// A ray's grid traversal between kernels of the multipass strategy: its state, the current
// voxel, the distances to its exit planes (tMax), where the ray leaves the grid, the voxel
// steps taken, and the cursor over the voxel's triangle list (next, end), or a subgrid's
// entry (base, -m).
RILL_STRUCT(TraceState, (Int, state), (Int3, voxel), (Float3, t_next), (Float, t_exit),
            (Int, steps), (Int2, cursor));

}  // namespace rt
