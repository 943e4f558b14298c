// Reading the fields of a JSON scene file (docs/scene-format.md): numbers, vectors, flags
// and transforms, each checked, with errors that name the file and the field
// ("scene.json: meshes[2].transform.scale must not be 0"). Shared by the scene reader
// (SceneJson.cpp) and the animation reader (AnimationJson.h).
#pragma once

#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>

#include "rill/rt/scene/Scene.h"

namespace rt::json_fields {

using nlohmann::json;

// Where the values come from.
struct Ctx {
  std::string file;  // for messages
  std::string base_dir;
  InputOptions input;  // for the OBJ files it names
};

// Throws SceneError "FILE: msg" (msg clipped to one line).
[[noreturn]] void fail(const Ctx& c, const std::string& msg);
// j is an object whose keys are all in `allowed`.
void check_keys(const Ctx& c, const json& j, const std::string& where,
                std::initializer_list<const char*> allowed);
// A string that names a file (a mesh's OBJ, a texture's PNG, a sequence's pattern), as
// written. A NUL character in it (JSON's \u0000) is an error naming the key: the system would
// read the name only up to it, and load another file.
std::string file_name(const Ctx& c, const json& j, const std::string& where);
float num(const Ctx& c, const json& j, const std::string& where);          // finite, float range
double num_double(const Ctx& c, const json& j, const std::string& where);  // finite
int integer(const Ctx& c, const json& j, const std::string& where, int lo, int hi);
bool boolean(const Ctx& c, const json& j, const std::string& where);
glm::vec3 vec3(const Ctx& c, const json& j, const std::string& where);
// A number gives a grey colour / uniform scale.
glm::vec3 vec3_or_scalar(const Ctx& c, const json& j, const std::string& where);
Transform transform(const Ctx& c, const json& j, const std::string& where);
// Adding `more` triangles keeps the scene within kMaxTriangles; checked before a shape is made
// or an instance copied: a few numbers in the JSON could otherwise ask for more triangles than
// there is memory for.
void check_room(const Ctx& c, const Scene& s, size_t more, const std::string& where);

}  // namespace rt::json_fields
