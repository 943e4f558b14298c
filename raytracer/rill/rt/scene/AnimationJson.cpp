// Reading animation from a JSON scene (AnimationJson.h).
#include "rill/rt/scene/AnimationJson.h"

#include "rill/rt/scene/FramePattern.h"
#include "rill/rt/scene/NameList.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

namespace rt::json_fields {

namespace {

Interpolation interpolation(const Ctx& c, const json& j, const std::string& where) {
  if (!j.is_string()) fail(c, where + " must be \"linear\" or \"smooth\"");
  try {
    return parse_interpolation(j.get<std::string>());
  } catch (const std::invalid_argument& e) {
    fail(c, where + ": " + e.what());
  }
}

// A key's time, after the previous key's.
double key_time(const Ctx& c, const json& key, const std::string& where, size_t k, double prev) {
  if (!key.contains("time")) fail(c, where + " needs a \"time\" (seconds)");
  const double t = num_double(c, key["time"], where + ".time");
  if (k > 0 && !(t > prev)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  ": time %g is not after keys[%zu]'s %g (keys must be in time order)", t, k - 1,
                  prev);
    fail(c, where + buf);
  }
  return t;
}

const json& keys_of(const Ctx& c, const json& j, const std::string& where) {
  if (!j.contains("keys") || !j["keys"].is_array() || j["keys"].empty())
    fail(c, where + " needs \"keys\": an array of at least one key");
  return j["keys"];
}

// "rotate": {"axis": [x, y, z], "degrees": a} or "quaternion": [x, y, z, w].
glm::dquat rotation(const Ctx& c, const json& key, const std::string& where) {
  if (key.contains("rotate") && key.contains("quaternion"))
    fail(c, where + ": give \"rotate\" or \"quaternion\", not both");
  if (key.contains("rotate")) {
    const json& r = key["rotate"];
    const std::string w = where + ".rotate";
    check_keys(c, r, w, {"axis", "degrees"});
    if (!r.contains("axis") || !r.contains("degrees"))
      fail(c, w + " needs \"axis\" and \"degrees\"");
    const glm::dvec3 axis(vec3(c, r["axis"], w + ".axis"));
    if (!(glm::length(axis) > 0)) fail(c, w + ".axis must not be zero");
    const double deg = num_double(c, r["degrees"], w + ".degrees");
    return glm::angleAxis(glm::radians(deg), glm::normalize(axis));
  }
  if (key.contains("quaternion")) {
    const json& q = key["quaternion"];
    const std::string w = where + ".quaternion";
    if (!q.is_array() || q.size() != 4) fail(c, w + " must be an array of 4 numbers [x, y, z, w]");
    glm::dquat r(num_double(c, q[3], w + "[3]"), num_double(c, q[0], w + "[0]"),
                 num_double(c, q[1], w + "[1]"), num_double(c, q[2], w + "[2]"));
    const double l = glm::length(r);
    if (!(l > 0) || !std::isfinite(l)) fail(c, w + " must not be zero");
    return r / l;
  }
  return glm::dquat(1.0, 0.0, 0.0, 0.0);
}

// An instance's point p placed by its transform about its pivot: T(translate) T(pivot) R S
// T(-pivot) p, in binary32 as rotate((p - pivot) * scale) + translate + pivot. Without a pivot
// it is Transform::apply_point, bit for bit.
glm::vec3 placed(const Transform& t, const glm::vec3& pivot, const glm::vec3& p) {
  if (pivot == glm::vec3(0.0f)) return t.apply_point(p);
  return t.apply_point(p - pivot) + pivot;
}

// An instance's "material": the index of the named material in the scene, added the first
// time an instance names it.
int instance_material(const Ctx& c, Scene& s, const json& j, const std::string& where,
                      const std::map<std::string, Material>& materials,
                      std::map<std::string, int>& added) {
  if (!j.is_string()) fail(c, where + " must be a material name");
  const std::string name = j.get<std::string>();
  if (auto it = added.find(name); it != added.end()) return it->second;
  auto it = materials.find(name);
  if (it == materials.end()) {
    std::vector<std::string> known;
    for (const auto& named : materials) known.push_back(named.first);
    fail(c, where + ": unknown material '" + clipped(name) + "' (" +
                (known.empty() ? std::string("the file defines no materials")
                               : "materials: " + name_list(known)) +
                ")");
  }
  return added[name] = s.add_material(it->second);
}

}  // namespace

