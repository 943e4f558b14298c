// Scenes for the ray tracer: triangles, materials, point lights, a pinhole camera and options.
//
// A Scene is a flat triangle soup. Triangles keep the order in which they were added (file
// order: shape by shape, face by face, polygons fanned as (v0, vk, vk+1)); that index is the
// primitive id of the AOV outputs (docs/primitive-ids.md).
//
// Scenes come from OBJ + MTL files (load_obj), the built-in generators (builtin_scene), or
// JSON scene files (load/SceneFile.h: load_json, and load_scene for any of the three), whose
// reader checks materials against the registered shaders and so sits above them.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "rill/rt/scene/Animation.h"
#include "rill/rt/scene/Texture.h"
#include "rill/rt/scene/VertexNormals.h"

namespace rt {

// Any problem with a scene, a file or an option: the message is one line for the user.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A user's string for a message: whole up to `max` characters, else its start and its length
// in bytes (a 100 KB shape name must not make a 100 KB error line); control bytes and bytes
// that are not UTF-8 written as \xNN.
std::string clipped(const std::string& s, size_t max = 80);
// A vector for a message: "[1, 0.5, 0]".
std::string vec_str(const glm::vec3& v);

// A value of a shader parameter (kernel/Shader.h): a number, a colour, or a texture (an
// index into Scene::textures) bound to a colour parameter.
struct ParamValue {
  enum class Kind { Number, Color, Texture };
  Kind kind = Kind::Number;
  float number = 0.0f;
  glm::vec3 color{0.0f};
  int texture = -1;
  static ParamValue of(float v) { return {Kind::Number, v, glm::vec3(0.0f), -1}; }
  static ParamValue of(const glm::vec3& v) { return {Kind::Color, 0.0f, v, -1}; }
  static ParamValue of_texture(int t) { return {Kind::Texture, 0.0f, glm::vec3(0.0f), t}; }
};

// A material: a surface shader, by name, and the values of its parameters. Every shader is a
// plugin registered by name (shaders/Registry.h): the built-in ones (phong, mirror, glass) as
// much as a user's, so a material holds nothing shader-specific. A parameter the material
// does not give takes the shader's declared default. The classic keys of MTL files and of
// JSON materials without a shader map onto the built-in shaders' parameters
// (scene/ClassicMaterial.h).
struct Material {
  std::string name = "default";
  std::string shader = "phong";
  // Parameters by name. One the shader does not declare is left alone (it may be another
  // shader's, from before the material changed shader); a JSON file's is an error.
  std::map<std::string, ParamValue> params;
  // Emitted radiance (docs/path-tracing.md), whatever the shader: a material with a non-zero
  // emission makes each of its triangles an area light. It emits on the triangle's front
  // side (where its vertex normals point, else where its winding's normal points: the side
  // a ray sees when Surface::entering is true), on both sides when two_sided.
  // With emission_texture (an index into Scene::textures, or -1), the radiance at a point is
  // emission times the texture's colour there (at the point's texture coordinates, or the
  // point itself for a solid texture): emission is then the texture's scale.
  glm::vec3 emission{0.0f};
  int emission_texture = -1;
  bool two_sided = false;
  bool emits() const { return emission.x > 0.0f || emission.y > 0.0f || emission.z > 0.0f; }

