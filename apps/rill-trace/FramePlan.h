// What --frames asks of a render (rill-trace render; FrameSequence.h): which frames, how
// the BVH follows the moving objects, each frame's output names, and where a frame's camera
// comes from for its errors.
#pragma once

#include <string>

#include "FrameSequence.h"
#include "Outputs.h"
#include "Prepare.h"
#include "RenderOptions.h"

namespace trace_cli {

// The frames and output names of a render.
struct FramePlan {
  FrameSpan span;  // frame 0 alone without --frames
  bool animated = false;
  bool sequence = false;  // --frames given: the names carry frame numbers
  rt::BvhUpdate bvh_update = rt::BvhUpdate::Rebuild;
  // The output name of path for a frame.
  NameOf file(int frame) const {
    return [sequence = sequence, frame](const std::string& path) {
      return sequence ? frame_path(path, frame) : path;
    };
  }
};

// Checks that every output has a frame number when there are several frames, that no two
// options name one file, and --video (and, with check_tools, that ffmpeg is there); sets a
// numbered default --out for a sequence. Throws rt::SceneError naming the option.
FramePlan plan_frames(const RenderOptions& o, Prepared& p, bool check_tools = true);

// Where a frame's interpolated camera comes from, for its errors: the scene file and the
// camera keys around the frame's time (keys that are each fine can still interpolate to a
// degenerate view, eye on look_at).
std::string frame_camera_where(const std::string& scene_path, const rt::Scene& s, int frame);

}  // namespace trace_cli
