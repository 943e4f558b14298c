// Scene basics (materials, triangles, validation, bounds, the default camera, transforms).
// The loaders are ObjLoader.cpp, Builtin.cpp and load/SceneJson.cpp.
#include "rill/rt/scene/Scene.h"

#include "rill/rt/scene/ImageLimits.h"
#include "rill/rt/scene/InputFile.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rt {

std::string vec_str(const glm::vec3& v) {
  std::ostringstream o;
  o << "[" << v.x << ", " << v.y << ", " << v.z << "]";
  return o.str();
}

namespace {

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec3 rotate(const glm::vec3& p, const glm::vec3& deg) {
  glm::vec3 r = p;
  const double k = 3.14159265358979323846 / 180.0;
  if (deg.x != 0.0f) {
    double c = std::cos(deg.x * k), s = std::sin(deg.x * k);
    r = glm::vec3(r.x, static_cast<float>(c * r.y - s * r.z),
                  static_cast<float>(s * r.y + c * r.z));
  }
  if (deg.y != 0.0f) {
    double c = std::cos(deg.y * k), s = std::sin(deg.y * k);
    r = glm::vec3(static_cast<float>(c * r.x + s * r.z), r.y,
                  static_cast<float>(-s * r.x + c * r.z));
  }
  if (deg.z != 0.0f) {
    double c = std::cos(deg.z * k), s = std::sin(deg.z * k);
    r = glm::vec3(static_cast<float>(c * r.x - s * r.y), static_cast<float>(s * r.x + c * r.y),
                  r.z);
  }
  return r;
}

void validate_texture(const Texture& t) {
  const std::string where = "texture '" + t.name + "': ";
  if (t.type == "bitmap") {
    if (t.width < 1 || t.height < 1 ||
        t.texels.size() != static_cast<size_t>(t.width) * static_cast<size_t>(t.height))
      throw SceneError(where + "needs width * height texels (" + std::to_string(t.width) + "x" +
                       std::to_string(t.height) + ", " + std::to_string(t.texels.size()) +
                       " given)");
    for (const glm::vec3& c : t.texels) {
      if (!finite3(c)) throw SceneError(where + "texels must be finite");
      if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
        throw SceneError(where + "texel " + vec_str(c) +
                         " has a negative component; colours must be >= 0");
    }
    return;
  }
  const auto& types = procedural_texture_types();
  if (std::find(types.begin(), types.end(), t.type) == types.end()) {
    std::string all = "bitmap";
    for (const std::string& k : types) all += ", " + k;
    throw SceneError(where + "unknown type '" + t.type + "' (" + all + ")");
  }
  if (!finite3(t.color1) || !finite3(t.color2) || !std::isfinite(t.scale))
    throw SceneError(where + "values must be finite numbers");
  for (const glm::vec3& c : {t.color1, t.color2})
    if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
      throw SceneError(where + "colour " + vec_str(c) +
                       " has a negative component; colours must be >= 0");
  // Beyond this the pattern repeats below a float's resolution of the hit point, and noise
  // of huge coordinates turned into NaN pixels (a scale of 1e20).
  if (!(t.scale > 0.0f) || t.scale > kMaxTextureScale)
    throw SceneError(where + "scale must be in (0, 1e6]");
}

}  // namespace

// ---- Scene ---------------------------------------------------------------------------------

int Scene::add_material(const Material& m) {
  materials.push_back(m);
  return static_cast<int>(materials.size()) - 1;
}

