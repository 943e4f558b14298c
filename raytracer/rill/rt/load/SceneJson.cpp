// The JSON scene format (docs/scene-format.md): textures, materials with their shaders'
// parameters, meshes and shapes, lights, camera, image and options.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "rill/rt/kernel/Shader.h"
#include "rill/rt/load/JsonStructure.h"
#include "rill/rt/load/LightJson.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/AnimationJson.h"
#include "rill/rt/scene/CameraJson.h"
#include "rill/rt/scene/ClassicMaterial.h"
#include "rill/rt/scene/InputFile.h"
#include "rill/rt/scene/JsonFields.h"
#include "rill/rt/scene/MeshFile.h"
#include "rill/rt/scene/NameList.h"
#include "rill/rt/scene/RemoveTriangles.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/shaders/Registry.h"

namespace rt {

namespace {

using nlohmann::json;
using namespace json_fields;

// ---- textures and materials ----------------------------------------------------------------

// Texture names of the file's "textures" -> index in Scene::textures.
using TextureNames = std::map<std::string, int>;

std::string join(const std::vector<std::string>& names) {
  std::string all;
  for (const std::string& n : names) all += (all.empty() ? "" : ", ") + n;
  return all;
}

void textures(const Ctx& c, Scene& s, const json& j, TextureNames& names) {
  if (!j.is_object()) fail(c, "textures must be an object of named textures");
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string where = "textures." + it.key();
    const json& t = it.value();
    if (!t.is_object()) fail(c, where + " must be an object");
    std::string type = "bitmap";
    if (t.contains("type")) {
      if (!t["type"].is_string()) fail(c, where + ".type must be a texture type");
      type = t["type"].get<std::string>();
    }
    const auto& procedural = procedural_texture_types();
    Texture tex;
    if (type == "bitmap") {
      check_keys(c, t, where, {"type", "file", "wrap", "filter", "srgb"});
      if (!t.contains("file") || !t["file"].is_string())
        fail(c, where + ".file must be the path of a PNG file");
      std::filesystem::path p(file_name(c, t["file"], where + ".file"));
      if (p.is_relative()) p = std::filesystem::path(c.base_dir) / p;
      const bool srgb = !t.contains("srgb") || boolean(c, t["srgb"], where + ".srgb");
      try {
        tex = load_png_texture(p.string(), srgb);
      } catch (const SceneError& e) {
        fail(c, where + ".file: " + e.what());
      }
      if (t.contains("wrap")) {
        if (!t["wrap"].is_string()) fail(c, where + ".wrap must be repeat, clamp or mirror");
        try {
          tex.wrap = parse_wrap_mode(t["wrap"].get<std::string>());
        } catch (const std::invalid_argument& e) {
          fail(c, where + ".wrap: " + e.what());
        }
      }
      if (t.contains("filter")) {
        const json& f = t["filter"];
        if (!f.is_string() ||
            (f.get<std::string>() != "bilinear" && f.get<std::string>() != "nearest"))
          fail(c, where + ".filter must be \"bilinear\" or \"nearest\"");
        tex.bilinear = f.get<std::string>() == "bilinear";
      }
    } else if (std::find(procedural.begin(), procedural.end(), type) != procedural.end()) {
      check_keys(c, t, where, {"type", "color1", "color2", "scale"});
      tex.type = type;
      if (t.contains("color1")) tex.color1 = vec3_or_scalar(c, t["color1"], where + ".color1");
      if (t.contains("color2")) tex.color2 = vec3_or_scalar(c, t["color2"], where + ".color2");
      if (t.contains("scale")) tex.scale = num(c, t["scale"], where + ".scale");
      if (!(tex.scale > 0.0f) || tex.scale > kMaxTextureScale)
        fail(c, where + ".scale must be in (0, 1e6]");
    } else {
      fail(c,
           where + ".type: unknown texture type '" + type + "' (bitmap, " + join(procedural) + ")");
    }
    tex.name = it.key();
    s.textures.push_back(std::move(tex));
    names[it.key()] = static_cast<int>(s.textures.size()) - 1;
  }
}

// A colour parameter: a number (grey), [r, g, b], or {"texture": NAME}.
ParamValue colour(const Ctx& c, const json& j, const std::string& where,
                  const TextureNames& names) {
  if (j.is_number() || (j.is_array() && j.size() == 3))
    return ParamValue::of(vec3_or_scalar(c, j, where));
  if (j.is_object() && j.size() == 1 && j.contains("texture") && j["texture"].is_string()) {
    const std::string name = j["texture"].get<std::string>();
    auto it = names.find(name);
    if (it == names.end()) {
      std::vector<std::string> known;
      for (const auto& [n, i] : names) known.push_back(n);
      fail(c, where + ": unknown texture '" + clipped(name) + "' (" +
                  (known.empty() ? std::string("the file defines no textures")
                                 : "textures: " + name_list(known)) +
                  ")");
    }
    return ParamValue::of_texture(it->second);
  }
  fail(c, where + ": expected a colour [r, g, b], a number or {\"texture\": NAME}");
}

// A parameter's value from the file: a colour (a number is grey) or a texture for a colour
// parameter, a number for a number parameter.
ParamValue param_value(const Ctx& c, const json& j, ParamType type, const std::string& at,
                       const TextureNames& names) {
  if (type == ParamType::Color) return colour(c, j, at, names);
  if (!j.is_number())
    fail(c, at + ": expected a number" +
                (j.is_object() ? " (textures bind only to colour parameters)" : ""));
  return ParamValue::of(num(c, j, at));
}

// A material's keys that are not its shader's: the light it emits (Material::emission).
bool is_light_key(const std::string& key) {
  return key == "emission" || key == "two_sided";
}

// "emission": a colour, a number (grey), or {"texture": NAME} with an optional "scale" (a
// colour or a number, default 1) that multiplies the texture's colour.
void read_light_keys(const Ctx& c, const json& j, const std::string& where,
                     const TextureNames& names, Material& m) {
  if (j.contains("emission")) {
    const json& e = j["emission"];
    const std::string at = where + ".emission";
    if (e.is_object()) {
      for (auto it = e.begin(); it != e.end(); ++it)
        if (it.key() != "texture" && it.key() != "scale")
          fail(c, at + ": unknown key '" + it.key() + "' (texture, scale)");
      if (!e.contains("texture"))
        fail(c, at + ": expected a colour [r, g, b], a number or {\"texture\": NAME}");
      m.emission_texture = colour(c, json{{"texture", e["texture"]}}, at, names).texture;
      m.emission =
          e.contains("scale") ? vec3_or_scalar(c, e["scale"], at + ".scale") : glm::vec3(1.0f);
    } else {
      m.emission = vec3_or_scalar(c, e, at);
    }
    if (m.emission.x < 0.0f || m.emission.y < 0.0f || m.emission.z < 0.0f)
      fail(c, where + ".emission " + vec_str(m.emission) + " has a negative component");
  }
  if (j.contains("two_sided")) m.two_sided = boolean(c, j["two_sided"], where + ".two_sided");
}

// A material without "shader": the classic keys (scene/ClassicMaterial.h), which make a
// phong material, or a glass one where it transmits. Textures bind to its colours.
Material classic_material(const Ctx& c, const std::string& name, const json& j,
                          const TextureNames& names) {
  const std::string where = "materials." + name;
  ClassicMaterial classic;
  std::map<std::string, ParamValue> textures;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (is_light_key(key)) continue;
    if (!is_classic_key(key)) {
      std::vector<std::string> allowed{"shader", "emission", "two_sided"};
      for (const char* k : kClassicKeys) allowed.push_back(k);
      fail(c, where + ": unknown key '" + key + "' (" + join(allowed) + ")");
    }
    const ParamType type = is_classic_color(key) ? ParamType::Color : ParamType::Number;
    const ParamValue v = param_value(c, it.value(), type, where + "." + key, names);
    if (v.kind == ParamValue::Kind::Texture)
      textures[key] = v;
    else
      set_classic(classic, key, v);
  }
  if (std::string why = classic.problem(); !why.empty()) fail(c, "material '" + name + "': " + why);
  Material m = classic.material(name);
  for (const auto& [key, v] : textures) m.params[key] = v;
  read_light_keys(c, j, where, names, m);
  return m;
}

