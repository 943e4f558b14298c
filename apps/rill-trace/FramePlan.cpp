#include "FramePlan.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <utility>

#include "rill/rt/scene/Scene.h"

namespace trace_cli {

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
  // Two options naming one file: the later write would silently replace the earlier one.
  {
    const std::pair<std::string, const std::string*> files[] = {
        {"--out", &p.out},       {"--pfm", &o.pfm},
        {"--depth", &o.depth},   {"--prim", &o.prim},
        {"--normal", &o.normal}, {"--exr", &o.exr},
        {"--albedo", &o.albedo}, {"--stats-json", &o.stats_json},
        {"--source", &o.source}};
    std::map<std::string, std::string> seen;  // normalized path -> option
    for (const auto& [option, path] : files) {
      if (path->empty() || *path == "/dev/null") continue;
      const std::string key = std::filesystem::path(*path).lexically_normal().string();
      auto [it, fresh] = seen.emplace(key, option);
      if (!fresh)
        throw rt::SceneError(it->second + " and " + option + " both name " + *path +
                             ": one would overwrite the other");
    }
  }
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