void Scene::add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, int mat,
                         const glm::vec3* n, const glm::vec3* col, const glm::vec2* uv) {
  const size_t before = positions.size();
  // The first triangle with normals (colours, texture coordinates) gives the earlier ones
  // geometric normals (white, (0, 0)).
  const bool with_normals = n != nullptr || !normals.empty();
  const bool with_colors = col != nullptr || !colors.empty();
  const bool with_uv = uv != nullptr || !texcoords.empty();
  if (with_normals && normals.empty())
    for (size_t i = 0; i < before; i += 3) {
      glm::vec3 g = glm::cross(positions[i + 1] - positions[i], positions[i + 2] - positions[i]);
      normals.insert(normals.end(), {g, g, g});
    }
  if (with_colors && colors.empty()) colors.assign(before, glm::vec3(1.0f));
  if (with_uv && texcoords.empty()) texcoords.assign(before, glm::vec2(0.0f));
  positions.insert(positions.end(), {a, b, c});
  material.push_back(mat);
  if (with_normals) {
    if (n != nullptr) {
      normals.insert(normals.end(), {n[0], n[1], n[2]});
    } else {
      glm::vec3 g = glm::cross(b - a, c - a);
      normals.insert(normals.end(), {g, g, g});
    }
  }
  if (with_colors) {
    if (col != nullptr)
      colors.insert(colors.end(), {col[0], col[1], col[2]});
    else
      colors.insert(colors.end(), 3, glm::vec3(1.0f));
  }
  if (with_uv) {
    if (uv != nullptr)
      texcoords.insert(texcoords.end(), {uv[0], uv[1], uv[2]});
    else
      texcoords.insert(texcoords.end(), 3, glm::vec2(0.0f));
  }
}

std::string clipped(const std::string& s, size_t max) {
  // Control bytes and bytes that are not UTF-8 as \xNN: an error message stays one line of
  // text whatever the file held. Well-formed UTF-8 (a name in any script) is kept.
  // The length of the well-formed UTF-8 sequence at i (RFC 3629: no overlong forms, no
  // surrogates, nothing past U+10FFFF, no C1 controls), or 0.
  auto utf8_length = [&](size_t i) -> size_t {
    const auto c = static_cast<unsigned char>(s[i]);
    const size_t n = c >= 0xc2 && c <= 0xdf   ? 2
                     : c >= 0xe0 && c <= 0xef ? 3
                     : c >= 0xf0 && c <= 0xf4 ? 4
                                              : 0;
    if (n == 0 || i + n > s.size()) return 0;
    for (size_t k = 1; k < n; ++k)
      if ((static_cast<unsigned char>(s[i + k]) & 0xc0) != 0x80) return 0;
    const auto c1 = static_cast<unsigned char>(s[i + 1]);
    if ((c == 0xc2 && c1 < 0xa0) || (c == 0xe0 && c1 < 0xa0) || (c == 0xed && c1 > 0x9f) ||
        (c == 0xf0 && c1 < 0x90) || (c == 0xf4 && c1 > 0x8f))
      return 0;
    return n;
  };
  std::string out;
  size_t i = 0;
  for (; i < s.size() && out.size() < max; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else if (const size_t n = c >= 0x80 ? utf8_length(i) : 0; n > 0) {
      out.append(s, i, n);
      i += n - 1;
    } else {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out.push_back(hex[c >> 4]);
      out.push_back(hex[c & 15]);
    }
  }
  if (i < s.size()) out += "... (" + std::to_string(s.size()) + " bytes)";
  return out;
}

void Scene::append(const Scene& o) {
  warnings.insert(warnings.end(), o.warnings.begin(), o.warnings.end());
  const int base = static_cast<int>(materials.size());
  const int tex_base = static_cast<int>(textures.size());
  textures.insert(textures.end(), o.textures.begin(), o.textures.end());
  for (Material m : o.materials) {
    for (auto& [name, v] : m.params)
      if (v.kind == ParamValue::Kind::Texture) v.texture += tex_base;
    if (m.emission_texture >= 0) m.emission_texture += tex_base;
    materials.push_back(std::move(m));
  }
  for (AnimatedObject obj : o.animation.objects) {
    obj.first += triangle_count();
    animation.objects.push_back(std::move(obj));
  }
  for (size_t t = 0; t < o.triangle_count(); ++t) {
    const glm::vec3* n = o.normals.empty() ? nullptr : &o.normals[3 * t];
    const glm::vec3* c = o.colors.empty() ? nullptr : &o.colors[3 * t];
    const glm::vec2* uv = o.texcoords.empty() ? nullptr : &o.texcoords[3 * t];
    add_triangle(o.positions[3 * t], o.positions[3 * t + 1], o.positions[3 * t + 2],
                 base + o.material[t], n, c, uv);
  }
}

