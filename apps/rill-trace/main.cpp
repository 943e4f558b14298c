// rill-trace: the Rill ray tracer's command line.
//
//   rill-trace render SCENE [--backend cpu|simd|opencl|glsl|glsl-compute|vulkan] [--accuracy
//   strict|fast|double]
//                           [--size WxH] [--out FILE.png] [--pfm FILE.pfm] [--depth FILE.pfm]
//                           [--prim FILE.pfm] [--normal FILE.pfm] [--exr FILE.exr]
//                           [--max-depth N] [--spp N]
//                           [--grid N|auto] [--grid-density D|auto] [--subgrids N|off|auto]
//                           [--light-buffer N|off|auto]
//                           [--strategy megakernel|multipass] [--loop auto|ray|segment]
//                           [--stats-json FILE] [--source FILE] [--quiet]
//                           [--triangle moller|watertight] [--offset epsilon|scaled]
//                           [--traversal incremental|recompute] [--packets auto|on|off]
//                           [--stats] [--wait-threshold F] [--masking on|off]   (multipass)
//                           [--device SPEC] [--tile N] [--tail-tile N] [--rank-timeout S]
//                           [--tile-timeout S] [--checkpoint S] [--progress] [--distribute]
//                           (under mpirun: docs/distributed.md)
//   rill-trace accuracy [--backends LIST] [--scenes LIST] [--size WxH] [--repeats N]
//                       [--one-at-a-time] [--out-dir DIR]
//   rill-trace noise [--scene SCENE] [--backends LIST] [--variants LIST] [--modes LIST]
//                    [--size WxH] [--max-spp N] [--repeats N] [--ref-spp N] [--ref-backend B]
//                    [--reference FILE] [--seed N] [--ref-seed N] [--targets LIST]
//                    [--out-dir DIR]
//   rill-trace demo [--scene SCENE] [--size WxH] [--out-dir DIR]
//   rill-trace info
//
// SCENE is a JSON scene file, an OBJ file (framed by a default camera, lit from the eye) or
// builtin:NAME. Exit status: 0 on success, 1 on an error (one line on stderr), 2 on bad
// options.
//
// Each subcommand lives in a file of its own (Commands.h); this file parses the command line
// and reports errors.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <regex>
#include <string>

#include "CliChecks.h"
#include "Commands.h"
#include "Doing.h"
#include "RenderOptions.h"
#include "rill/Kernel.h"
#include "rill/rt/scene/OutputFile.h"

int main(int argc, char** argv) {
  using namespace trace_cli;
  // Ctrl-C or a kill while an image is written leaves no partial file (OutputFile.h).
  rt::remove_partial_output_on_interrupt();
  CLI::App app{"rill-trace: the Rill ray tracer (one DSL kernel, every backend)"};
  app.require_subcommand(1);
  RenderOptions ro;
  AccuracyCommandOptions ao;
  NoiseCommandOptions no;
  DemoOptions dm;
  CLI::App* r = add_render_command(app, ro);
  CLI::App* acc = add_accuracy_command(app, ao);
  CLI::App* nz = add_noise_command(app, no);
  CLI::App* d = add_demo_command(app, dm);
  CLI::App* in = add_info_command(app);
  refuse_empty_values(app);  // every option that takes a value, those added above included

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // An unknown first word: CLI11 only says that a subcommand is required.
    std::string what = e.what();
    // An option given twice: CLI11 says "--size: At Most 1 required but received 2".
    static const std::regex twice("^(-[-\\w]+): At Most 1 required but received (\\d+)$");
    if (std::smatch m; std::regex_match(what, m, twice))
      what = m[1].str() + " is given " + m[2].str() + " times: give it once";
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty())
      what = std::string("unknown command '") + argv[1] + "' (render, accuracy, noise, demo, info)";
    std::fprintf(stderr, "rill-trace: %s (see --help)\n", what.c_str());
    return 2;
  }
  int rc = 0;
  try {
    ro.backend_given = r->count("--backend") > 0;
    // The debug mode reaches every compile of the process through the environment, as if
    // RILL_DEBUG had been set (rill::compile reads it).
    if (*r && (ro.debug || ro.debug_nonfinite))
      setenv("RILL_DEBUG", ro.debug_nonfinite ? "nonfinite" : "1", 1);
    if (*r) rc = render(ro);
    if (*acc) rc = accuracy(ao);
    if (*nz) rc = noise(no);
    if (*d) rc = demo(dm);
    if (*in) rc = info();
  } catch (const CommandLineError& e) {
    std::fprintf(stderr, "rill-trace: %s (see --help)\n", e.what());
    rc = 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "rill-trace: out of memory while %s\n", g_doing.c_str());
    rc = 1;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    for (char& c : msg)
      if (c == '\n') c = ' ';
    std::fprintf(stderr, "rill-trace: %s\n", msg.c_str());
    rc = 1;
  }
  // Workaround for a library bug (reported): a GLSL kernel left in the in-process kernel
  // cache until exit crashes in OSMesaMakeCurrent when OpenCL (PoCL) was used too.
  rill::clear_kernel_cache();
  return rc;
}