// A material: a shader, by name, and its parameters; or, without "shader", a classic one.
Material material(const Ctx& c, const std::string& name, const json& j, const TextureNames& names) {
  const std::string where = "materials." + name;
  if (!j.is_object()) fail(c, where + " must be an object");
  if (!j.contains("shader")) return classic_material(c, name, j, names);
  if (!j["shader"].is_string()) fail(c, where + ".shader must be a shader name");
  Material m;
  m.name = name;
  m.shader = j["shader"].get<std::string>();
  const SurfaceShader* shader = find_shader(m.shader);
  if (shader == nullptr)
    fail(c, where + ".shader: unknown shader '" + m.shader + "' (known: " + join(shader_names()) +
                ")");
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    if (key == "shader" || is_light_key(key)) continue;
    auto decl = std::find_if(shader->params.begin(), shader->params.end(),
                             [&](const ShaderParam& p) { return p.name == key; });
    if (decl == shader->params.end()) {
      std::vector<std::string> allowed{"shader", "emission", "two_sided"};
      for (const ShaderParam& p : shader->params) allowed.push_back(p.name);
      fail(c, where + ": unknown key '" + key + "' (" + join(allowed) + ")");
    }
    m.params[key] = param_value(c, it.value(), decl->type, where + "." + key, names);
  }
  read_light_keys(c, j, where, names, m);
  for (const ShaderParam& p : shader->params)
    if (p.required && !j.contains(p.name))
      fail(c, where + ": shader '" + shader->name + "' needs parameter '" + p.name + "' (a " +
                  param_type_name(p.type) + ")");
  return m;
}

