// rill-trace's image sequences (render --frames A:B, docs/cli.md): which frames, the output
// name of each ("frame-%04d.png"), the progress line, and the preview video through ffmpeg.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "JobThread.h"
#include "rill/rt/scene/Animation.h"
#include "rill/rt/scene/FramePattern.h"

namespace trace_cli {

// The frames of "--frames": "N" (one frame) or "A:B" (A to B, both included), checked
// against the scene's frame count (frames 0..count-1); throws rt::SceneError naming the bad
// value.
struct FrameSpan {
  int first = 0, last = 0;
  int count() const { return last - first + 1; }
};
FrameSpan parse_frames(const std::string& spec, const rt::TimeRange& range, bool animated);

// Output names with a frame number: rt::has_frame_number and rt::frame_path
// (scene/FramePattern.h).
using rt::frame_path;
using rt::has_frame_number;

// "\rframe 12/48 [======>      ] 25%, 35.2 ms" on stderr, when stderr is a terminal.
class Progress {
 public:
  Progress(int total, bool quiet);
  void update(int done, double last_ms);
  void finish();

 private:
  int total_;
  bool on_;
};

// Writes frames on a thread of its own (a JobThread), in the order they were posted, so that the
// thread that posts them goes on (rank 0 of a distributed sequence keeps feeding the ranks while a
// PNG is encoded). The first write that throws ends the writing; finish() waits for the writes
// posted and throws that error.
class FrameWriter {
 public:
  FrameWriter();
  ~FrameWriter();  // waits for the writes posted
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;
  void post(std::function<void()> write);
  // Throws the first write's error, if one failed so far (without waiting).
  void check();
  // Waits until at most n of the writes posted have not finished: a sequence that renders
  // faster than it writes keeps only so many frames in memory.
  void wait_in_flight(int n);
  void finish();

 private:
  struct State;
  std::shared_ptr<State> s_;  // shared with the writes in flight
  JobThread thread_;
};

// Runs ffmpeg on the frames written as `pattern` (frames first..), at `fps`, into `video`.
// ffmpeg missing: an error saying how to get it (checked by video_tool_missing first, so
// that nothing is rendered for nothing).
std::string video_tool_missing();
void write_video(const std::string& pattern, int first, double fps, const std::string& video);

}  // namespace trace_cli