namespace {

// The animated objects' ranges lie within the scene and do not overlap, and their tracks and
// the camera's have keys at increasing, finite times (the JSON reader names the key first;
// this catches scenes built in code).
void validate_animation(const Animation& a, size_t triangles) {
  std::vector<std::pair<size_t, size_t>> ranges;
  for (const AnimatedObject& o : a.objects) {
    const std::string where = "animated object '" + clipped(o.name) + "'";
    if (o.first > triangles || o.count > triangles - o.first)
      throw SceneError(where + ": triangles " + std::to_string(o.first) + ".." +
                       std::to_string(o.first + o.count) + " are not in the scene (" +
                       std::to_string(triangles) + " triangles)");
    if (o.track.keys.empty()) throw SceneError(where + " has no keys");
    if (!std::isfinite(o.pivot.x) || !std::isfinite(o.pivot.y) || !std::isfinite(o.pivot.z))
      throw SceneError(where + ": the pivot must be finite");
    if (!o.shape_normals.empty() && o.shape_normals.size() != o.shapes.size())
      throw SceneError(where + ": " + std::to_string(o.shapes.size()) + " shapes but " +
                       std::to_string(o.shape_normals.size()) + " sets of normals");
    for (size_t k = 0; k < o.shapes.size(); ++k)
      if (o.shapes[k].size() != 3 * o.count ||
          (!o.shape_normals.empty() && o.shape_normals[k].size() != 3 * o.count))
        throw SceneError(where + ": shape " + std::to_string(k) + " has " +
                         std::to_string(o.shapes[k].size()) + " corners, not " +
                         std::to_string(3 * o.count));
    for (size_t k = 0; k < o.track.keys.size(); ++k) {
      const PoseKey& key = o.track.keys[k];
      if (!std::isfinite(key.time) || (k > 0 && !(key.time > o.track.keys[k - 1].time)))
        throw SceneError(where + ": key " + std::to_string(k) +
                         " must have a finite time after the previous key's");
      const Pose& p = key.pose;
      auto finite = [](const glm::dvec3& v) {
        return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
      };
      if (!finite(p.translate) || !finite(p.scale) || p.scale.x == 0 || p.scale.y == 0 ||
          p.scale.z == 0 || !std::isfinite(glm::length(p.rotation)) ||
          std::fabs(glm::length(p.rotation) - 1) > 1e-6)
        throw SceneError(where + ": key " + std::to_string(k) +
                         " needs a finite translation, a non-zero scale and a unit rotation");
    }
    ranges.emplace_back(o.first, o.first + o.count);
  }
  std::sort(ranges.begin(), ranges.end());
  for (size_t i = 1; i < ranges.size(); ++i)
    if (ranges[i].first < ranges[i - 1].second)
      throw SceneError("two animated objects share triangles " + std::to_string(ranges[i].first) +
                       ".." + std::to_string(ranges[i - 1].second));
  for (size_t k = 1; k < a.camera.keys.size(); ++k)
    if (!(a.camera.keys[k].time > a.camera.keys[k - 1].time))
      throw SceneError("camera key " + std::to_string(k) + " must come after the previous key");
  if (a.animated() && !(a.time.end > a.time.start && a.time.fps > 0))
    throw SceneError("an animated scene needs a time range with end after start and fps > 0");
}

}  // namespace

void check_lens(const Camera& camera, const std::string& where) {
  if (!std::isfinite(camera.ortho_height) || !std::isfinite(camera.aperture) ||
      !std::isfinite(camera.focus_distance))
    throw SceneError(where + ": values must be finite numbers");
  if (camera.projection == Projection::Orthographic && !(camera.ortho_height > 0.0f))
    throw SceneError(where + ": height must be > 0 (the orthographic view's height)");
  if (!(camera.aperture >= 0.0f))
    throw SceneError(where + ": aperture must be >= 0 (the lens's radius; 0 is a pinhole)");
  if (!(camera.focus_distance >= 0.0f)) throw SceneError(where + ": focus_distance must be > 0");
  if (camera.projection == Projection::Orthographic && camera.aperture > 0.0f)
    throw SceneError(where + ": aperture is for a perspective camera, not an orthographic one");
}

