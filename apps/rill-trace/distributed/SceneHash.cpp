// The scene hash (SceneHash.h).
#include "distributed/SceneHash.h"

#include <cstring>
#include <type_traits>
#include <vector>

namespace rt::distributed {

namespace {

class Fnv1a {
 public:
  void bytes(const void* p, size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h_ = (h_ ^ b[i]) * 0x100000001b3ull;
  }
  template <class T>
  requires std::is_arithmetic_v<T> || std::is_enum_v<T>
  void add(T v) { bytes(&v, sizeof v); }
  void add(const glm::vec2& v) { bytes(&v, sizeof v); }
  void add(const glm::vec3& v) { bytes(&v, sizeof v); }
  void add(const glm::dvec3& v) { bytes(&v, sizeof v); }
  void add(const glm::dquat& q) { bytes(&q, sizeof q); }
  void add(const std::string& s) {
    add(s.size());
    bytes(s.data(), s.size());
  }
  // Vectors of plain values (floats, ints, glm vectors): their length, then their bytes.
  template <class T>
  requires std::is_trivially_copyable_v<T>
  void add(const std::vector<T>& v) {
    add(v.size());
    bytes(v.data(), v.size() * sizeof(T));
  }
  uint64_t value() const { return h_; }

 private:
  uint64_t h_ = 0xcbf29ce484222325ull;
};

}  // namespace

namespace {

uint64_t hash(const Scene& s, const std::string& settings, bool with_spp) {
  Fnv1a h;
  h.add(settings);
  h.add(s.camera.eye), h.add(s.camera.look_at), h.add(s.camera.up), h.add(s.camera.fov_y);
  h.add(s.has_camera), h.add(s.width), h.add(s.height);
  h.add(s.positions), h.add(s.normals), h.add(s.colors), h.add(s.texcoords), h.add(s.material);
  h.add(s.textures.size());
  for (const Texture& t : s.textures) {
    h.add(t.name), h.add(t.type), h.add(t.width), h.add(t.height), h.add(t.texels);
    h.add(t.wrap), h.add(t.bilinear), h.add(t.color1), h.add(t.color2), h.add(t.scale);
  }
  h.add(s.materials.size());
  for (const Material& m : s.materials) {
    h.add(m.name), h.add(m.shader), h.add(m.emission), h.add(m.emission_texture), h.add(m.two_sided), h.add(m.params.size());
    for (const auto& [name, p] : m.params) {
      h.add(name), h.add(p.kind), h.add(p.number), h.add(p.color), h.add(p.texture);
    }
  }
  h.add(s.lights.size());
  for (const Light& l : s.lights) {
    h.add(l.position), h.add(l.color);
    // A point light without falloff hashes as before these keys existed (saved files stay
    // valid).
    if (l.type != LightType::Point || l.falloff != Falloff::None)
      h.add(l.type), h.add(l.direction), h.add(l.inner_deg), h.add(l.outer_deg), h.add(l.falloff);
  }
  h.add(s.background);
  const SceneOptions& o = s.options;
  h.add(o.shadows), h.add(o.ambient), h.add(o.max_depth), h.add(o.grid), h.add(o.subgrid_min);
  h.add(o.grid_density), h.add(with_spp ? o.spp : 1), h.add(o.smooth_normals);
  h.add(o.integrator), h.add(o.seed), h.add(o.nee), h.add(o.mis), h.add(o.light_samples);
  // Animation (docs/dynamic-scenes.md): a distributed render is the first frame, but which
  // frame that is and where everything is then come from all of it.
  const Animation& a = s.animation;
  h.add(a.time.start), h.add(a.time.end), h.add(a.time.fps), h.add(a.objects.size());
  for (const AnimatedObject& ob : a.objects) {
    h.add(ob.name), h.add(ob.first), h.add(ob.count), h.add(ob.shape_fps);
    h.add(ob.track.interpolation), h.add(ob.track.keys.size());
    for (const PoseKey& k : ob.track.keys) {
      h.add(k.time), h.add(k.pose.translate), h.add(k.pose.rotation), h.add(k.pose.scale);
    }
    h.add(ob.shapes.size());
    for (const std::vector<glm::vec3>& shape : ob.shapes) h.add(shape);
    h.add(ob.shape_normals.size());
    for (const std::vector<glm::vec3>& normals : ob.shape_normals) h.add(normals);
  }
  h.add(a.camera.interpolation), h.add(a.camera.keys.size());
  for (const CameraKey& k : a.camera.keys) {
    h.add(k.time), h.add(k.camera.eye), h.add(k.camera.look_at), h.add(k.camera.up);
    h.add(k.camera.fov_y);
  }
  return h.value();
}

}  // namespace

uint64_t scene_hash(const Scene& s, const std::string& settings) {
  return hash(s, settings, true);
}

uint64_t accumulation_hash(const Scene& s, const std::string& settings) {
  return hash(s, settings, false);
}

}  // namespace rt::distributed