std::vector<glm::vec3> points(const Ctx& c, const json& j, const std::string& where, size_t n) {
  if (!j.is_array() || j.size() != n)
    fail(c, where + " must be an array of " + std::to_string(n) + " points");
  std::vector<glm::vec3> p;
  for (size_t i = 0; i < n; ++i) p.push_back(vec3(c, j[i], where + "[" + std::to_string(i) + "]"));
  return p;
}

// The size fields of the shapes that can be large: key, default and range. mesh() reads them
// with errors; shape_triangles() reads them leniently to add a scene's shapes up first.
struct SizeField {
  const char* key;
  int fallback, lo, hi;
};
constexpr SizeField kSlices{"slices", 48, 3, 4096}, kStacks{"stacks", 24, 2, 4096},
    kSubdivisions{"subdivisions", 8, 1, 256};
size_t sphere_triangles(size_t slices, size_t stacks) {
  return 2 * slices * stacks;
}
size_t teapot_triangles(size_t subdivisions) {
  return 64 * subdivisions * subdivisions;  // 32 patches
}

int size_field(const Ctx& c, const json& j, const std::string& where, const SizeField& f) {
  return j.contains(f.key) ? integer(c, j[f.key], where + "." + f.key, f.lo, f.hi) : f.fallback;
}

