// Running sums on disk (AccumulationFile.h).
#include "rill/rt/film/AccumulationFile.h"

#include <cstring>
#include <fstream>
#include <vector>

#include "rill/rt/scene/OutputFile.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

// RILLACC1: the sums and carries; RILLACC2: then the sums of squares too (a render saved with
// its variance, which a resumed render goes on adding to).
constexpr char kMagic[8] = {'R', 'I', 'L', 'L', 'A', 'C', 'C', '1'};
constexpr char kMagicSquares[8] = {'R', 'I', 'L', 'L', 'A', 'C', 'C', '2'};

struct Header {
  char magic[8];
  uint64_t hash;
  uint32_t seed;
  int32_t width, height, samples;
};
static_assert(sizeof(Header) == 32);

}  // namespace

void write_accumulation(const std::string& path, const Accumulation& a,
                        const AccumulationKey& key) {
  const size_t n = static_cast<size_t>(a.width) * static_cast<size_t>(a.height);
  if (a.sum.size() != n || a.carry.size() != n || (!a.squares.empty() && a.squares.size() != n))
    throw SceneError(path + ": the accumulation's sums do not match its size");
  Header h{};
  std::memcpy(h.magic, a.squares.empty() ? kMagic : kMagicSquares, sizeof kMagic);
  h.hash = key.scene_hash;
  h.seed = key.seed;
  h.width = a.width;
  h.height = a.height;
  h.samples = a.samples;
  write_output_file(path, [&](OutputSink& out) {
    out.write(&h, sizeof h);
    out.write(a.sum.data(), n * sizeof(glm::vec3));
    out.write(a.carry.data(), n * sizeof(glm::vec3));
    if (!a.squares.empty()) out.write(a.squares.data(), n * sizeof(glm::vec3));
  });
}

Accumulation read_accumulation(const std::string& path, const AccumulationKey& key, int width,
                               int height) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw SceneError(path + ": cannot open the render to resume");
  Header h{};
  f.read(reinterpret_cast<char*>(&h), sizeof h);
  const bool squares = f && std::memcmp(h.magic, kMagicSquares, sizeof kMagic) == 0;
  if (!f || (!squares && std::memcmp(h.magic, kMagic, sizeof kMagic) != 0))
    throw SceneError(path + ": not a render saved by rill-trace --save");
  if (h.seed != key.seed)
    throw SceneError(path + ": saved with seed " + std::to_string(h.seed) + ", the scene's is " +
                     std::to_string(key.seed));
  if (h.width != width || h.height != height)
    throw SceneError(path + ": saved at " + std::to_string(h.width) + "x" +
                     std::to_string(h.height) + ", the render is " + std::to_string(width) + "x" +
                     std::to_string(height));
  if (h.hash != key.scene_hash)
    throw SceneError(path +
                     ": saved from another scene or with other render settings (accuracy, knobs, "
                     "max_depth, options)");
  if (h.samples < 1 || h.samples > kMaxSpp)
    throw SceneError(path + ": holds " + std::to_string(h.samples) + " samples per pixel");
  Accumulation a;
  a.width = width;
  a.height = height;
  a.samples = h.samples;
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  a.sum.resize(n);
  a.carry.resize(n);
  f.read(reinterpret_cast<char*>(a.sum.data()),
         static_cast<std::streamsize>(n * sizeof(glm::vec3)));
  f.read(reinterpret_cast<char*>(a.carry.data()),
         static_cast<std::streamsize>(n * sizeof(glm::vec3)));
  if (squares) {
    a.squares.resize(n);
    f.read(reinterpret_cast<char*>(a.squares.data()),
           static_cast<std::streamsize>(n * sizeof(glm::vec3)));
  }
  if (!f)
    throw SceneError(path + ": cut short (" + std::to_string(h.samples) + " samples of " +
                     std::to_string(width) + "x" + std::to_string(height) + " expected)");
  if (f.peek() != std::char_traits<char>::eof())
    throw SceneError(path + ": has bytes after its sums");
  return a;
}

}  // namespace rt
