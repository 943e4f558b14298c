// rill-trace's subcommands (docs/cli.md), one file each: render (RenderCommand.cpp, with its
// options in RenderOptions.h and, under mpirun, distributed/DistributedRender.cpp), accuracy
// (AccuracyCommand.cpp over AccuracyBench.h), noise (NoiseCommand.cpp over
// NoiseBench.h), demo (DemoCommand.cpp) and info
// (InfoCommand.cpp). Each returns the exit status and throws on an error; main() reports it.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "AccuracyBench.h"
#include "NoiseBench.h"
#include "RenderOptions.h"

namespace trace_cli {

// rill-trace render: one image, or the frames of --frames; over every rank when started by
// mpirun as one of several processes.
int render(RenderOptions o);
#if RILL_HAVE_MPI
// The same over every rank of the MPI job (distributed/Farm.h, docs/distributed.md).
int render_distributed(const RenderOptions& o);
#endif

// rill-trace accuracy: time against error for every accuracy knob on every backend.
struct AccuracyCommandOptions {
  rt::AccuracyBenchOptions bench;
  std::string size, backends, scenes;  // as given: WxH, comma-separated lists
};
CLI::App* add_accuracy_command(CLI::App& app, AccuracyCommandOptions& o);
int accuracy(const AccuracyCommandOptions& o);

// rill-trace noise: path tracing's error against spp and time on every backend.
struct NoiseCommandOptions {
  rt::NoiseBenchOptions bench;
  std::string size, backends, variants, modes, targets;  // as given
};
CLI::App* add_noise_command(CLI::App& app, NoiseCommandOptions& o);
int noise(const NoiseCommandOptions& o);

// rill-trace demo: the flagship scene on every backend, and whether the images are identical.
struct DemoOptions {
  std::string scene = "builtin:glass", size, out_dir = ".";
};
CLI::App* add_demo_command(CLI::App& app, DemoOptions& o);
int demo(const DemoOptions& o);

// rill-trace info: the backends, built-in scenes and surface shaders.
CLI::App* add_info_command(CLI::App& app);
int info();

}  // namespace trace_cli
