#include "CameraOptions.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

#include "CliChecks.h"
#include "rill/rt/scene/InputFile.h"

namespace trace_cli {

namespace {

// "X,Y,Z": three finite numbers, nothing else.
glm::vec3 parse_vec3(const std::string& name, const std::string& s) {
  const std::vector<std::string> parts = split_list(s);
  glm::vec3 v(0.0f);
  bool ok = parts.size() == 3 && std::count(s.begin(), s.end(), ',') == 2;
  for (size_t k = 0; ok && k < 3; ++k) {
    size_t used = 0;
    try {
      v[static_cast<int>(k)] = std::stof(parts[k], &used);
    } catch (const std::exception&) {
      ok = false;
    }
    ok = ok && used == parts[k].size() && std::isfinite(v[static_cast<int>(k)]);
  }
  if (!ok)
    throw std::invalid_argument(name + " expects X,Y,Z, three finite numbers (got '" + s + "')");
  return v;
}

// One finite number, nothing else.
double parse_number(const std::string& name, const std::string& s, const char* what) {
  size_t used = 0;
  double f = NAN;
  try {
    f = std::stod(s, &used);
  } catch (const std::exception&) {
  }
  if (used != s.size() || !std::isfinite(f))
    throw std::invalid_argument(name + " expects " + what + " (got '" + s + "')");
  return f;
}

// A length in scene units: finite and > 0, or >= 0 where zero is allowed (the aperture).
float check_length(const std::string& name, double v, bool zero_allowed, const char* what) {
  if (!std::isfinite(v) || v > 3.0e38 || (zero_allowed ? !(v >= 0) : !(v > 0)))
    throw std::invalid_argument(name + " is " + what + ", a finite number " +
                                (zero_allowed ? ">= 0" : "> 0"));
  return static_cast<float>(v);
}

// What a length option takes: "--aperture expects a radius in scene units (got 'x')", "--aperture
// is the lens's radius in scene units (0: a pinhole), a finite number >= 0".
struct LengthKind {
  const char* noun;
  const char* what;
  bool zero_allowed;
};

void add_length_option(CLI::App* r, const std::string& name, std::optional<float>& out,
                       LengthKind kind, const std::string& description) {
  add_parsed_option(
      r, name, out,
      [name, kind](const std::string& s) {
        const double v =
            parse_number(name, s, (std::string(kind.noun) + " in scene units").c_str());
        return check_length(name, v, kind.zero_allowed, kind.what);
      },
      description);
}

constexpr const char* kHeight = "the orthographic view's height in scene units";
constexpr const char* kAperture = "the lens's radius in scene units (0: a pinhole)";
constexpr const char* kFocus = "the distance from the eye to the plane in focus";

float check_fov(const std::string& name, double f) {
  if (!(f > 0 && f < 180))
    throw std::invalid_argument(name + " is the vertical field of view in degrees, in (0, 180)");
  return static_cast<float>(f);
}

// A --camera file's height, aperture or focus_distance.
void length_key(const std::string& where, const std::string& key, const nlohmann::json& value,
                CameraOptions& o) {
  const std::string name = where + ": " + key;
  const double v = value.is_number() ? value.get<double>() : NAN;
  if (key == "height")
    o.ortho_height = check_length(name, v, false, kHeight);
  else if (key == "aperture")
    o.aperture = check_length(name, v, true, kAperture);
  else
    o.focus_distance = check_length(name, v, false, kFocus);
}

// --camera FILE.json: an object with the scene format's camera keys (eye, look_at, up,
// fov_y, type, height, aperture, focus_distance), each optional. The keys of an animated
// camera are the scene file's business.
void read_camera_file(const std::string& path, CameraOptions& o) {
  const std::string where = "--camera " + path;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(rt::read_input_file(path, "a camera file"));
  } catch (const nlohmann::json::exception& e) {
    throw std::invalid_argument(where + ": not JSON (" + e.what() + ")");
  } catch (const rt::SceneError& e) {
    throw std::invalid_argument("--camera: " + std::string(e.what()));
  }
  if (!j.is_object()) throw std::invalid_argument(where + ": expects a JSON object");
  auto vec = [&](const char* key) {
    const nlohmann::json& v = j[key];
    bool ok = v.is_array() && v.size() == 3;
    for (size_t k = 0; ok && k < 3; ++k) ok = v[k].is_number() && std::isfinite(v[k].get<double>());
    if (!ok) throw std::invalid_argument(where + ": " + key + " expects [x, y, z], three numbers");
    return glm::vec3(v[0].get<float>(), v[1].get<float>(), v[2].get<float>());
  };
  for (const auto& [key, value] : j.items()) {
    if (key == "eye")
      o.eye = vec("eye");
    else if (key == "look_at")
      o.look_at = vec("look_at");
    else if (key == "up")
      o.up = vec("up");
    else if (key == "fov_y" && value.is_number())
      o.fov_y = check_fov(where + ": fov_y", value.get<double>());
    else if (key == "fov_y")
      throw std::invalid_argument(where + ": fov_y expects a number of degrees");
    else if (key == "type" && value == "perspective")
      o.projection = rt::Projection::Perspective;
    else if (key == "type" && value == "orthographic")
      o.projection = rt::Projection::Orthographic;
    else if (key == "type")
      throw std::invalid_argument(where + ": type expects \"perspective\" or \"orthographic\"");
    else if (key == "height" || key == "aperture" || key == "focus_distance")
      length_key(where, key, value, o);
    else
      throw std::invalid_argument(
          where + ": unknown key '" + key +
          "' (valid: eye, look_at, up, fov_y, type, height, aperture, focus_distance)");
  }
}

}  // namespace