  // Sets a parameter; returns the material, so that one reads as an expression:
  // Material{"red"}.set("diffuse", glm::vec3(0.8f, 0.1f, 0.1f)).
  Material& set(const std::string& param, float v) {
    params[param] = ParamValue::of(v);
    return *this;
  }
  Material& set(const std::string& param, const glm::vec3& c) {
    params[param] = ParamValue::of(c);
    return *this;
  }
};

// Lights (docs/scene-format.md, "lights"): a point light shines from `position` in every
// direction; a spot light from `position` into a cone about `direction`, full within
// inner_deg of the axis, nothing beyond outer_deg, and pbrt's smoothstep of the cosine
// between (kernel/LightShape.h); a directional light from infinitely far away along
// `direction`. Under Whitted, `color` is what a surface facing the light receives, without
// falloff unless `falloff` says inverse_square (point and spot lights); under the path
// integrator it is a point or spot light's intensity (always falling off as 1/r^2) and a
// directional light's irradiance on a surface facing it.
enum class LightType { Point, Spot, Directional };
enum class Falloff { None, InverseSquare };
const char* light_type_name(LightType t);  // "point", "spot", "directional"
const char* falloff_name(Falloff f);       // "none", "inverse_square"
struct Light {
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
  LightType type = LightType::Point;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot: the cone's axis; directional: where light goes
  float inner_deg = 25.0f, outer_deg = 30.0f;  // spot: 0 <= inner <= outer, 0 < outer <= 90
  Falloff falloff = Falloff::None;             // Whitted, point and spot lights
};
// The spot cone's widest half-angle (degrees): a hemisphere.
constexpr float kMaxSpotDeg = 90.0f;

// The camera (docs/camera.md): a perspective camera with a vertical field of view in degrees,
// a pinhole or, with aperture > 0, a thin lens focused at focus_distance; or an orthographic
// camera whose view is ortho_height scene units tall.
enum class Projection { Perspective, Orthographic };
// What the kernels generate rays for (a kernel variant each): a perspective camera with
// aperture 0 is the pinhole, with aperture > 0 the thin lens.
enum class CameraKind { Pinhole, Orthographic, ThinLens };
struct Camera {
  glm::vec3 eye{0.0f, 0.0f, 5.0f};
  glm::vec3 look_at{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y = 45.0f;
  Projection projection = Projection::Perspective;
  float ortho_height = 2.0f;    // orthographic: the view's height in scene units
  float aperture = 0.0f;        // perspective: the lens's radius in scene units; 0 = a pinhole
  float focus_distance = 0.0f;  // thin lens: the focal plane's distance; 0 = |look_at - eye|
};

// The values of SceneOptions' accelerator settings, which the scene formats and the command
// line accept and accel/ acts on (Grid.h, LightBuffer.h).
constexpr double kGridDensity = 4.0;  // voxels per triangle of the automatic resolution
// grid_density left to the renderer: chosen from the scene and the backend (Grid.h,
// grid_density_for).
constexpr double kGridDensityAuto = -1.0;
constexpr double kGridDensityMin = 0.125, kGridDensityMax = 256.0;
constexpr int32_t kNoSubgrids = 0;     // a one-level grid
constexpr int32_t kSubgridsAuto = -1;  // subgrids where the backend runs on the CPU
constexpr int kLightBufferAuto = -1;   // a light buffer where the scene has shadows
constexpr int kLightBufferOff = 0;
constexpr int kLightBufferMaxRes = 1024;  // cells per cube face edge

// How light is carried (docs/path-tracing.md): the thesis's Whitted ray tracing (point lights,
// hard shadows, perfect mirrors and glass, Phong's non-radiometric local light), or
// unidirectional path tracing in radiometric units.
enum class Integrator { Whitted, Path };
const char* integrator_name(Integrator i);  // "whitted", "path"
// Throws SceneError naming the bad value and the integrators there are.
Integrator parse_integrator(const std::string& s);

// The most samples per pixel a scene or a render may ask for (2^20: enough for references).
constexpr int kMaxSpp = 1 << 20;
// Whitted's area light samples per shaded point (options.light_samples).
constexpr int kMaxLightSamples = 1024;

struct SceneOptions {
  bool shadows = true;   // hard shadows from every light
  float ambient = 0.1f;  // ambient term: ambient * Kd
  int max_depth = 5;     // reflection / refraction bounces after the primary ray
  int grid = 0;          // grid cells per axis; 0 = automatic (see Grid.h)
  // Voxels listing more triangles get a subgrid; 0 = none; -1 (kSubgridsAuto, the default):
  // chosen for the backend that renders (Grid.h, subgrid_min_for).
  int subgrid_min = kSubgridsAuto;
  // Voxels per triangle of the automatic resolution; kGridDensityAuto (the default): chosen
  // for the scene and the backend that renders (Grid.h, grid_density_for).
  double grid_density = kGridDensityAuto;
  // The shadow rays' light buffer (accel/LightBuffer.h): -1 (kLightBufferAuto) chosen from
  // the scene, 0 off (shadow rays walk the grid), or cells per cube face edge.
  int light_buffer = kLightBufferAuto;
  int spp = 1;                 // samples per pixel, 1..kMaxSpp
  bool smooth_normals = true;  // interpolate vertex normals where the mesh has them
  Integrator integrator = Integrator::Whitted;
  // The path integrator's random sequence (rill/Random.h's Philox key): another seed,
  // another independent image of the same expectation.
  uint32_t seed = 0;
  bool nee = true;  // path: next-event estimation (light sampling at each surface)
  bool mis = true;  // path: multiple importance sampling of NEE and BSDF sampling
  // Whitted: shadow rays to the area lights (points drawn on all emitting triangles
  // together) at each shaded point (kernel/Shading.h).
  int light_samples = 16;
};

struct Scene {
  std::string name;
  // What loading the scene noticed without failing (an MTL file that is not there, ...),
  // one line each naming the file; rill-trace prints them and puts them in --stats-json.
  std::vector<std::string> warnings;
  Camera camera;
  bool has_camera = false;  // false: frame the geometry (default_camera)
  // The camera is the framing camera (Framing.h; the scene set none), made for the image
  // size the scene had when loaded: rill-trace makes it again for --size and --up-axis.
  bool camera_framed = false;
  // The index in lights of the light placed for the framing camera (an OBJ rendered alone),
  // or -1: rill-trace moves it with the camera (framing_light_position).
  int framing_light = -1;
  int width = 512, height = 512;