void check_camera(const Camera& camera, const std::string& where) {
  if (!finite3(camera.eye) || !finite3(camera.look_at) || !finite3(camera.up) ||
      !std::isfinite(camera.fov_y))
    throw SceneError(where + ": values must be finite numbers");
  if (!(camera.fov_y > 0.0f && camera.fov_y < 180.0f))
    throw SceneError(where + ": fov_y must be between 0 and 180 degrees");
  check_lens(camera, where);
  if (camera.eye == camera.look_at)
    throw SceneError(where + ": eye and look_at are the same point");
  glm::dvec3 f = glm::dvec3(camera.look_at) - glm::dvec3(camera.eye);
  glm::dvec3 u = glm::dvec3(camera.up);
  glm::dvec3 c = glm::cross(f, u);
  if (glm::length(c) <= 1e-6 * glm::length(f) * glm::length(u))
    throw SceneError(where + ": up " + vec_str(camera.up) + " is parallel to the view direction");
}

// One material's values (Scene::validate; the JSON reader checks every material it defines
// with it, used by a mesh or not): every parameter finite, colours not negative, textures
// that exist. What a shader asks of its own parameters (a range, a sum) is its check
// (SurfaceShader::check), run where the shader is known: the JSON reader and the Tracer.
// texture_count: the scene's textures, which a parameter may refer to.
void validate_material(const Material& m, size_t texture_count) {
  const std::string where = "material '" + m.name + "': ";
  if (m.shader.empty()) throw SceneError(where + "no shader named");
  if (!finite3(m.emission) || m.emission.x < 0.0f || m.emission.y < 0.0f || m.emission.z < 0.0f)
    throw SceneError(where + "emission " + vec_str(m.emission) +
                     " must be finite with no negative component");
  if (m.emission_texture < -1 ||
      (m.emission_texture >= 0 && static_cast<size_t>(m.emission_texture) >= texture_count))
    throw SceneError(where + "emission refers to texture " + std::to_string(m.emission_texture) +
                     ", but the scene has " + std::to_string(texture_count));
  for (const auto& [name, v] : m.params) {
    const bool finite = v.kind == ParamValue::Kind::Number  ? std::isfinite(v.number)
                        : v.kind == ParamValue::Kind::Color ? finite3(v.color)
                                                            : true;
    if (!finite) throw SceneError(where + name + " must be finite");
    // Colours are reflectances and light: a negative one would render negative radiance.
    if (v.kind == ParamValue::Kind::Color &&
        (v.color.x < 0.0f || v.color.y < 0.0f || v.color.z < 0.0f))
      throw SceneError(where + name + " " + vec_str(v.color) +
                       " has a negative component; colours must be >= 0");
    if (v.kind == ParamValue::Kind::Texture &&
        (v.texture < 0 || static_cast<size_t>(v.texture) >= texture_count))
      throw SceneError(where + name + " refers to texture " + std::to_string(v.texture) +
                       ", but the scene has " + std::to_string(texture_count));
  }
}

namespace {
// What a spot or directional light asks beyond a point light's (Light).
void validate_light_shape(const Light& l) {
  const std::string where =
      std::string(light_type_name(l.type)) + " light at " + vec_str(l.position) + ": ";
  if (l.type != LightType::Point &&
      (!finite3(l.direction) || !(glm::length(glm::dvec3(l.direction)) > 0.0)))
    throw SceneError(where + "direction " + vec_str(l.direction) + " must be finite and not zero");
  if (l.type == LightType::Spot && !(l.outer_deg > 0.0f && l.outer_deg <= kMaxSpotDeg &&
                                     l.inner_deg >= 0.0f && l.inner_deg <= l.outer_deg))
    throw SceneError(where + "cone angles inner " + std::to_string(l.inner_deg) + ", outer " +
                     std::to_string(l.outer_deg) +
                     " must have 0 <= inner <= outer and 0 < outer <= 90 degrees");
  if (l.type == LightType::Directional && l.falloff != Falloff::None)
    throw SceneError(where + "a directional light has no distance falloff");
}
}  // namespace