// The triangles a sphere or teapot of valid size will make (0 for anything else: other
// shapes are small, files are counted as they load, bad fields are reported by mesh()).
size_t shape_triangles(const json& m) {
  if (!m.is_object() || !m.contains("shape") || !m["shape"].is_string()) return 0;
  auto field = [&](const SizeField& f) -> size_t {
    if (!m.contains(f.key)) return static_cast<size_t>(f.fallback);
    if (!m[f.key].is_number_integer()) return 0;
    const int64_t v = m[f.key].get<int64_t>();
    return v >= f.lo && v <= f.hi ? static_cast<size_t>(v) : 0;
  };
  const std::string shape = m["shape"].get<std::string>();
  if (shape == "sphere") return sphere_triangles(field(kSlices), field(kStacks));
  if (shape == "teapot") return teapot_triangles(field(kSubdivisions));
  return 0;
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
    check_keys(c, j, where, {"file", "material", "transform", "smooth", "normal_weighting"});
    const std::string name = file_name(c, j["file"], where + ".file");
    std::filesystem::path p(name);
    if (p.is_relative()) p = std::filesystem::path(c.base_dir) / p;
    std::error_code ec;
    if (!std::filesystem::exists(p, ec))
      fail(c,
           where + ".file: " + p.string() + ": no such file" +
               (name != p.string() ? " ('" + name + "' is relative to the scene's folder)" : ""));
    ObjLoadOptions o;
    o.transform = t;
    o.override_material = mat;
    o.override_textures = &s.textures;
    o.input = c.input;
    // "smooth": true (the default crease angle), false, or the crease angle in degrees.
    if (j.contains("smooth")) {
      const json& sm = j["smooth"];
      if (sm.is_number()) {
        o.crease_degrees = num(c, sm, where + ".smooth");
        if (!(o.crease_degrees >= 0 && o.crease_degrees <= 180))
          fail(c, where + ".smooth must be true, false or a crease angle in degrees (0..180)");
      } else if (sm.is_boolean()) {
        o.smooth = sm.get<bool>();
      } else {
        fail(c, where + ".smooth must be true, false or a crease angle in degrees (0..180)");
      }
    }
    if (j.contains("normal_weighting")) {
      const json& w = j["normal_weighting"];
      try {
        if (!w.is_string()) throw std::invalid_argument("it is not a string");
        o.normal_weighting = parse_normal_weighting(w.get<std::string>());
      } catch (const std::invalid_argument&) {
        fail(c, where + ".normal_weighting must be \"angle\", \"area\" or \"area_angle\"");
      }
    }
    const size_t first = s.materials.size();
    s.append(load_mesh_file(p.string(), o));
    // append() renumbers the OBJ's texture indices as its own; the override's already refer
    // to this scene's textures (the OBJ then has one material and no textures).
    if (mat != nullptr) s.materials[first] = *mat;
    return;
  }
  if (!j.contains("shape") || !j["shape"].is_string())
    fail(c,
         where +
             " needs \"file\" (OBJ, PLY, glTF) or \"shape\" (box, sphere, quad, triangle, teapot)");
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
    int sl = size_field(c, j, where, kSlices);
    int st = size_field(c, j, where, kStacks);
    bool smooth = !j.contains("smooth") || boolean(c, j["smooth"], where + ".smooth");
    check_room(c, s, sphere_triangles(sl, st), where);
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
                     tp(tmp.positions[3 * i + 2]), m, np, nullptr, &tmp.texcoords[3 * i]);
    }
  } else if (shape == "quad") {
    check_keys(c, j, where, {"shape", "vertices", "material", "transform"});
    auto v = points(c, j.value("vertices", json()), where + ".vertices", 4);
    add_quad(s, tp(v[0]), tp(v[1]), tp(v[2]), tp(v[3]), m);
  } else if (shape == "triangle") {
    check_keys(c, j, where, {"shape", "vertices", "material", "transform"});
    auto v = points(c, j.value("vertices", json()), where + ".vertices", 3);
    const glm::vec2 uv[3] = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.0f, 1.0f}};
    s.add_triangle(tp(v[0]), tp(v[1]), tp(v[2]), m, nullptr, nullptr, uv);
  } else if (shape == "teapot") {
    check_keys(c, j, where, {"shape", "subdivisions", "material", "transform", "smooth"});
    int n = size_field(c, j, where, kSubdivisions);
    bool smooth = !j.contains("smooth") || boolean(c, j["smooth"], where + ".smooth");
    check_room(c, s, teapot_triangles(n), where);
    add_teapot(s, n, m, t, smooth);
  } else {
    fail(c, where + ".shape '" + shape + "' is unknown (box, sphere, quad, triangle, teapot)");
  }
}