TimeRange time_range(const Ctx& c, const json& j) {
  check_keys(c, j, "animation", {"start", "end", "fps"});
  TimeRange r;
  if (j.contains("start")) r.start = num_double(c, j["start"], "animation.start");
  if (!j.contains("end")) fail(c, "animation needs an \"end\" time (seconds)");
  r.end = num_double(c, j["end"], "animation.end");
  if (j.contains("fps")) r.fps = num_double(c, j["fps"], "animation.fps");
  if (!(r.fps > 0 && r.fps <= 1000)) fail(c, "animation.fps must be in (0, 1000]");
  if (!(r.end > r.start)) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "animation: the time range is empty (end %g is not after start %g)", r.end,
                  r.start);
    fail(c, buf);
  }
  if ((r.end - r.start) * r.fps > 1e6) fail(c, "animation: more than a million frames");
  return r;
}

PoseTrack pose_track(const Ctx& c, const json& j, const std::string& where) {
  check_keys(c, j, where, {"keys", "interpolation"});
  PoseTrack track;
  if (j.contains("interpolation"))
    track.interpolation = interpolation(c, j["interpolation"], where + ".interpolation");
  const json& keys = keys_of(c, j, where);
  double prev = 0.0;
  for (size_t k = 0; k < keys.size(); ++k) {
    const std::string w = where + ".keys[" + std::to_string(k) + "]";
    const json& key = keys[k];
    check_keys(c, key, w, {"time", "translate", "rotate", "quaternion", "scale"});
    PoseKey pk;
    pk.time = prev = key_time(c, key, w, k, prev);
    if (key.contains("translate"))
      pk.pose.translate = glm::dvec3(vec3(c, key["translate"], w + ".translate"));
    pk.pose.rotation = rotation(c, key, w);
    if (key.contains("scale")) {
      pk.pose.scale = glm::dvec3(vec3_or_scalar(c, key["scale"], w + ".scale"));
      if (pk.pose.scale.x == 0 || pk.pose.scale.y == 0 || pk.pose.scale.z == 0)
        fail(c, w + ".scale must not be 0");
    }
    track.keys.push_back(pk);
  }
  return track;
}

CameraTrack camera_track(const Ctx& c, const json& camera, const Camera& base) {
  CameraTrack track;
  if (camera.contains("interpolation"))
    track.interpolation = interpolation(c, camera["interpolation"], "camera.interpolation");
  if (!camera.contains("keys")) return track;
  const json& keys = keys_of(c, camera, "camera");
  double prev = 0.0;
  for (size_t k = 0; k < keys.size(); ++k) {
    const std::string w = "camera.keys[" + std::to_string(k) + "]";
    const json& key = keys[k];
    check_keys(c, key, w, {"time", "eye", "look_at", "up", "fov_y"});
    CameraKey ck;
    ck.time = prev = key_time(c, key, w, k, prev);
    ck.camera.eye = key.contains("eye") ? vec3(c, key["eye"], w + ".eye") : base.eye;
    ck.camera.look_at =
        key.contains("look_at") ? vec3(c, key["look_at"], w + ".look_at") : base.look_at;
    ck.camera.up = key.contains("up") ? vec3(c, key["up"], w + ".up") : base.up;
    ck.camera.fov_y = key.contains("fov_y") ? num(c, key["fov_y"], w + ".fov_y") : base.fov_y;
    if (!(ck.camera.fov_y > 0 && ck.camera.fov_y < 180)) fail(c, w + ".fov_y must be in (0, 180)");
    track.keys.push_back(ck);
  }
  return track;
}

