#include "FramePlan.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <utility>

#include "OutputPaths.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

namespace {

// Before rendering: each output's format against its name, and no output that is another or
// an input, by any spelling (OutputPaths.h). A sequence's outputs are checked frame by frame:
// frame-%d.png and frame-%04d.png are one file from frame 1000 on.
void check_outputs(const RenderOptions& o, const Prepared& p, const FramePlan& plan) {
  const std::pair<std::string, const std::string*> images[] = {
      {"--out", &p.out},       {"--pfm", &o.pfm}, {"--depth", &o.depth},  {"--prim", &o.prim},
      {"--normal", &o.normal}, {"--exr", &o.exr}, {"--albedo", &o.albedo}};
  const std::pair<std::string, const std::string*> others[] = {
      {"--stats-json", &o.stats_json}, {"--source", &o.source}, {"--save", &o.save}};
  std::vector<NamedFile> outputs;
  for (const auto& [option, path] : images)
    if (!path->empty()) check_output_format(option, *path);
  for (const auto& [option, path] : others)
    if (!path->empty()) check_output_format(option, *path);
  for (int k = plan.span.first; k <= plan.span.last; ++k)
    for (const auto& [option, path] : images)
      if (!path->empty()) outputs.push_back({option, plan.file(k)(*path)});
  for (const auto& [option, path] : others)
    if (!path->empty()) outputs.push_back({option, *path});
  if (!o.video.empty()) outputs.push_back({"--video", o.video});  // ffmpeg's format: its own
  std::vector<NamedFile> inputs;
  if (o.scene.rfind("builtin:", 0) != 0) inputs.push_back({"the scene file", o.scene});
  for (const std::string& f : p.inputs) inputs.push_back({"a file the scene loaded", f});
  // --save F --resume F goes on from F and saves over it (docs/cli.md): F is read whole before
  // the render starts, and replaced whole only once the new sums are written.
  if (!o.resume.empty() && (o.save.empty() || file_identity(o.resume) != file_identity(o.save)))
    inputs.push_back({"the --resume file", o.resume});
  check_output_files(outputs, inputs);
}

}  // namespace

FramePlan plan_frames(const RenderOptions& o, Prepared& p, bool check_tools) {
  const rt::Scene& scene = p.scene;
  FramePlan plan;
  plan.animated = scene.animation.animated();
  plan.sequence = !o.frames.empty();
  plan.span =
      plan.sequence ? parse_frames(o.frames, scene.animation.time, plan.animated) : FrameSpan{};
  plan.bvh_update = o.bvh;
  const FrameSpan& span = plan.span;
  if (!any_image_output(o) && span.count() > 1)
    p.out = (scene.name.empty() ? std::string("render") : scene.name) + "-%04d.png";
  const std::pair<std::string, const std::string*> outputs[] = {
      {"--out", &p.out},       {"--pfm", &o.pfm}, {"--depth", &o.depth},  {"--prim", &o.prim},
      {"--normal", &o.normal}, {"--exr", &o.exr}, {"--albedo", &o.albedo}};
  for (const auto& [option, path] : outputs) {
    if (path->empty()) continue;
    const bool numbered = plan.sequence && has_frame_number(*path, option);
    if (span.count() > 1 && !numbered)
      throw rt::SceneError("--frames " + o.frames + " writes " + std::to_string(span.count()) +
                           " frames: " + option + " needs a frame number, such as frame-%04d" +
                           std::filesystem::path(*path).extension().string());
  }
  check_outputs(o, p, plan);
  if (!o.video.empty()) {
    if (p.out.empty() || !plan.sequence)
      throw rt::SceneError("--video makes a video of the frames' PNGs: give --frames and --out");
    if (std::string why = check_tools ? video_tool_missing() : std::string(); !why.empty())
      throw rt::SceneError(why);
  }
  return plan;
}

std::string frame_camera_where(const std::string& scene_path, const rt::Scene& s, int frame) {
  const double t = s.animation.time.time_of(frame);
  const auto& keys = s.animation.camera.keys;
  size_t i = 0;
  while (i + 1 < keys.size() && keys[i + 1].time <= t) ++i;
  std::string from = "camera.keys[" + std::to_string(i) + "]";
  if (i + 1 < keys.size() && keys[i].time < t)
    from = "between camera.keys[" + std::to_string(i) + "] and [" + std::to_string(i + 1) + "]";
  char time[32];
  std::snprintf(time, sizeof time, "%g", t);
  return scene_path + ": the camera at frame " + std::to_string(frame) + " (time " + time + ", " +
         from + ")";
}

}  // namespace trace_cli
