// The animation parts of a JSON scene file (docs/scene-format.md, "Animation"): the time
// range, a mesh's or an instance's "animate" keys, the camera's "keys", and "instances" (copies
// of a named mesh). Errors name the file and the key: "scene.json: meshes[1].animate.keys[2]:
// time 0.5 is not after keys[1]'s 1 (keys must be in time order)".
#pragma once

#include <map>
#include <set>
#include <string>

#include "rill/rt/scene/Animation.h"
#include "rill/rt/scene/JsonFields.h"

namespace rt::json_fields {

// A named mesh's triangles [first, first + count) in the scene.
struct MeshRange {
  size_t first = 0, count = 0;
};
using MeshNames = std::map<std::string, MeshRange>;

// "animation": {"start", "end", "fps"}.
TimeRange time_range(const Ctx& c, const json& j);
// "animate": {"keys": [...], "interpolation": "linear" | "smooth"}.
PoseTrack pose_track(const Ctx& c, const json& j, const std::string& where);
// The camera's "keys" (and "interpolation"): a key's missing fields are `base`'s.
CameraTrack camera_track(const Ctx& c, const json& camera, const Camera& base);
// Appends the instances of "instances": copies of a named mesh's triangles, placed by the
// instance's "transform" about its "pivot" (T(translate) T(pivot) R S T(-pivot)), with its
// "material" (a name of `materials`) on every face if it gives one, and animated by its
// "animate" (about the pivot as placed, when it gives one). Returns the names of the meshes
// it copied.
std::set<std::string> instances(const Ctx& c, Scene& s, const json& j, const MeshNames& meshes,
                                const std::map<std::string, Material>& materials);
// The time range of an animated scene whose file gives none: from its first key to its last
// (and to the end of its OBJ sequences), at 24 frames per second.
TimeRange keys_time_range(const Animation& a);

// A deforming mesh: the mesh entry `mesh` (in the scene as its triangles
// [o.first, o.first + o.count), loaded from the sequence's first file) has "file": a path
// with a frame number (%d, %03d) and "sequence": {"first", "last", "fps"}. Loads every file
// of the sequence into o.shapes (positions after the mesh's transform) and o.shape_normals;
// a file whose faces use other vertices than the first file's (or another count) is an error
// naming it. Returns the first file's path, for the mesh itself, when `load` is false.
std::string sequence_file(const Ctx& c, const json& mesh, const std::string& where);
void load_sequence(const Ctx& c, const json& mesh, const std::string& where, AnimatedObject& o);

}  // namespace rt::json_fields