std::set<std::string> instances(const Ctx& c, Scene& s, const json& j, const MeshNames& meshes,
                                const std::map<std::string, Material>& materials) {
  if (!j.is_array()) fail(c, "instances must be an array");
  std::set<std::string> used;
  std::map<std::string, int> added;  // materials named by instances: name -> index
  for (size_t i = 0; i < j.size(); ++i) {
    const std::string where = "instances[" + std::to_string(i) + "]";
    const json& inst = j[i];
    check_keys(c, inst, where, {"mesh", "name", "transform", "pivot", "material", "animate"});
    if (!inst.contains("mesh") || !inst["mesh"].is_string())
      fail(c, where + " needs \"mesh\": the name of a mesh of \"meshes\"");
    const std::string name = inst["mesh"].get<std::string>();
    auto it = meshes.find(name);
    if (it == meshes.end()) {
      std::vector<std::string> known;
      for (const auto& [n, r] : meshes) known.push_back(n);
      fail(c, where + ".mesh: unknown object '" + clipped(name) + "' (named meshes: " +
                  (known.empty() ? "none; give a mesh a \"name\"" : name_list(known)) + ")");
    }
    used.insert(name);
    Transform t;
    if (inst.contains("transform")) t = transform(c, inst["transform"], where + ".transform");
    const glm::vec3 pivot =
        inst.contains("pivot") ? vec3(c, inst["pivot"], where + ".pivot") : glm::vec3(0.0f);
    const int material =
        inst.contains("material")
            ? instance_material(c, s, inst["material"], where + ".material", materials, added)
            : -1;
    const MeshRange r = it->second;
    check_room(c, s, r.count, where);  // before copying
    const size_t first = s.triangle_count();
    for (size_t k = r.first; k < r.first + r.count; ++k) {
      glm::vec3 p[3], n[3], col[3];
      glm::vec2 uv[3];
      for (int v = 0; v < 3; ++v) {
        const size_t at = 3 * k + static_cast<size_t>(v);
        p[v] = placed(t, pivot, s.positions[at]);
        if (!s.normals.empty()) n[v] = t.apply_normal(s.normals[at]);
        if (!s.colors.empty()) col[v] = s.colors[at];
        if (!s.texcoords.empty()) uv[v] = s.texcoords[at];
      }
      s.add_triangle(p[0], p[1], p[2], material >= 0 ? material : s.material[k],
                     s.normals.empty() ? nullptr : n, s.colors.empty() ? nullptr : col,
                     s.texcoords.empty() ? nullptr : uv);
    }
    // A deforming mesh's copies deform too: its shapes, moved by the instance's transform.
    const AnimatedObject* deforming = nullptr;
    for (const AnimatedObject& a : s.animation.objects)
      if (a.first == r.first && a.count == r.count && !a.shapes.empty()) deforming = &a;
    if (inst.contains("animate") || deforming != nullptr) {
      AnimatedObject o;
      o.name = where;
      if (inst.contains("name")) {
        if (!inst["name"].is_string()) fail(c, where + ".name must be a string");
        o.name = inst["name"].get<std::string>();
      }
      o.first = first;
      o.count = r.count;
      // The keys turn and scale the copy about its pivot where the transform put it; without
      // a pivot, about the scene's origin, as before instances had pivots.
      if (inst.contains("pivot")) o.pivot = glm::dvec3(placed(t, pivot, pivot));
      if (inst.contains("animate"))
        o.track = pose_track(c, inst["animate"], where + ".animate");
      else
        o.track.keys.push_back(PoseKey{});
      if (deforming != nullptr) {
        o.shape_fps = deforming->shape_fps;
        for (size_t k = 0; k < deforming->shapes.size(); ++k) {
          std::vector<glm::vec3> p(deforming->shapes[k].size()), n(p.size());
          for (size_t v = 0; v < p.size(); ++v) {
            p[v] = placed(t, pivot, deforming->shapes[k][v]);
            n[v] = t.apply_normal(deforming->shape_normals[k][v]);
          }
          o.shapes.push_back(std::move(p));
          o.shape_normals.push_back(std::move(n));
        }
      }
      s.animation.objects.push_back(std::move(o));
    }
  }
  return used;
}

TimeRange keys_time_range(const Animation& a) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const AnimatedObject& o : a.objects) {
    lo = std::min(lo, o.track.keys.front().time);
    hi = std::max(hi, o.track.keys.back().time);
  }
  if (!a.camera.keys.empty()) {
    lo = std::min(lo, a.camera.keys.front().time);
    hi = std::max(hi, a.camera.keys.back().time);
  }
  TimeRange r;
  r.start = std::isfinite(lo) ? lo : 0.0;
  // A sequence counts its files from the range's start, at its own rate or 24 fps.
  for (const AnimatedObject& o : a.objects)
    if (!o.shapes.empty())
      hi = std::max(hi, r.start + static_cast<double>(o.shapes.size() - 1) /
                                      (o.shape_fps > 0 ? o.shape_fps : 24.0));
  r.end = hi > r.start ? hi : r.start + 1.0;  // a single key: one second of it
  return r;
}