  // Three vertices per triangle, in primitive-id order.
  std::vector<glm::vec3> positions;
  // Three vertex normals per triangle, or empty. A triangle without normals in a mesh that
  // has some gets its geometric normal at all three vertices.
  std::vector<glm::vec3> normals;
  // Three vertex colours per triangle (multiplying Kd), or empty.
  std::vector<glm::vec3> colors;
  // Three texture coordinates per triangle, or empty. A triangle without them in a scene
  // that has some gets (0, 0) at its three vertices.
  std::vector<glm::vec2> texcoords;
  std::vector<Texture> textures;  // what materials' parameters bind (ParamValue::texture)
  std::vector<int32_t> material;  // per triangle, index into materials
  std::vector<Material> materials;

  std::vector<Light> lights;
  glm::vec3 background{0.1f, 0.1f, 0.15f};
  SceneOptions options;
  // Dynamic scenes (scene/Animation.h): the time range, the objects that move (ranges of the
  // triangles above, stored at rest) and the camera's keys. Empty for a static scene.
  Animation animation;

  size_t triangle_count() const { return material.size(); }
  int add_material(const Material& m);  // returns its index
  // Appends a triangle with material index mat (and optional per-vertex normals, colours
  // and texture coordinates: three of each).
  void add_triangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, int mat,
                    const glm::vec3* n = nullptr, const glm::vec3* col = nullptr,
                    const glm::vec2* uv = nullptr);
  // Appends all of other's triangles, materials and textures (the appended materials'
  // texture parameters are renumbered) and its animated objects (their triangle ranges
  // renumbered); lights, camera and time range are not taken.
  void append(const Scene& other);
  // Checks invariants (sizes, finite materials, texture coordinates, textures and lights,
  // texture indices of material parameters, camera, image size, animated objects' ranges and
  // keys); throws SceneError.
  // Triangles with non-finite vertices are allowed: they are never hit.
  void validate() const;
};

// The camera checks of Scene::validate (finite, fov_y in (0, 180), eye not at look_at, up not
// along the view), with messages starting "where: ". Dynamic scenes check every key, and
// rill-trace each frame's interpolated camera.
// The most triangles a scene may hold (Scene::validate; the JSON reader checks it before it
// makes a shape or copies an instance).
inline constexpr size_t kMaxTriangles = size_t{1} << 26;

void check_camera(const Camera& camera, const std::string& where);
// The projection's and lens's part of check_camera: finite values, an orthographic height > 0,
// aperture and focus_distance >= 0 (0: the defaults), no aperture on an orthographic camera.
void check_lens(const Camera& camera, const std::string& where);
// A material's values whatever its shader: a shader named, every parameter finite, colours
// >= 0, texture parameters within texture_count. Throws SceneError naming the material. What
// a shader asks of its own parameters (reflect + transmit <= 1, the ranges of shininess and
// ior) is its SurfaceShader::check, which resolve_shaders runs (shaders/Registry.h).
void validate_material(const Material& m, size_t texture_count);

// Bounding box of the finite triangles; returns false if there are none.
bool scene_bounds(const Scene& s, glm::vec3& lo, glm::vec3& hi);

// The framing camera of an image of the scene's size (Framing.h, framing_camera), for a
// scene that sets no camera. Defined in Framing.cpp.
Camera default_camera(const Scene& s);

// Placement of a mesh: scale, then rotate about x, y, z (degrees), then translate.
struct Transform {
  glm::vec3 scale{1.0f};
  glm::vec3 rotate_deg{0.0f};
  glm::vec3 translate{0.0f};
  glm::vec3 apply_point(const glm::vec3& p) const;
  glm::vec3 apply_normal(const glm::vec3& n) const;  // not normalized
  bool identity() const;
};

// OBJ + MTL. Polygons are fanned (v0, vk, vk+1). Materials come from the MTL files the OBJ
// names (Kd, Ks, Ns, Ni, d, illum: see docs/scene-format.md); faces without one get
// `fallback` (or a default grey). If `override_material` is set, every face gets it.
//
// Lines that Rill's reading of OBJ and MTL does not accept (ObjSyntax.h: "v abc def", an
// unknown statement, a face of two vertices) are warnings naming file and line (the first
// few, then a count), or errors under InputOptions::strict. A file that gives no triangles is
// an error unless InputOptions::allow_empty.
struct InputOptions {
  bool strict = false;       // rill-trace --strict-input: malformed lines are errors
  bool allow_empty = false;  // rill-trace --allow-empty: a mesh file without faces is no error
};
struct ObjLoadOptions {
  Transform transform;
  const Material* override_material = nullptr;
  InputOptions input;
  // When set, receives each triangle's three OBJ vertex numbers (0-based, in the order of
  // its corners): an OBJ sequence compares them to check that its topology stays the same.
  std::vector<int32_t>* corners = nullptr;
  // Vertex normals for the faces of a file that give no `vn` (VertexNormals.h): off, or on
  // with faces that meet at more than crease_degrees keeping a hard edge. Faces with `vn`
  // keep their own.
  bool smooth = true;
  float crease_degrees = kDefaultCreaseDegrees;
  NormalWeighting normal_weighting = NormalWeighting::Angle;
  // The textures override_material's texture parameters refer to (the scene it comes from),
  // so that faces without `vt` on a material that reads texture coordinates get a warning.
  const std::vector<Texture>* override_textures = nullptr;
};
Scene load_obj(const std::string& path, const ObjLoadOptions& opt = {});

// Built-in scenes: "thesis-a" (3 boxes, 36 triangles), "thesis-b" (cubes in a room, 2064),
// "thesis-c" (high- and low-polygon objects with a tessellated Utah teapot, 61562),
// "cornell" (Cornell box), "cornell-path" (the same with diffuse walls and an area light, for
// the path integrator), "glass" (glass and mirrors), "textured" (procedural and bitmap
// textures, a mirror shader), "bounce" (scene B with balls bouncing and cubes spinning: a
// dynamic scene of 4 seconds), "empty".
std::vector<std::string> builtin_scene_names();
Scene builtin_scene(const std::string& name);

// Shapes the built-in scenes and JSON files are made of (appended to `s` with material mat),
// with texture coordinates: a quad maps a, b, c, d to (0, 0), (1, 0), (1, 1), (0, 1); each
// face of a box is such a quad; a sphere has u = longitude / 360 degrees (growing
// counter-clockwise seen from +y) and v from 0 at the south pole to 1 at the north; the
// teapot has each Bezier patch's own (u, v).
void add_box(Scene& s, const glm::vec3& lo, const glm::vec3& hi, int mat, const Transform& t = {},
             bool inward = false);
void add_quad(Scene& s, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c,
              const glm::vec3& d, int mat);
void add_sphere(Scene& s, const glm::vec3& center, float radius, int slices, int stacks, int mat,
                bool smooth = true);
// The Utah teapot (32 Bezier patches), each patch cut into n x n quads (2 triangles each):
// 64 n^2 triangles. Base on y = 0, spout along +x, height about 3.15 * scale.
void add_teapot(Scene& s, int n, int mat, const Transform& t = {}, bool smooth = true);

}  // namespace rt
