// Checked JSON field readers (JsonFields.h).
#include "rill/rt/scene/JsonFields.h"

#include <cmath>

namespace rt::json_fields {

[[noreturn]] void fail(const Ctx& c, const std::string& msg) {
  // The message may quote the user's keys and names: clipped, so one line stays one line.
  throw SceneError(c.file + ": " + clipped(msg, 400));
}

void check_keys(const Ctx& c, const json& j, const std::string& where,
                std::initializer_list<const char*> allowed) {
  if (!j.is_object()) fail(c, where + " must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) {
      // The keys this object takes, as a material's error lists its shader's: a misspelt key
      // is fixed from the message, without the docs.
      std::string keys;
      for (const char* a : allowed) keys += (keys.empty() ? "" : ", ") + std::string(a);
      fail(c, where + ": unknown key '" + clipped(it.key()) + "' (" + keys + ")");
    }
  }
}

std::string file_name(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_string()) fail(c, where + " must be a path");
  std::string name = j.get<std::string>();
  if (const size_t nul = name.find('\0'); nul != std::string::npos)
    fail(c, where + " has a NUL character (at byte " + std::to_string(nul) +
                "): a file name cannot; the system would read it as '" + name.substr(0, nul) + "'");
  return name;
}

float num(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_number()) fail(c, where + " must be a number");
  double v = j.get<double>();
  if (!std::isfinite(v) || std::fabs(v) > 3.0e38) fail(c, where + " must be a finite number");
  return static_cast<float>(v);
}

int integer(const Ctx& c, const json& j, const std::string& where, int lo, int hi) {
  if (!j.is_number_integer() && !(j.is_number() && std::floor(j.get<double>()) == j.get<double>()))
    fail(c, where + " must be an integer");
  double v = j.get<double>();
  if (!(v >= lo && v <= hi))
    fail(c, where + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

bool boolean(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_boolean()) fail(c, where + " must be true or false");
  return j.get<bool>();
}

glm::vec3 vec3(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) fail(c, where + " must be an array of 3 numbers");
  return glm::vec3(num(c, j[0], where + "[0]"), num(c, j[1], where + "[1]"),
                   num(c, j[2], where + "[2]"));
}

// A number gives a grey colour / uniform scale.
glm::vec3 vec3_or_scalar(const Ctx& c, const json& j, const std::string& where) {
  if (j.is_number()) return glm::vec3(num(c, j, where));
  return vec3(c, j, where);
}

Transform transform(const Ctx& c, const json& j, const std::string& where) {
  check_keys(c, j, where, {"translate", "scale", "rotate_x", "rotate_y", "rotate_z"});
  Transform t;
  if (j.contains("translate")) t.translate = vec3(c, j["translate"], where + ".translate");
  if (j.contains("scale")) {
    t.scale = vec3_or_scalar(c, j["scale"], where + ".scale");
    if (t.scale.x == 0 || t.scale.y == 0 || t.scale.z == 0) fail(c, where + ".scale must not be 0");
  }
  if (j.contains("rotate_x")) t.rotate_deg.x = num(c, j["rotate_x"], where + ".rotate_x");
  if (j.contains("rotate_y")) t.rotate_deg.y = num(c, j["rotate_y"], where + ".rotate_y");
  if (j.contains("rotate_z")) t.rotate_deg.z = num(c, j["rotate_z"], where + ".rotate_z");
  return t;
}

double num_double(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_number()) fail(c, where + " must be a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(c, where + " must be a finite number");
  return v;
}

void check_room(const Ctx& c, const Scene& s, size_t more, const std::string& where) {
  if (s.triangle_count() + more > kMaxTriangles)
    fail(c, where + ": it would make " + std::to_string(s.triangle_count() + more) +
                " triangles; at most " + std::to_string(kMaxTriangles) + " are supported");
}

}  // namespace rt::json_fields
