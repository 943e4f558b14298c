// Checked reads of input files (InputFile.h).
#include "rill/rt/scene/InputFile.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

std::string megabytes(uint64_t bytes) {
  std::ostringstream s;
  s.precision(3);
  s << static_cast<double>(bytes) / (1024.0 * 1024.0) << " MiB";
  return s.str();
}

thread_local InputFileLog* t_log = nullptr;  // the innermost log of this thread

}  // namespace

InputFileLog::InputFileLog() : outer_(t_log) {
  t_log = this;
}

InputFileLog::~InputFileLog() {
  t_log = outer_;
}

uint64_t max_input_bytes() {
  constexpr uint64_t kDefault = uint64_t{4} << 30;
  const char* env = std::getenv("RILL_MAX_INPUT_MB");
  if (env == nullptr || *env == '\0') return kDefault;
  char* end = nullptr;
  const unsigned long long mb = std::strtoull(env, &end, 10);
  if (*end != '\0' || mb < 1 || mb > (uint64_t{1} << 30))
    throw SceneError(std::string("RILL_MAX_INPUT_MB='") + env +
                     "' is not a size in MiB (1..1073741824)");
  return static_cast<uint64_t>(mb) << 20;
}

uint64_t check_input_file(const std::string& path, const std::string& kind) {
  namespace fs = std::filesystem;
  if (const size_t nul = path.find('\0'); nul != std::string::npos)
    throw SceneError(clipped(path) + ": a file name with a NUL character (at byte " +
                     std::to_string(nul) + "); the system would read it as '" +
                     clipped(path.substr(0, nul)) + "', another file");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) throw SceneError(path + ": no such file");
  if (fs::is_directory(st)) throw SceneError(path + ": is a directory, not " + kind);
  if (!fs::is_regular_file(st))
    throw SceneError(path + ": is not a regular file (a device, pipe or socket), not " + kind +
                     "; input is read from regular files only");
  const uint64_t size = fs::file_size(path, ec);
  if (ec) throw SceneError(path + ": cannot read its size: " + ec.message());
  const uint64_t limit = max_input_bytes();
  if (size > limit)
    throw SceneError(path + ": " + megabytes(size) + ", over the input limit of " +
                     megabytes(limit) + " per file (RILL_MAX_INPUT_MB raises it)");
  return size;
}

std::string read_input_file(const std::string& path, const std::string& kind) {
  const uint64_t size = check_input_file(path, kind);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open for reading: " + std::strerror(errno));
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  // A file that changed size while being read: keep what was there.
  text.resize(static_cast<size_t>(in.gcount()));
  if (in.bad()) throw SceneError(path + ": read error");
  for (InputFileLog* log = t_log; log != nullptr; log = log->outer_) log->paths_.push_back(path);
  return text;
}

}  // namespace rt
