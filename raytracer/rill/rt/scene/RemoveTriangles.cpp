// Removing triangle ranges from a scene (RemoveTriangles.h).
#include "rill/rt/scene/RemoveTriangles.h"

#include <algorithm>
#include <string>

namespace rt {

namespace {

// Keeps the elements of `v` (`per` of them per triangle) of the triangles that `keep` says.
template <class T>
void keep_triangles(std::vector<T>& v, size_t per, const std::vector<bool>& keep) {
  if (v.empty()) return;
  size_t to = 0;
  for (size_t t = 0; t < keep.size(); ++t)
    if (keep[t])
      for (size_t k = 0; k < per; ++k) v[to++] = v[per * t + k];
  v.resize(to);
}

}  // namespace

void remove_triangles(Scene& s, std::vector<TriangleRange> ranges) {
  const size_t n = s.triangle_count();
  std::sort(ranges.begin(), ranges.end(),
            [](const TriangleRange& a, const TriangleRange& b) { return a.first < b.first; });
  std::vector<bool> keep(n, true);
  for (size_t i = 0; i < ranges.size(); ++i) {
    const TriangleRange& r = ranges[i];
    if (r.first > n || r.count > n - r.first ||
        (i > 0 && r.first < ranges[i - 1].first + ranges[i - 1].count))
      throw SceneError("remove_triangles: triangles " + std::to_string(r.first) + ".." +
                       std::to_string(r.first + r.count) +
                       " overlap another range or are not in the scene");
    std::fill(keep.begin() + static_cast<std::ptrdiff_t>(r.first),
              keep.begin() + static_cast<std::ptrdiff_t>(r.first + r.count), false);
  }
  // The triangles removed before each kept one: its id moves down by that many.
  std::vector<size_t> removed_before(n + 1, 0);
  for (size_t t = 0; t < n; ++t) removed_before[t + 1] = removed_before[t] + (keep[t] ? 0 : 1);
  std::vector<AnimatedObject> objects;
  for (AnimatedObject& o : s.animation.objects) {
    if (o.first > n || o.count > n - o.first)
      throw SceneError("remove_triangles: animated object '" + clipped(o.name) +
                       "' is not in the scene");
    const size_t gone = removed_before[o.first + o.count] - removed_before[o.first];
    if (gone == o.count && o.count > 0) continue;  // removed with its mesh
    if (gone != 0)
      throw SceneError("remove_triangles: animated object '" + clipped(o.name) +
                       "' is only partly in a removed range");
    o.first -= removed_before[o.first];
    objects.push_back(std::move(o));
  }
  s.animation.objects = std::move(objects);
  keep_triangles(s.positions, 3, keep);
  keep_triangles(s.normals, 3, keep);
  keep_triangles(s.colors, 3, keep);
  keep_triangles(s.texcoords, 3, keep);
  keep_triangles(s.material, 1, keep);
}

}  // namespace rt