namespace {

struct Sequence {
  std::string pattern;  // the file path with its frame number
  int first = 0, last = 0;
  double fps = 0;
};

Sequence read_sequence(const Ctx& c, const json& mesh, const std::string& where) {
  Sequence q;
  const json& j = mesh["sequence"];
  const std::string w = where + ".sequence";
  check_keys(c, j, w, {"first", "last", "fps"});
  if (!mesh.contains("file") || !mesh["file"].is_string())
    fail(c, w + " needs \"file\": an OBJ path with the frame number, such as wave-%03d.obj");
  q.pattern = file_name(c, mesh["file"], where + ".file");
  bool numbered = false;
  try {
    numbered = has_frame_number(q.pattern, where + ".file");
  } catch (const SceneError& e) {
    fail(c, e.what());
  }
  if (!numbered)
    fail(c, where + ".file '" + q.pattern +
                "' needs one frame number, %d or %03d (a width of at most 20), for its "
                "\"sequence\"");
  if (!j.contains("last")) fail(c, w + " needs \"last\": the number of its last file");
  q.first = j.contains("first") ? integer(c, j["first"], w + ".first", 0, 99999999) : 0;
  q.last = integer(c, j["last"], w + ".last", 0, 99999999);
  if (q.last < q.first) fail(c, w + ": last is before first");
  if (q.last - q.first >= 100000) fail(c, w + ": more than 100000 files");
  if (j.contains("fps")) {
    q.fps = num_double(c, j["fps"], w + ".fps");
    if (!(q.fps > 0 && q.fps <= 1000)) fail(c, w + ".fps must be in (0, 1000]");
  }
  return q;
}

// A loaded OBJ file's corners as the scene keeps them, and their normals (the geometric normal
// cross(b - a, c - a) for a file without any, as Scene::add_triangle gives one).
void shape_of(const Scene& f, std::vector<glm::vec3>& pos, std::vector<glm::vec3>& nrm) {
  pos = f.positions;
  if (!f.normals.empty()) {
    nrm = f.normals;
    return;
  }
  nrm.resize(pos.size());
  for (size_t i = 0; i < pos.size(); i += 3) {
    const glm::vec3 g = glm::cross(pos[i + 1] - pos[i], pos[i + 2] - pos[i]);
    nrm[i] = nrm[i + 1] = nrm[i + 2] = g;
  }
}

}  // namespace

std::string sequence_file(const Ctx& c, const json& mesh, const std::string& where) {
  const Sequence q = read_sequence(c, mesh, where);
  return frame_path(q.pattern, q.first);
}

void load_sequence(const Ctx& c, const json& mesh, const std::string& where, AnimatedObject& o) {
  const Sequence q = read_sequence(c, mesh, where);
  ObjLoadOptions opt;
  if (mesh.contains("transform"))
    opt.transform = transform(c, mesh["transform"], where + ".transform");
  opt.input = c.input;
  std::vector<int32_t> first_corners, corners;
  o.shape_fps = q.fps;
  for (int k = q.first; k <= q.last; ++k) {
    std::filesystem::path p(frame_path(q.pattern, k));
    if (p.is_relative()) p = std::filesystem::path(c.base_dir) / p;
    corners.clear();
    opt.corners = k == q.first ? &first_corners : &corners;
    Scene f;
    try {
      f = load_obj(p.string(), opt);
    } catch (const SceneError& e) {  // a file missing or malformed: which sequence, which frame
      fail(c, where + ".sequence: file " + std::to_string(k) + " of " + std::to_string(q.first) +
                  ".." + std::to_string(q.last) + ": " + e.what());
    }
    if (f.triangle_count() != o.count)
      fail(c, where + ".sequence: " + p.filename().string() + " has " +
                  std::to_string(f.triangle_count()) + " triangles where " +
                  std::filesystem::path(frame_path(q.pattern, q.first)).filename().string() +
                  " has " + std::to_string(o.count) +
                  " (the files of a sequence keep their topology)");
    if (k > q.first && corners != first_corners) {
      size_t t = 0;
      while (t * 3 < corners.size() && corners[3 * t] == first_corners[3 * t] &&
             corners[3 * t + 1] == first_corners[3 * t + 1] &&
             corners[3 * t + 2] == first_corners[3 * t + 2])
        ++t;
      fail(c, where + ".sequence: " + p.filename().string() + ": triangle " + std::to_string(t) +
                  " uses other vertices than in the first file (the files of a sequence keep "
                  "their topology)");
    }
    o.shapes.emplace_back();
    o.shape_normals.emplace_back();
    shape_of(f, o.shapes.back(), o.shape_normals.back());
  }
}

}  // namespace rt::json_fields
