// What the scene fuzzers do with a scene once a loader accepted it: the checks and the
// build that `rill-trace render` runs before it compiles a kernel (validate, the materials
// against their shaders as a Tracer resolves them, the grid at the scene's own settings). Any
// exception other than the loaders' own errors (rt::SceneError, and std::runtime_error from the
// image readers) escapes and is a finding: the fuzzer stops with the input that caused it.
#pragma once

#include <rill/rt/accel/Grid.h>
#include <rill/rt/scene/Scene.h>
#include <rill/rt/shaders/Registry.h>

#include <stdlib.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>

namespace rill::fuzz {

inline void build_up_to_grid(rt::Scene& s) {
  // A grid budget of 16 MiB (about 88^3 voxels): scenes that ask for more are refused with the
  // error users get over their machine's limit, instead of every fuzz input with
  // "grid": 512 taking seconds and gigabytes (build_grid's memory check).
  static const bool budget = (setenv("RILL_MAX_GRID_MB", "16", /*overwrite=*/0), true);
  (void)budget;
  s.validate();
  (void)rt::resolve_shaders(s);
  // The CPU backends' settings, without starting a backend (subgrid_min_for would ask it).
  const int32_t sub =
      s.options.subgrid_min == rt::kSubgridsAuto ? rt::kSubgridMin : s.options.subgrid_min;
  rt::build_grid(s, s.options.grid, sub, s.options.grid_density);
}

// A 2x2 8-bit RGB PNG, for the scratch folders' textures.
inline constexpr unsigned char kTinyPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd,
    0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8,
    0xcf, 0xc0, 0xc0, 0x00, 0xc2, 0x0c, 0xff, 0x81, 0x00, 0x00, 0x1f, 0xee, 0x05, 0xfb, 0x0b,
    0xd9, 0x68, 0x8b, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// A folder of this process's own under the system's temporary folder (removed at exit), for
// fuzzers that exercise the loaders' file paths: parallel fuzzing jobs do not share it. It
// holds t.png (kTinyPng) for the textures inputs name.
class ScratchDir {
 public:
  ScratchDir() {
    path_ = std::filesystem::temp_directory_path() / ("rill-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(path_);
    write("t.png", reinterpret_cast<const char*>(kTinyPng), sizeof kTinyPng);
  }
  ScratchDir(const ScratchDir&) = delete;  // one owner removes the folder
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string dir() const { return path_.string(); }
  void write(const std::string& name, const char* data, size_t size) const {
    std::ofstream(file(name), std::ios::binary | std::ios::trunc)
        .write(data, static_cast<std::streamsize>(size));
  }

 private:
  std::filesystem::path path_;
};

}  // namespace rill::fuzz
