// What a render writes and reports (rill-trace render): the images asked for, the
// --stats-json fields every render shares, and the notes after the outputs.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "Prepare.h"
#include "RenderOptions.h"

namespace trace_cli {

// An output's name for one frame, or for a partial render ("x.png" -> "x.partial.png").
using NameOf = std::function<std::string(const std::string&)>;

// Writes the outputs asked for from a render, each under name(its path) (a partial render
// writes beside the names asked for); returns what it wrote.
std::vector<std::string> write_outputs(
    const RenderOptions& o, const Prepared& p, const rt::RenderResult& r,
    const NameOf& name = [](const std::string& s) { return s; });

// The --stats-json fields a distributed render shares with a single-process one: width x
// height images, rays traced over all of them.
nlohmann::json stats_json(const RenderOptions& o, const Prepared& p, int width, int height,
                          int64_t rays);

// The path megakernel's samples per launch as this render runs them (path regeneration: more
// than 1), and why: "--time-limit", "--variance", "RILL_PATH_REGENERATE=on|off" or "the
// backend's default" (rt::path_samples_per_launch). per_launch is 0 for a render that does
// not run the path megakernel (Whitted's tracer, another strategy).
struct PathLaunches {
  int per_launch = 0;
  std::string why;
};
PathLaunches path_launches(const RenderOptions& o, const Prepared& p);

// Writes j to path, indented, through the checked writer (rt/scene/OutputFile.h); throws
// naming the file when it cannot.
void write_json(const std::string& path, const nlohmann::json& j);

// --source, when given: the generated kernel source of the variant the render ran (the
// outputs asked for, the scene's samples per pixel).
void write_source(const RenderOptions& o, const Prepared& p);

// How many "wrote FILE" lines print_notes prints; the rest are counted.
constexpr size_t kWroteShown = 8;

// The notes after the outputs (unless --quiet): what was written (the first kWroteShown files,
// then "... and N more (the last: FILE)"), and scene trouble.
void print_notes(const RenderOptions& o, const Prepared& p,
                 const std::vector<std::string>& written);

}  // namespace trace_cli