void add_camera_options(CLI::App* r, CameraOptions& o) {
  // CLI11 runs the options' callbacks after parsing, in the order they are defined here:
  // --camera first, so that --eye and the others win over the file's keys wherever they are.
  r->add_option_function<std::string>(
       "--camera",
       [&o](const std::string& path) {
         try {
           read_camera_file(path, o);
         } catch (const std::invalid_argument& e) {
           throw CLI::ValidationError(e.what());
         }
       },
       "a JSON object with the scene format's camera keys (eye, look_at, up, fov_y, type, "
       "height, aperture, focus_distance), each overriding the scene's camera; the single "
       "options override it in turn")
      ->check(file_name());
  add_parsed_option(
      r, "--eye", o.eye, [](const std::string& s) { return parse_vec3("--eye", s); },
      "X,Y,Z: the camera's position (overrides the scene's camera or the framing camera)");
  add_parsed_option(
      r, "--look-at", o.look_at, [](const std::string& s) { return parse_vec3("--look-at", s); },
      "X,Y,Z: the point the camera looks at");
  add_parsed_option(
      r, "--up", o.up, [](const std::string& s) { return parse_vec3("--up", s); },
      "X,Y,Z: a vector roughly up (need not be unit or orthogonal to the view)");
  add_parsed_option(
      r, "--fov", o.fov_y,
      [](const std::string& s) {
        return check_fov("--fov", parse_number("--fov", s, "a number of degrees"));
      },
      "DEGREES: the vertical field of view, in (0, 180)");
  add_length_option(r, "--ortho-height", o.ortho_height, {"a height", kHeight, false},
                    "HEIGHT: an orthographic camera, its view HEIGHT scene units tall (rays "
                    "along the view direction)");
  add_length_option(
      r, "--aperture", o.aperture, {"a radius", kAperture, true},
      "RADIUS: depth of field, a thin lens of this radius in scene units (0: a pinhole)");
  add_length_option(r, "--focus-distance", o.focus_distance, {"a distance", kFocus, false},
                    "DISTANCE: the thin lens's plane in focus, this far from the eye along the "
                    "view (default: the distance to the look-at point)");
  add_parsed_option(r, "--up-axis", o.up_axis, rt::parse_up_axis,
                    "the framing camera's up axis (a scene without a camera): x, y, z, or auto "
                    "(y, unless the mesh stands tall in z: docs/camera.md)")
      ->default_str("auto");
}

void apply_camera_options(rt::Scene& scene, const CameraOptions& o) {
  if (scene.camera_framed)
    scene.camera = rt::framing_camera(scene, scene.width, scene.height, o.up_axis);
  if (o.any()) {
    if (!scene.animation.camera.keys.empty())
      throw CommandLineError(
          "--eye, --look-at, --up, --fov, --ortho-height, --aperture, --focus-distance and "
          "--camera set a fixed camera, and this scene's camera is animated (camera.keys): edit "
          "the scene's keys instead");
    rt::Camera& c = scene.camera;
    if (o.eye) c.eye = *o.eye;
    if (o.look_at) c.look_at = *o.look_at;
    if (o.up) c.up = *o.up;
    if (o.fov_y) c.fov_y = *o.fov_y;
    const bool was_ortho = c.projection == rt::Projection::Orthographic;
    if (o.projection) c.projection = *o.projection;
    if (o.ortho_height) c.projection = rt::Projection::Orthographic;
    if (c.projection == rt::Projection::Orthographic && !was_ortho && !o.ortho_height)
      throw CommandLineError(
          "an orthographic camera (--camera's type) needs its view's height: give "
          "--ortho-height or the file's height");
    if (o.ortho_height) c.ortho_height = *o.ortho_height;
    if (o.aperture) c.aperture = *o.aperture;
    if (o.focus_distance) c.focus_distance = *o.focus_distance;
    try {
      rt::check_camera(c,
                       "the camera of --eye, --look-at, --up, --fov, --ortho-height, --aperture, "
                       "--focus-distance and --camera");
    } catch (const rt::SceneError& e) {
      throw CommandLineError(e.what());
    }
  }
  if (scene.framing_light >= 0 && static_cast<size_t>(scene.framing_light) < scene.lights.size())
    scene.lights[static_cast<size_t>(scene.framing_light)].position =
        rt::framing_light_position(scene.camera);
}

}  // namespace trace_cli
