// assimp reading through Rill's input files (AssimpFile.h).
#include "rill/rt/scene/AssimpFile.h"

#include <assimp/MemoryIOWrapper.h>
#include <assimp/DefaultLogger.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/LogStream.hpp>

#include <cstring>
#include <filesystem>
#include <mutex>
#include <new>

#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// assimp's file access: each file read whole by read_input_file into a memory stream. The
// first refusal is kept, since assimp's own message for it only says it could not open a file.
class InputFileSystem : public Assimp::IOSystem {
 public:
  bool Exists(const char* file) const override {
    std::error_code ec;
    return std::filesystem::is_regular_file(file, ec);
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::strchr(mode, 'w') != nullptr || std::strchr(mode, 'a') != nullptr) return nullptr;
    std::string bytes;
    try {
      bytes = read_input_file(file, "a file the mesh file names");
    } catch (const SceneError& e) {
      if (refusal.empty()) refusal = e.what();
      return nullptr;
    }
    // MemoryIOStream frees its buffer with delete[] when it owns it.
    auto* buffer = new uint8_t[bytes.size() + 1];
    std::memcpy(buffer, bytes.data(), bytes.size());
    return new Assimp::MemoryIOStream(buffer, bytes.size(), /*own=*/true);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
  std::string refusal;
};

// assimp's log lines at warning level and above, without its "Warn,  T0: " prefix.
class LogLines : public Assimp::LogStream {
 public:
  explicit LogLines(std::vector<std::string>& lines) : lines_(lines) {}
  void write(const char* message) override {
    std::string m = message;
    const size_t colon = m.find(": ");
    if (colon != std::string::npos && colon < 16) m.erase(0, colon + 2);
    while (!m.empty() && (m.back() == '\n' || m.back() == '\r')) m.pop_back();
    if (!m.empty()) lines_.push_back(m);
  }

 private:
  std::vector<std::string>& lines_;
};

// assimp's log is one per process (DefaultLogger): reads take turns, each listening to it
// while it reads. A program that made its own logger keeps it (ours is attached beside it).
std::mutex& log_mutex() {
  static std::mutex m;
  return m;
}

class Listening {
 public:
  explicit Listening(std::vector<std::string>& lines) : lock_(log_mutex()), stream_(lines) {
    if (Assimp::DefaultLogger::isNullLogger()) {
      Assimp::DefaultLogger::create(nullptr, Assimp::Logger::NORMAL, 0);
      made_ = true;
    }
    Assimp::DefaultLogger::get()->attachStream(&stream_,
                                               Assimp::Logger::Warn | Assimp::Logger::Err);
  }
  ~Listening() {
    Assimp::DefaultLogger::get()->detachStream(&stream_,
                                               Assimp::Logger::Warn | Assimp::Logger::Err);
    if (made_) Assimp::DefaultLogger::kill();
  }
  Listening(const Listening&) = delete;
  Listening& operator=(const Listening&) = delete;

 private:
  std::lock_guard<std::mutex> lock_;
  LogLines stream_;
  bool made_ = false;
};

}  // namespace

AssimpFile::AssimpFile(const std::string& path, const std::string& kind) {
  Listening listening(log_);
  auto* io = new InputFileSystem;
  importer_.SetIOHandler(io);  // the importer owns it from here
  try {
    scene_ = importer_.ReadFile(path, 0);
  } catch (const std::bad_alloc&) {
    throw SceneError(path + ": assimp ran out of memory reading it as " + kind);
  } catch (const std::exception& e) {
    throw SceneError(path + ": assimp cannot read it as " + kind + ": " + clipped(e.what(), 200));
  }
  if (scene_ == nullptr) {
    std::string why = importer_.GetErrorString();
    if (!io->refusal.empty()) why = io->refusal + (why.empty() ? "" : " (" + why + ")");
    throw SceneError(path + ": assimp cannot read it as " + kind + ": " +
                     (why.empty() ? "no reason given" : clipped(why, 300)));
  }
}

}  // namespace rt
