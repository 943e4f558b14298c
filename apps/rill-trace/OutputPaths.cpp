// Checks of the files a command writes (OutputPaths.h).
#include "OutputPaths.h"

#include <sys/stat.h>

#include <cctype>
#include <filesystem>
#include <map>

#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Scene.h"

namespace trace_cli {

namespace {

namespace fs = std::filesystem;

// Formats known by their extensions: an output named with one of these is taken to be meant
// in that format.
struct Format {
  const char* name;
  std::vector<std::string> extensions;
};

const std::vector<Format>& known_formats() {
  static const std::vector<Format> formats = {{"PNG", {".png"}},
                                              {"PFM", {".pfm"}},
                                              {"OpenEXR", {".exr"}},
                                              {"JSON", {".json"}},
                                              {"JPEG", {".jpg", ".jpeg"}},
                                              {"TIFF", {".tif", ".tiff"}},
                                              {"BMP", {".bmp"}},
                                              {"GIF", {".gif"}},
                                              {"WebP", {".webp"}},
                                              {"Radiance HDR", {".hdr"}},
                                              {"PPM", {".ppm", ".pgm", ".pnm", ".pbm"}},
                                              {"TGA", {".tga"}},
                                              {"OBJ", {".obj"}},
                                              {"MTL", {".mtl"}}};
  return formats;
}

// What each output option writes: a format above, or for --source and --save (a kernel's
// text, a render's running sums) something no known extension names.
const char* format_of(const std::string& option) {
  static const std::map<std::string, const char*> of = {
      {"--out", "PNG"},
      {"--pfm", "PFM"},
      {"--depth", "PFM"},
      {"--prim", "PFM"},
      {"--normal", "PFM"},
      {"--albedo", "PFM"},
      {"--exr", "OpenEXR"},
      {"--stats-json", "JSON"},
      {"--source", "the kernel source as text"},
      {"--save", "the running sums in rill-trace's own format"}};
  const auto it = of.find(option);
  return it == of.end() ? "its own format" : it->second;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

void check_output_format(const std::string& option, const std::string& path) {
  const std::string as_given = fs::path(path).extension().string();
  const std::string ext = lower(as_given);
  const std::string writes = format_of(option);
  for (const Format& f : known_formats())
    for (const std::string& e : f.extensions)
      if (e == ext && writes != f.name)
        throw rt::SceneError(option + " " + rt::clipped(path) + ": " + rt::clipped(as_given) +
                             " names " + f.name + ", but " + option + " writes " + writes +
                             " (the formats written: --out PNG; --pfm, --depth, --prim, --normal "
                             "and --albedo PFM; --exr OpenEXR; --stats-json JSON)");
}

std::string file_identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode)) return {};
    return "inode " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  }
  // Not there yet: where a write would put it, a dangling link followed as the writer follows
  // it, and the folders' links resolved.
  std::error_code ec;
  const fs::path target = rt::output_target(path);
  const fs::path resolved = fs::weakly_canonical(fs::absolute(target, ec), ec);
  return "path " + (ec ? fs::absolute(target).lexically_normal() : resolved).string();
}

void check_output_files(const std::vector<NamedFile>& outputs,
                        const std::vector<NamedFile>& inputs) {
  std::map<std::string, const NamedFile*> input_of;
  for (const NamedFile& in : inputs)
    if (std::string id = file_identity(in.path); !id.empty()) input_of.emplace(id, &in);
  std::map<std::string, const NamedFile*> output_of;
  for (const NamedFile& out : outputs) {
    const std::string id = file_identity(out.path);
    if (id.empty()) continue;
    if (const auto in = input_of.find(id); in != input_of.end())
      throw rt::SceneError(out.what + " " + rt::clipped(out.path) + " is " + in->second->what +
                           (in->second->path != out.path
                                ? " (" + rt::clipped(in->second->path) + ")"
                                : std::string()) +
                           ": an output never overwrites an input");
    const auto [it, fresh] = output_of.emplace(id, &out);
    if (fresh) continue;
    const NamedFile& first = *it->second;
    if (fs::path(first.path).lexically_normal() == fs::path(out.path).lexically_normal())
      throw rt::SceneError(first.what + " and " + out.what + " both name " + rt::clipped(out.path) +
                           ": one would overwrite the other");
    throw rt::SceneError(first.what + " " + rt::clipped(first.path) + " and " + out.what + " " +
                         rt::clipped(out.path) + " are one file: one would overwrite the other");
  }
}

}  // namespace trace_cli
