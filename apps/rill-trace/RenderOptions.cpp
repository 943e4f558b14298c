#include "RenderOptions.h"

#include <functional>
#include <string>

#include "CliChecks.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"

namespace trace_cli {

bool any_image_output(const RenderOptions& o) {
  return !o.out.empty() || !o.pfm.empty() || !o.depth.empty() || !o.prim.empty() ||
         !o.normal.empty() || !o.exr.empty() || !o.albedo.empty();
}

// The parser of an option that takes "on" or "off" (as a bool), naming the option in its error.
static std::function<bool(const std::string&)> on_off(const std::string& option) {
  return [option](const std::string& s) {
    if (s != "on" && s != "off")
      throw rt::SceneError(option + " expects on or off (got '" + s + "')");
    return s == "on";
  };
}

CLI::App* add_render_command(CLI::App& app, RenderOptions& o) {
  CLI::App* r = app.add_subcommand("render", "render a scene");
  r->add_option("scene", o.scene, "JSON scene, OBJ file or builtin:NAME")->required();
  r->add_option("--backend", o.backend, "cpu, simd, opencl, glsl, glsl-compute or vulkan")
      ->default_str("cpu");
  add_parsed_option(r, "--accuracy", o.accuracy, rill::parse_accuracy, "strict, fast or double")
      ->default_str("strict");
  add_parsed_option(
      r, "--size", o.width,
      [&o](const std::string& s) {
        parse_size(s, o.width, o.height);
        return o.width;
      },
      "image size WxH (default: the scene's)")
      ->check(non_empty());
  add_camera_options(r, o.camera);
  r->add_option("--out", o.out, "PNG output (sRGB)")->check(file_name());
  r->add_option("--pfm", o.pfm, "linear colour as PFM")->check(file_name());
  r->add_option("--depth", o.depth, "hit distance AOV as PFM (+inf: miss)")->check(file_name());
  r->add_option("--prim", o.prim, "primitive id AOV as PFM (-1: miss)")->check(file_name());
  r->add_option("--normal", o.normal, "shading normal AOV as PFM")->check(file_name());
  r->add_option("--albedo", o.albedo,
                "path: the first hit's albedo AOV as PFM (for denoisers; 0 for a miss)")
      ->check(file_name());
  r->add_option("--exr", o.exr,
                "OpenEXR, 32-bit channels: linear colour R G B, depth Z (+inf: miss) and normal "
                "N.X N.Y N.Z as FLOAT, primitive id prim as UINT (4294967295: miss)")
      ->check(file_name());
  r->add_flag("--variance", o.variance,
              "with --exr: channels var.R var.G var.B, each pixel's variance of its mean colour "
              "(2 samples or more; not with --resume)");
  r->add_option("--max-depth", o.max_depth, "reflection/refraction bounces")
      ->check(number_in(0, 64, true));
  r->add_option("--spp", o.spp,
                "samples per pixel (the path integrator's target with --time-limit)")
      ->check(number_in(1, rt::kMaxSpp, true));
  add_parsed_option(r, "--integrator", o.integrator, rt::parse_integrator,
                    "whitted or path (default: the scene's options.integrator)")
      ->check(non_empty());
  r->add_option("--seed", o.seed, "path: the random sequence (default: the scene's options.seed)")
      ->check(number_in(0, 2147483647, true));
  r->add_option("--time-limit", o.time_limit,
                "path: stop after the pass (one sample per pixel) that crosses S seconds, and "
                "say how many samples per pixel it reached")
      ->check(number_in(1e-3, 1e7, false));
  r->add_option("--save", o.save,
                "path: write the running sums to FILE at the end (and every --save-every "
                "passes), to --resume from")
      ->check(file_name());
  r->add_option("--save-every", o.save_every, "with --save: also every N passes")
      ->check(number_in(1, rt::kMaxSpp, true));
  r->add_option("--resume", o.resume,
                "path: go on from the sums --save wrote (same scene, size and seed) up to --spp: "
                "bitwise the image rendered at once")
      ->check(file_name());
  add_parsed_option(r, "--grid", o.grid, parse_grid, "voxels per axis, or auto")
      ->check(non_empty());
  add_parsed_option(r, "--grid-density", o.grid_density, rt::parse_grid_density,
                    "voxels per triangle of the auto grid, 0.125..256, or auto (default: 16 "
                    "on simd for a scene of 10000 triangles or more, else 4)")
      ->check(non_empty());
  add_parsed_option(
      r, "--subgrids", o.subgrid_min, rt::parse_subgrid_min,
      "voxels listing more triangles than this get a subgrid (1..1048576), off, or auto "
      "(default: 12 when the backend runs on the CPU, off on a GPU)")
      ->check(non_empty());
  add_parsed_option(
      r, "--light-buffer", o.light_buffer, rt::parse_light_buffer,
      "shadow rays: cells per edge of each light's direction cube (1..1024), off (walk "
      "the grid), or auto (default: 64 where the scene has shadows)")
      ->check(non_empty());
  add_parsed_option(
      r, "--strategy", o.strategy, rt::parse_strategy,
      "megakernel (one kernel, Sh style), multipass (the thesis's kernel sequence; whitted) "
      "or wavefront (the path integrator's stages, a kernel each; path)")
      ->default_str("megakernel");
  add_parsed_option(r, "--loop", o.loop, rt::parse_megakernel_loop,
                    "megakernel: one traced ray per loop iteration (ray), or one path segment with "
                    "its shadow rays (segment), or auto (default: segment on cpu and simd, ray on "
                    "opencl, glsl and glsl-compute). Images do not depend on it")
      ->default_str("auto");
  r->add_option("--stats-json", o.stats_json, "write timings and counts as JSON")
      ->check(file_name());
  r->add_option("--source", o.source, "write the generated kernel source")->check(file_name());
  r->add_flag("--quiet", o.quiet, "print only the stats line");
  r->add_option("--threads", o.threads,
                "worker threads of the CPU backends (cpu, simd); default: one per core. Images "
                "do not depend on it")
      ->check(number_in(1, 4096, true));
  r->add_flag("--strict-input", o.strict_input,
              "malformed lines in OBJ and MTL files are errors (default: warnings naming the "
              "first few lines, then a count)");
  r->add_flag("--allow-empty", o.allow_empty,
              "a mesh file without faces loads as no triangles instead of an error");
  r->add_option("--bench-frames", o.bench_frames,
                "frame-rate mode: render N more frames back to back after the first and report "
                "their times and frames per second")
      ->check(number_in(0, 100000, true));
  r->add_option("--tile", o.tile,
                "distributed (mpirun): tile size in pixels, handed out one at a time; images "
                "do not depend on it")
      ->default_str("128")
      ->check(number_in(1, 16384, true));
  r->add_option("--tail-tile", o.tail_tile,
                "distributed: the last tiles handed out (twice as many as there are ranks) are "
                "cut into tiles of N pixels, so that the ranks finish together (0: not cut)")
      ->default_str("half of --tile")
      ->check(number_in(0, 16384, true));
  r->add_option("--rank-timeout", o.rank_timeout,
                "distributed: seconds a rank may be silent before it is lost")
      ->default_str("20")
      ->check(number_in(1, 86400, false));
  r->add_option("--tile-timeout", o.tile_timeout,
                "distributed: seconds a rank may take for a tile before it is lost (0: no limit)")
      ->default_str("0")
      ->check(number_in(0, 86400, false));
  r->add_option("--checkpoint", o.checkpoint,
                "distributed: rank 0 writes the image so far as NAME.partial.EXT this often, in "
                "seconds, while it renders (0: never); removed when the render completes")
      ->default_str("2")
      ->check(number_in(0, 86400, false));
  r->add_option("--device", o.device,
                "the device of opencl, glsl, glsl-compute or vulkan (RILL_OPENCL_DEVICE, "
                "RILL_EGL_DEVICE or RILL_VULKAN_DEVICE); {local_rank} is the rank's index on its "
                "host");
  r->add_flag("--progress", o.progress,
              "distributed: rank 0 draws a progress bar on stderr, the tiles done per rank "
              "(mpirun passes stderr through a pipe, so rill-trace cannot tell a terminal)");
  r->add_flag("--distribute", o.distribute,
              "require a distributed render: an error unless started by mpirun with 2 or more "
              "processes");
  r->add_option("--frames", o.frames,
                "dynamic scenes: frame N, or frames A:B (both included); outputs need a frame "
                "number, e.g. --out frame-%04d.png");
  add_parsed_option(
      r, "--bvh", o.bvh,
      [](const std::string& s) {
        try {
          return rt::parse_bvh_update(s);
        } catch (const std::invalid_argument& e) {
          throw rt::SceneError(std::string("--bvh: ") + e.what());
        }
      },
      "dynamic scenes: the moving objects' BVH each frame: rebuild or refit")
      ->default_str("rebuild");
  r->add_option("--video", o.video,
                "with --frames: a preview video of the PNGs (ffmpeg), .mp4 or .gif")
      ->check(file_name());
  add_parsed_option(r, "--triangle", o.knobs.triangle, rt::parse_triangle_test,
                    "triangle test: moller or watertight")
      ->default_str("moller");
  add_parsed_option(r, "--offset", o.knobs.offset, rt::parse_self_intersection,
                    "self-intersection: scaled (Wachter-Binder) or epsilon")
      ->default_str("scaled");
  add_parsed_option(r, "--traversal", o.knobs.traversal, rt::parse_traversal,
                    "grid traversal: incremental or recompute")
      ->default_str("incremental");
  add_parsed_option(r, "--packets", o.knobs.packets, rt::parse_packets,
                    "lane groups walk the grid together: auto (off today), on or off")
      ->default_str("auto");
  r->add_flag("--debug", o.debug,
              "kernels check every gather's index and stop at the first read outside an "
              "array, naming the element, index and array (docs/debugging.md)");
  r->add_flag("--debug-nonfinite", o.debug_nonfinite,
              "--debug, and report the first statement that produced a NaN or infinity");
  r->add_flag("--stats", o.stats,
              "print the compile stages; the path megakernel: its samples per launch and why; "
              "multipass and wavefront: per-pass calls, elements and time");
  r->add_option("--wait-threshold", o.wait_threshold,
                "multipass: rerun the intersector while this fraction of rays waits (0..1]")
      ->default_str("0.2")
      ->check(number_in(1e-6, 1.0, false));
  add_parsed_option(r, "--masking", o.masking, on_off("--masking"),
                    "multipass: launch each pass masked to its state (on|off)")
      ->default_str("on");
  add_parsed_option(
      r, "--overlap", o.overlap, on_off("--overlap"),
      "--frames: write each frame's outputs while the next one renders, and (--frames, "
      "--bench-frames) read each frame back from the device while the next one traces where the "
      "backend can (opencl, glsl-compute) (on|off); images do not depend on it")
      ->default_str("on");
  return r;
}

}  // namespace trace_cli
