// The JSON scene format (docs/scene-format.md).
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

namespace {

using nlohmann::json;

struct Ctx {
  std::string file;  // for messages
  std::string base_dir;
};

[[noreturn]] void fail(const Ctx& c, const std::string& msg) {
  throw SceneError(c.file + ": " + msg);
}

void check_keys(const Ctx& c, const json& j, const std::string& where,
                std::initializer_list<const char*> allowed) {
  if (!j.is_object()) fail(c, where + " must be an object");
  for (auto it = j.begin(); it != j.end(); ++it) {
    bool ok = false;
    for (const char* a : allowed) ok = ok || it.key() == a;
    if (!ok) fail(c, where + ": unknown key '" + it.key() + "'");
  }
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
  return glm::vec3(num(c, j[0], where), num(c, j[1], where), num(c, j[2], where));
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

Material material(const Ctx& c, const std::string& name, const json& j) {
  const std::string where = "materials." + name;
  check_keys(c, j, where, {"diffuse", "specular", "shininess", "reflect", "transmit", "ior"});
  Material m;
  m.name = name;
  m.specular = glm::vec3(0.0f);
  if (j.contains("diffuse")) m.diffuse = vec3_or_scalar(c, j["diffuse"], where + ".diffuse");
  if (j.contains("specular")) m.specular = vec3_or_scalar(c, j["specular"], where + ".specular");
  if (j.contains("shininess")) m.shininess = num(c, j["shininess"], where + ".shininess");
  if (j.contains("reflect")) m.reflect = num(c, j["reflect"], where + ".reflect");
  if (j.contains("transmit")) m.transmit = num(c, j["transmit"], where + ".transmit");
  if (j.contains("ior")) m.ior = num(c, j["ior"], where + ".ior");
  return m;
}

std::vector<glm::vec3> points(const Ctx& c, const json& j, const std::string& where, size_t n) {
  if (!j.is_array() || j.size() != n)
    fail(c, where + " must be an array of " + std::to_string(n) + " points");
  std::vector<glm::vec3> p;
  for (size_t i = 0; i < n; ++i) p.push_back(vec3(c, j[i], where));
  return p;
}

void mesh(const Ctx& c, Scene& s, const json& j, size_t index,
          const std::map<std::string, Material>& materials) {
  const std::string where = "meshes[" + std::to_string(index) + "]";
  if (!j.is_object()) fail(c, where + " must be an object");
  Transform t;
  if (j.contains("transform")) t = transform(c, j["transform"], where + ".transform");
  const Material* mat = nullptr;
  if (j.contains("material")) {
    if (!j["material"].is_string()) fail(c, where + ".material must be a material name");
    auto it = materials.find(j["material"].get<std::string>());
    if (it == materials.end())
      fail(c, where + ".material '" + j["material"].get<std::string>() +
                  "' is not defined in materials");
    mat = &it->second;
  }
  if (j.contains("file")) {
    check_keys(c, j, where, {"file", "material", "transform"});
    if (!j["file"].is_string()) fail(c, where + ".file must be a path");
    std::filesystem::path p(j["file"].get<std::string>());
    if (p.is_relative()) p = std::filesystem::path(c.base_dir) / p;
    ObjLoadOptions o;
    o.transform = t;
    o.override_material = mat;
    s.append(load_obj(p.string(), o));
    return;
  }
  if (!j.contains("shape") || !j["shape"].is_string())
    fail(c, where + " needs \"file\" (an OBJ) or \"shape\" (box, sphere, quad, triangle, teapot)");
  const std::string shape = j["shape"].get<std::string>();
  Material grey;
  const int m = s.add_material(mat != nullptr ? *mat : grey);
  auto tp = [&](const glm::vec3& p) { return t.apply_point(p); };
  if (shape == "box") {
    check_keys(c, j, where, {"shape", "min", "max", "material", "transform", "inward"});
    glm::vec3 lo = j.contains("min") ? vec3(c, j["min"], where + ".min") : glm::vec3(-0.5f);
    glm::vec3 hi = j.contains("max") ? vec3(c, j["max"], where + ".max") : glm::vec3(0.5f);
    bool inward = j.contains("inward") && boolean(c, j["inward"], where + ".inward");
    add_box(s, lo, hi, m, t, inward);
  } else if (shape == "sphere") {
    check_keys(
        c, j, where,
        {"shape", "center", "radius", "slices", "stacks", "material", "transform", "smooth"});
    glm::vec3 ctr =
        j.contains("center") ? vec3(c, j["center"], where + ".center") : glm::vec3(0.0f);
    float r = j.contains("radius") ? num(c, j["radius"], where + ".radius") : 1.0f;
    if (!(r > 0)) fail(c, where + ".radius must be positive");
    int sl = j.contains("slices") ? integer(c, j["slices"], where + ".slices", 3, 4096) : 48;
    int st = j.contains("stacks") ? integer(c, j["stacks"], where + ".stacks", 2, 4096) : 24;
    bool smooth = !j.contains("smooth") || boolean(c, j["smooth"], where + ".smooth");
    Scene tmp;
    tmp.add_material(Material{});
    add_sphere(tmp, ctr, r, sl, st, 0, smooth);
    for (size_t i = 0; i < tmp.triangle_count(); ++i) {
      glm::vec3 n[3];
      const glm::vec3* np = nullptr;
      if (!tmp.normals.empty()) {
        for (int k = 0; k < 3; ++k) n[k] = t.apply_normal(tmp.normals[3 * i + k]);
        np = n;
      }
      s.add_triangle(tp(tmp.positions[3 * i]), tp(tmp.positions[3 * i + 1]),
                     tp(tmp.positions[3 * i + 2]), m, np);
    }
  } else if (shape == "quad") {
    check_keys(c, j, where, {"shape", "vertices", "material", "transform"});
    auto v = points(c, j.value("vertices", json()), where + ".vertices", 4);
    add_quad(s, tp(v[0]), tp(v[1]), tp(v[2]), tp(v[3]), m);
  } else if (shape == "triangle") {
    check_keys(c, j, where, {"shape", "vertices", "material", "transform"});
    auto v = points(c, j.value("vertices", json()), where + ".vertices", 3);
    s.add_triangle(tp(v[0]), tp(v[1]), tp(v[2]), m);
  } else if (shape == "teapot") {
    check_keys(c, j, where, {"shape", "subdivisions", "material", "transform", "smooth"});
    int n = j.contains("subdivisions")
                ? integer(c, j["subdivisions"], where + ".subdivisions", 1, 256)
                : 8;
    bool smooth = !j.contains("smooth") || boolean(c, j["smooth"], where + ".smooth");
    add_teapot(s, n, m, t, smooth);
  } else {
    fail(c, where + ".shape '" + shape + "' is unknown (box, sphere, quad, triangle, teapot)");
  }
}

}  // namespace

Scene parse_json_scene(const std::string& text, const std::string& base_dir,
                       const std::string& name) {
  Ctx c{name, base_dir};
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    auto p = msg.find("parse error");
    fail(c, "invalid JSON: " + (p == std::string::npos ? msg : msg.substr(p)));
  }
  try {
    check_keys(
        c, j, "scene",
        {"builtin", "camera", "image", "meshes", "materials", "lights", "background", "options"});
    Scene s;
    if (j.contains("builtin")) {
      if (!j["builtin"].is_string()) fail(c, "builtin must be a scene name");
      s = builtin_scene(j["builtin"].get<std::string>());
    }
    s.name = std::filesystem::path(name).stem().string();

    std::map<std::string, Material> materials;
    if (j.contains("materials")) {
      if (!j["materials"].is_object()) fail(c, "materials must be an object of named materials");
      for (auto it = j["materials"].begin(); it != j["materials"].end(); ++it)
        materials[it.key()] = material(c, it.key(), it.value());
    }
    if (j.contains("meshes")) {
      if (!j["meshes"].is_array()) fail(c, "meshes must be an array");
      for (size_t i = 0; i < j["meshes"].size(); ++i) mesh(c, s, j["meshes"][i], i, materials);
    }
    if (j.contains("lights")) {
      if (!j["lights"].is_array()) fail(c, "lights must be an array");
      s.lights.clear();
      for (size_t i = 0; i < j["lights"].size(); ++i) {
        const std::string where = "lights[" + std::to_string(i) + "]";
        const json& l = j["lights"][i];
        check_keys(c, l, where, {"position", "color"});
        Light light;
        if (!l.contains("position")) fail(c, where + " needs a position");
        light.position = vec3(c, l["position"], where + ".position");
        if (l.contains("color")) light.color = vec3_or_scalar(c, l["color"], where + ".color");
        s.lights.push_back(light);
      }
    }
    if (j.contains("background")) s.background = vec3_or_scalar(c, j["background"], "background");
    if (j.contains("image")) {
      const json& im = j["image"];
      check_keys(c, im, "image", {"width", "height"});
      if (im.contains("width")) s.width = integer(c, im["width"], "image.width", 1, 16384);
      if (im.contains("height")) s.height = integer(c, im["height"], "image.height", 1, 16384);
    }
    if (j.contains("options")) {
      const json& o = j["options"];
      check_keys(c, o, "options",
                 {"shadows", "ambient", "max_depth", "grid", "grid_density", "subgrids", "spp",
                  "smooth_normals"});
      if (o.contains("shadows")) s.options.shadows = boolean(c, o["shadows"], "options.shadows");
      if (o.contains("ambient")) s.options.ambient = num(c, o["ambient"], "options.ambient");
      if (o.contains("max_depth"))
        s.options.max_depth = integer(c, o["max_depth"], "options.max_depth", 0, 64);
      if (o.contains("spp")) s.options.spp = integer(c, o["spp"], "options.spp", 1, 4096);
      if (o.contains("smooth_normals"))
        s.options.smooth_normals = boolean(c, o["smooth_normals"], "options.smooth_normals");
      if (o.contains("grid")) {
        if (o["grid"].is_string() && o["grid"].get<std::string>() == "auto")
          s.options.grid = 0;
        else
          s.options.grid = integer(c, o["grid"], "options.grid", 1, 512);
      }
      if (o.contains("grid_density")) {
        const double d = num(c, o["grid_density"], "options.grid_density");
        if (!(d >= kGridDensityMin && d <= kGridDensityMax))
          fail(c, "options.grid_density must be in [0.125, 256] (voxels per triangle)");
        s.options.grid_density = d;
      }
      if (o.contains("subgrids")) {
        if (o["subgrids"].is_string() && o["subgrids"].get<std::string>() == "off")
          s.options.subgrid_min = 0;
        else
          s.options.subgrid_min = integer(c, o["subgrids"], "options.subgrids", 1, 1 << 20);
      }
    }
    if (j.contains("camera")) {
      const json& cam = j["camera"];
      check_keys(c, cam, "camera", {"eye", "look_at", "up", "fov_y"});
      Camera k = s.camera;
      if (cam.contains("eye")) k.eye = vec3(c, cam["eye"], "camera.eye");
      if (cam.contains("look_at")) k.look_at = vec3(c, cam["look_at"], "camera.look_at");
      if (cam.contains("up")) k.up = vec3(c, cam["up"], "camera.up");
      if (cam.contains("fov_y")) k.fov_y = num(c, cam["fov_y"], "camera.fov_y");
      s.camera = k;
      s.has_camera = true;
    }
    if (!s.has_camera) {
      s.camera = default_camera(s);
      s.has_camera = true;
    }
    try {
      s.validate();
    } catch (const SceneError& e) {
      fail(c, e.what());
    }
    return s;
  } catch (const nlohmann::json::exception& e) {
    fail(c, std::string("invalid scene: ") + e.what());
  }
}

Scene load_json(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw SceneError(path + ": no such file");
  if (fs::is_directory(path, ec)) throw SceneError(path + ": is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_json_scene(text.str(), fs::path(path).parent_path().string(), path);
}

}  // namespace rt
