// Image sequences for rill-trace (FrameSequence.h).
#include "FrameSequence.h"

#include "ProgressBar.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <mutex>
#include <utility>

#include "rill/rt/scene/FramePattern.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

namespace {

bool parse_int(const std::string& s, int& v) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  v = std::atoi(s.c_str());
  return true;
}

}  // namespace

FrameSpan parse_frames(const std::string& spec, const rt::TimeRange& range, bool animated) {
  const int count = animated ? range.frame_count() : 1;
  FrameSpan f;
  const size_t colon = spec.find(':');
  const bool ok = colon == std::string::npos ? parse_int(spec, f.first) && (f.last = f.first, true)
                                             : parse_int(spec.substr(0, colon), f.first) &&
                                                   parse_int(spec.substr(colon + 1), f.last);
  if (!ok)
    throw rt::SceneError("--frames expects N or A:B, frame numbers from 0 (got '" +
                         rt::clipped(spec) + "')");
  if (f.last < f.first)
    throw rt::SceneError("--frames " + spec + ": the last frame is before the first");
  if (f.last >= count)
    throw rt::SceneError("--frames " + spec + ": the scene has " + std::to_string(count) +
                         " frame" + (count == 1 ? "" : "s") + " (0.." + std::to_string(count - 1) +
                         ")" + (animated ? "" : "; it has no animation (docs/dynamic-scenes.md)"));
  return f;
}

Progress::Progress(int total, bool quiet) : total_(total), on_(!quiet && isatty(2) && total > 1) {}

void Progress::update(int done, double last_ms) {
  if (!on_) return;
  std::fprintf(stderr, "\rframe %d/%d %s %3d%%, %.1f ms", done, total_,
               progress_bar(done, total_).c_str(), total_ > 0 ? 100 * done / total_ : 100, last_ms);
  std::fflush(stderr);
}

void Progress::finish() {
  if (on_) std::fprintf(stderr, "\n");
}

std::string video_tool_missing() {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") == 0) return {};
  return "--video needs ffmpeg, which is not on the PATH (apt-get install ffmpeg); the frames "
         "themselves need no video";
}

void write_video(const std::string& pattern, int first, double fps, const std::string& video) {
  const std::string why = video_tool_missing();
  if (!why.empty()) throw rt::SceneError(why);
  // ffmpeg reads the same printf pattern; a GIF gets a palette made for it (Floyd-Steinberg).
  const bool gif = std::filesystem::path(video).extension() == ".gif";
  std::vector<std::string> args = {
      "ffmpeg",        "-loglevel",           "error", "-y",   "-framerate", std::to_string(fps),
      "-start_number", std::to_string(first), "-i",    pattern};
  if (gif) {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen[p];[b][p]paletteuse"});
  } else {
    // yuv420p plays everywhere, and needs even sizes.
    args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p"});
  }
  args.push_back(video);
  const pid_t pid = fork();
  if (pid < 0) throw rt::SceneError("--video: cannot start ffmpeg");
  if (pid == 0) {
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execvp("ffmpeg", argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw rt::SceneError("--video: ffmpeg failed writing " + video + " (its message is above)");
}

// The first write's error, shared by the writes that run on the thread and the caller.
struct FrameWriter::State {
  std::mutex mutex;
  std::exception_ptr error;
  int in_flight = 0;  // writes posted and not finished (wait_in_flight)
  std::condition_variable finished;
};

FrameWriter::FrameWriter() : s_(std::make_shared<State>()) {}

FrameWriter::~FrameWriter() {
  try {
    finish();
  } catch (...) {  // an error nobody asked for any more
  }
}

void FrameWriter::post(std::function<void()> write) {
  {
    std::lock_guard<std::mutex> lock(s_->mutex);
    ++s_->in_flight;
  }
  thread_.post([s = s_, write = std::move(write)] {
    bool dropped = false;
    {
      std::lock_guard<std::mutex> lock(s->mutex);
      dropped = s->error != nullptr;  // after a failure the rest are dropped
    }
    if (!dropped) {
      try {
        write();
      } catch (...) {
        std::lock_guard<std::mutex> lock(s->mutex);
        s->error = std::current_exception();
      }
    }
    // Counted finished however it ended: written, failed or dropped.
    std::lock_guard<std::mutex> lock(s->mutex);
    --s->in_flight;
    s->finished.notify_all();
  });
}

void FrameWriter::wait_in_flight(int n) {
  std::unique_lock<std::mutex> lock(s_->mutex);
  s_->finished.wait(lock, [&] { return s_->in_flight <= n; });
}

void FrameWriter::check() {
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(s_->mutex);
    error = s_->error;
  }
  if (error) std::rethrow_exception(error);
}

void FrameWriter::finish() {
  thread_.drain();
  std::exception_ptr error;
  {
    std::lock_guard<std::mutex> lock(s_->mutex);
    error = std::exchange(s_->error, nullptr);
  }
  if (error) std::rethrow_exception(error);
}

}  // namespace trace_cli