void Scene::validate() const {
  const size_t n = triangle_count();
  if (positions.size() != 3 * n) throw SceneError("internal: positions and materials disagree");
  if (!normals.empty() && normals.size() != 3 * n)
    throw SceneError("internal: normals and positions disagree");
  if (!colors.empty() && colors.size() != 3 * n)
    throw SceneError("internal: colors and positions disagree");
  if (!texcoords.empty() && texcoords.size() != 3 * n)
    throw SceneError("internal: texcoords and positions disagree");
  for (size_t i = 0; i < texcoords.size(); ++i)
    if (!std::isfinite(texcoords[i].x) || !std::isfinite(texcoords[i].y))
      throw SceneError("triangle " + std::to_string(i / 3) +
                       ": texture coordinates must be finite numbers");
  for (const Texture& t : textures) validate_texture(t);
  validate_animation(animation, n);
  if (n > kMaxTriangles)
    throw SceneError("scene has " + std::to_string(n) + " triangles; at most " +
                     std::to_string(kMaxTriangles) + " are supported");
  for (int32_t m : material)
    if (m < 0 || static_cast<size_t>(m) >= materials.size())
      throw SceneError("internal: triangle with material index " + std::to_string(m));
  for (const Material& m : materials) validate_material(m, textures.size());
  for (const Light& l : lights) {
    if (!finite3(l.position) || !finite3(l.color))
      throw SceneError("light at " + vec_str(l.position) + ": values must be finite numbers");
    if (l.color.x < 0.0f || l.color.y < 0.0f || l.color.z < 0.0f)
      throw SceneError("light at " + vec_str(l.position) + ": colour " + vec_str(l.color) +
                       " has a negative component; colours must be >= 0");
    validate_light_shape(l);
  }
  if (!finite3(background)) throw SceneError("background must be finite");
  if (background.x < 0.0f || background.y < 0.0f || background.z < 0.0f)
    throw SceneError("background " + vec_str(background) +
                     " has a negative component; colours must be >= 0");
  check_camera(camera, "camera");
  for (size_t k = 0; k < animation.camera.keys.size(); ++k) {
    const CameraPose& p = animation.camera.keys[k].camera;
    Camera key = camera;  // the keys move the camera; its lens and projection stay
    key.eye = p.eye;
    key.look_at = p.look_at;
    key.up = p.up;
    key.fov_y = p.fov_y;
    check_camera(key, "camera.keys[" + std::to_string(k) + "]");
  }
  if (!image_size_fits(width, height))
    throw SceneError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     " is out of range (" + image_size_limits() + ")");
  if (!std::isfinite(options.ambient) || options.ambient < 0 || options.ambient > 1)
    throw SceneError("options: ambient must be in [0, 1]");
  if (options.max_depth < 0 || options.max_depth > 64)
    throw SceneError("options: max_depth must be in [0, 64]");
  if (options.spp < 1 || options.spp > kMaxSpp)
    throw SceneError("options: spp must be in [1, " + std::to_string(kMaxSpp) + "]");
  if (options.light_samples < 1 || options.light_samples > kMaxLightSamples)
    throw SceneError("options: light_samples must be in [1, " + std::to_string(kMaxLightSamples) +
                     "]");
  if (options.grid < 0 || options.grid > 512)
    throw SceneError("options: grid must be 'auto' (0) or 1..512 cells per axis");
}

const char* light_type_name(LightType t) {
  return t == LightType::Spot ? "spot" : t == LightType::Directional ? "directional" : "point";
}

const char* falloff_name(Falloff f) {
  return f == Falloff::InverseSquare ? "inverse_square" : "none";
}

const char* integrator_name(Integrator i) {
  return i == Integrator::Path ? "path" : "whitted";
}

Integrator parse_integrator(const std::string& s) {
  if (s == "whitted") return Integrator::Whitted;
  if (s == "path") return Integrator::Path;
  throw SceneError("unknown integrator '" + clipped(s) + "' (whitted, path)");
}

bool scene_bounds(const Scene& s, glm::vec3& lo, glm::vec3& hi) {
  bool any = false;
  lo = glm::vec3(INFINITY);
  hi = glm::vec3(-INFINITY);
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3* p = &s.positions[3 * t];
    if (!finite3(p[0]) || !finite3(p[1]) || !finite3(p[2])) continue;
    for (int k = 0; k < 3; ++k) {
      lo = glm::min(lo, p[k]);
      hi = glm::max(hi, p[k]);
    }
    any = true;
  }
  return any;
}

// ---- Transform -----------------------------------------------------------------------------

glm::vec3 Transform::apply_point(const glm::vec3& p) const {
  return rotate(p * scale, rotate_deg) + translate;
}

glm::vec3 Transform::apply_normal(const glm::vec3& n) const {
  return rotate(n / scale, rotate_deg);
}

bool Transform::identity() const {
  return scale == glm::vec3(1.0f) && rotate_deg == glm::vec3(0.0f) && translate == glm::vec3(0.0f);
}

}  // namespace rt