// The scene's large shapes, added up before any is made: meshes whose sum is over the limit
// fail at once, naming the first mesh past it, instead of after tessellating the ones before.
void check_room_for_shapes(const Ctx& c, const Scene& s, const json& meshes) {
  size_t total = 0;
  for (size_t i = 0; i < meshes.size(); ++i) {
    total += shape_triangles(meshes[i]);
    check_room(c, s, total, "meshes[" + std::to_string(i) + "]");
  }
}

}  // namespace

Scene parse_json_scene(const std::string& text, const std::string& base_dir,
                       const std::string& name, const InputOptions& input) {
  Ctx c{name, base_dir, input};
  // Syntax, keys given twice and the nesting first, in a pass that builds nothing; then the
  // document, which that pass found sound.
  if (const std::string why = json_structure_problem(text, kMaxJsonDepth); !why.empty())
    fail(c, why);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    fail(c, std::string("invalid JSON: ") + e.what());
  }
  try {
    check_keys(c, j, "scene",
               {"builtin", "camera", "image", "meshes", "instances", "textures", "materials",
                "lights", "background", "options", "animation"});
    Scene s;
    if (j.contains("builtin")) {
      if (!j["builtin"].is_string()) fail(c, "builtin must be a scene name");
      try {
        s = builtin_scene(j["builtin"].get<std::string>());
      } catch (const SceneError& e) {
        fail(c, std::string("builtin: ") + e.what());
      }
    }
    s.name = std::filesystem::path(name).stem().string();

    TextureNames texture_names;
    if (j.contains("textures")) textures(c, s, j["textures"], texture_names);
    std::map<std::string, Material> materials;
    if (j.contains("materials")) {
      if (!j["materials"].is_object()) fail(c, "materials must be an object of named materials");
      for (auto it = j["materials"].begin(); it != j["materials"].end(); ++it)
        materials[it.key()] = material(c, it.key(), it.value(), texture_names);
      // Every material defined, used by a mesh or not: a mistake in one is found before a
      // mesh starts using it.
      for (const auto& [name, m] : materials) {
        try {
          validate_material(m, s.textures.size());
        } catch (const SceneError& e) {
          fail(c, e.what());
        }
        if (std::string why = material_problem(m, material_shader(m)); !why.empty())
          fail(c, "material '" + name + "': " + why);
      }
    }
    MeshNames mesh_names;
    struct Prototype {
      std::string name, where;
      MeshRange range;
    };
    std::vector<Prototype> prototypes;
    if (j.contains("meshes")) {
      if (!j["meshes"].is_array()) fail(c, "meshes must be an array");
      check_room_for_shapes(c, s, j["meshes"]);
      for (size_t i = 0; i < j["meshes"].size(); ++i) {
        // "name" and "animate" apply to any mesh; the rest is the shape's or file's.
        json m = j["meshes"][i];
        const std::string where = "meshes[" + std::to_string(i) + "]";
        std::string name;
        json animate;
        if (m.is_object() && m.contains("name")) {
          if (!m["name"].is_string() || m["name"].get<std::string>().empty())
            fail(c, where + ".name must be a non-empty string");
          name = m["name"].get<std::string>();
          if (mesh_names.count(name)) fail(c, where + ".name '" + name + "' is used twice");
          m.erase("name");
        }
        if (m.is_object() && m.contains("animate")) {
          animate = m["animate"];
          m.erase("animate");
        }
        // A prototype renders only through its instances: loaded like any mesh, for them to
        // copy, and taken out after them.
        bool prototype = false;
        if (m.is_object() && m.contains("prototype")) {
          prototype = boolean(c, m["prototype"], where + ".prototype");
          m.erase("prototype");
          if (prototype && name.empty())
            fail(c, where + ": a prototype needs a \"name\", for instances to copy it");
          if (prototype && !animate.is_null())
            fail(c, where + ".animate: a prototype is not rendered itself; animate its instances");
        }
        // An OBJ sequence: the mesh is its first file, and every file is a shape of it.
        json sequence_of;
        if (m.is_object() && m.contains("sequence")) {
          sequence_of = m;
          m["file"] = sequence_file(c, m, where);
          m.erase("sequence");
        }
        const size_t first = s.triangle_count();
        mesh(c, s, m, i, materials);
        check_room(c, s, 0, where);  // an OBJ file: the next mesh is not read past the limit
        const MeshRange range{first, s.triangle_count() - first};
        if (!name.empty()) mesh_names[name] = range;
        if (prototype) prototypes.push_back({name, where, range});
        if (!animate.is_null() || !sequence_of.is_null()) {
          AnimatedObject o;
          o.name = name.empty() ? where : name;
          o.first = range.first;
          o.count = range.count;
          if (!animate.is_null())
            o.track = pose_track(c, animate, where + ".animate");
          else
            o.track.keys.push_back(PoseKey{});  // deforms in place
          if (!sequence_of.is_null()) load_sequence(c, sequence_of, where, o);
          s.animation.objects.push_back(std::move(o));
        }
      }
    }
    std::set<std::string> instanced;
    if (j.contains("instances")) instanced = instances(c, s, j["instances"], mesh_names, materials);
    if (!prototypes.empty()) {
      std::vector<TriangleRange> ranges;
      for (const Prototype& p : prototypes) {
        ranges.push_back({p.range.first, p.range.count});
        if (instanced.count(p.name) == 0)
          s.warnings.push_back(c.file + ": " + p.where + ": prototype '" + clipped(p.name) +
                               "' has no instances, so nothing of it is rendered");
      }
      remove_triangles(s, ranges);
    }
    if (j.contains("lights")) {
      if (!j["lights"].is_array()) fail(c, "lights must be an array");
      s.lights.clear();
      for (size_t i = 0; i < j["lights"].size(); ++i) {
        const std::string where = "lights[" + std::to_string(i) + "]";
        s.lights.push_back(read_light(c, j["lights"][i], where));
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
      check_keys(
          c, o, "options",
          {"shadows", "ambient", "max_depth", "grid", "grid_density", "subgrids", "light_buffer",
           "spp", "smooth_normals", "integrator", "seed", "nee", "mis", "light_samples"});
      if (o.contains("shadows")) s.options.shadows = boolean(c, o["shadows"], "options.shadows");
      if (o.contains("ambient")) s.options.ambient = num(c, o["ambient"], "options.ambient");
      if (o.contains("max_depth"))
        s.options.max_depth = integer(c, o["max_depth"], "options.max_depth", 0, 64);
      if (o.contains("spp")) s.options.spp = integer(c, o["spp"], "options.spp", 1, kMaxSpp);
      if (o.contains("integrator")) {
        if (!o["integrator"].is_string())
          fail(c, "options.integrator must be \"whitted\" or \"path\"");
        try {
          s.options.integrator = parse_integrator(o["integrator"].get<std::string>());
        } catch (const SceneError& e) {
          fail(c, std::string("options.integrator: ") + e.what());
        }
      }
      if (o.contains("seed"))
        s.options.seed =
            static_cast<uint32_t>(integer(c, o["seed"], "options.seed", 0, 2147483647));
      if (o.contains("nee")) s.options.nee = boolean(c, o["nee"], "options.nee");
      if (o.contains("mis")) s.options.mis = boolean(c, o["mis"], "options.mis");
      if (o.contains("light_samples"))
        s.options.light_samples =
            integer(c, o["light_samples"], "options.light_samples", 1, kMaxLightSamples);
      if (o.contains("smooth_normals"))
        s.options.smooth_normals = boolean(c, o["smooth_normals"], "options.smooth_normals");
      // A word other than the option's own: name the words, not only the number range.
      auto words = [&](const char* key, const char* accepted, const char* range) {
        const json& v = o[key];
        if (!v.is_string()) return;
        const std::string w = v.get<std::string>();
        for (const char* a : {"auto", "off"})
          if (w == a && std::string(accepted).find(a) != std::string::npos) return;
        fail(c, std::string("options.") + key + " '" + clipped(w) + "': expected " + accepted +
                    " or an integer in " + range);
      };
      if (o.contains("grid")) words("grid", "\"auto\"", "1..512");
      if (o.contains("subgrids")) words("subgrids", "\"auto\", \"off\"", "1..1048576");
      if (o.contains("light_buffer"))
        words("light_buffer", "\"auto\", \"off\"",
              ("1.." + std::to_string(kLightBufferMaxRes)).c_str());
      if (o.contains("grid")) {
        if (o["grid"].is_string() && o["grid"].get<std::string>() == "auto")
          s.options.grid = 0;
        else
          s.options.grid = integer(c, o["grid"], "options.grid", 1, 512);
      }
      if (o.contains("grid_density")) {
        if (o["grid_density"].is_string() && o["grid_density"].get<std::string>() == "auto") {
          s.options.grid_density = kGridDensityAuto;
        } else {
          if (o["grid_density"].is_string())
            fail(c,
                 "options.grid_density must be \"auto\" or a number in [0.125, 256] (voxels "
                 "per triangle)");
          const double d = num(c, o["grid_density"], "options.grid_density");
          if (!(d >= kGridDensityMin && d <= kGridDensityMax))
            fail(c,
                 "options.grid_density must be \"auto\" or in [0.125, 256] (voxels per "
                 "triangle)");
          s.options.grid_density = d;
        }
      }
      if (o.contains("subgrids")) {
        if (o["subgrids"].is_string() && o["subgrids"].get<std::string>() == "off")
          s.options.subgrid_min = kNoSubgrids;
        else if (o["subgrids"].is_string() && o["subgrids"].get<std::string>() == "auto")
          s.options.subgrid_min = kSubgridsAuto;
        else
          s.options.subgrid_min = integer(c, o["subgrids"], "options.subgrids", 1, 1 << 20);
      }
      if (o.contains("light_buffer")) {
        const json& lb = o["light_buffer"];
        if (lb.is_string() && lb.get<std::string>() == "off")
          s.options.light_buffer = kLightBufferOff;
        else if (lb.is_string() && lb.get<std::string>() == "auto")
          s.options.light_buffer = kLightBufferAuto;
        else
          s.options.light_buffer = integer(c, lb, "options.light_buffer", 1, kLightBufferMaxRes);
      }
    }
    if (j.contains("camera")) {
      const json& cam = j["camera"];
      check_keys(c, cam, "camera",
                 {"eye", "look_at", "up", "fov_y", "type", "height", "aperture", "focus_distance",
                  "keys", "interpolation"});
      Camera k = s.camera;
      if (cam.contains("eye")) k.eye = vec3(c, cam["eye"], "camera.eye");
      if (cam.contains("look_at")) k.look_at = vec3(c, cam["look_at"], "camera.look_at");
      if (cam.contains("up")) k.up = vec3(c, cam["up"], "camera.up");
      if (cam.contains("fov_y")) k.fov_y = num(c, cam["fov_y"], "camera.fov_y");
      camera_projection(c, cam, k);
      s.camera = k;
      s.has_camera = true;
      if (cam.contains("keys") || cam.contains("interpolation"))
        s.animation.camera = camera_track(c, cam, k);
    }
    if (j.contains("animation"))
      s.animation.time = time_range(c, j["animation"]);
    else if (s.animation.animated() && !(s.animation.time.end > s.animation.time.start))
      s.animation.time = keys_time_range(s.animation);
    if (!s.has_camera) {
      s.camera = default_camera(s);
      s.has_camera = true;
      s.camera_framed = true;
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

Scene load_json(const std::string& path, const InputOptions& input) {
  return parse_json_scene(read_input_file(path, "a scene file"),
                          std::filesystem::path(path).parent_path().string(), path, input);
}

}  // namespace rt
