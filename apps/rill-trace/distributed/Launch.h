// How this rill-trace process was started, and which backend and device it renders on.
//
// A distributed render is one rill-trace per MPI rank, started by a launcher (mpirun). Each
// process has to know, before anything touches MPI, whether it is one of several: only then
// does it start MPI (a plain `rill-trace render` never does, so it runs as it always did), and
// a build without MPI must refuse to render the whole image N times side by side. On a
// cluster the ranks of one command line also need different devices (a GPU per rank), which
// the launcher can only give them through the environment or a per-rank value.
#pragma once

#include <string>

namespace rt::distributed {

// The number of processes the MPI launcher started (Open MPI's OMPI_COMM_WORLD_SIZE, or
// PMI_SIZE / PMIX_SIZE of MPICH, Slurm and PMIx launchers); 0 when none started this one.
int launcher_world_size();

// The backend a rank renders on: --backend when given, else $RILL_TRACE_BACKEND, else cpu.
std::string rank_backend(const std::string& cli_backend, bool cli_given);

// The device spec a rank renders on: --device when given, else $RILL_TRACE_DEVICE, else ""
// (the backend's default), with every "{local_rank}" replaced by the rank's index among the
// ranks of its host (0, 1, ... on each node: one GPU per rank).
std::string rank_device(const std::string& cli_device, int local_rank);

// Points the backend at the device: RILL_OPENCL_DEVICE for opencl, RILL_EGL_DEVICE for glsl
// and glsl-compute (docs/backends.md), before the backend starts. An empty spec leaves the
// environment as it is; a spec for a CPU backend is an error naming the option.
void use_device(const std::string& backend, const std::string& spec);

}  // namespace rt::distributed
