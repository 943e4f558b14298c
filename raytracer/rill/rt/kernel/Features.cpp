// The kernel features a scene calls for (Features.h).
#include "rill/rt/kernel/Features.h"

#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/LightShape.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/scene/Camera.h"
#include "rill/rt/scene/Scene.h"

namespace rt {

std::string Features::str() const {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += ' ';
    s += name;
  };
  add(geometry, "geometry");
  add(lights, "lights");
  add(area_lights, "area-lights");
  add(light_shapes, "light-shapes");
  add(shadows, "shadows");
  add(specular, "specular");
  add(reflection, "reflection");
  add(refraction, "refraction");
  add(vertex_normals, "vertex-normals");
  add(vertex_colors, "vertex-colors");
  add(texcoords, "texcoords");
  add(dynamic, "dynamic");
  add(camera == CameraKind::Orthographic, "orthographic");
  add(camera == CameraKind::ThinLens, "thin-lens");
  if (stack > 0) s += " stack=" + std::to_string(stack);
  return s.empty() ? "none" : s;
}

std::vector<bool> used_materials(const Scene& s) {
  std::vector<bool> used(s.materials.size());
  for (size_t t = 0; t < s.triangle_count(); ++t)
    if (triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]))
      used[static_cast<size_t>(s.material[t])] = true;
  // A moving triangle may be degenerate at rest (a sequence's first file collapsed to a
  // point, say) and not later: every animated triangle counts, at rest or not.
  for (const AnimatedObject& o : s.animation.objects)
    for (size_t t = o.first; t < o.first + o.count; ++t)
      used[static_cast<size_t>(s.material[t])] = true;
  return used;
}

Features scene_features(const Scene& s, const MaterialShaders& shaders) {
  Features f;
  const std::vector<bool> used = used_materials(s);
  for (bool u : used) f.geometry = f.geometry || u;
  for (const AnimatedObject& o : s.animation.objects) f.dynamic = f.dynamic || o.count > 0;
  f.lights = !s.lights.empty() && f.geometry;
  f.light_shapes = f.lights && any_light_shaped(s);
  if (s.options.integrator == Integrator::Whitted)
    for (size_t m = 0; m < s.materials.size(); ++m)
      f.area_lights = f.area_lights || (used[m] && s.materials[m].emits());
  f.shadows = (f.lights || f.area_lights) && s.options.shadows;
  for (size_t m = 0; m < s.materials.size(); ++m) {
    if (!used[m]) continue;
    const Material& mat = s.materials[m];
    if (mat.emits() && mat.emission_texture >= 0) f.texcoords = true;
    const SurfaceShader& sh = *shaders.at(m);
    const MaterialParams params(mat, sh.params);
    const Lobes lobes = sh.lobes ? sh.lobes(params) : Lobes{};
    f.reflection = f.reflection || lobes.reflect;
    f.refraction = f.refraction || lobes.transmit;
    for (const ShaderParam& p : sh.params) {
      if ((f.lights || f.area_lights) && p.name == "specular" && params.nonzero("specular"))
        f.specular = true;
      if (params.get(p.name).kind == ParamValue::Kind::Texture) f.texcoords = true;
    }
  }
  // Refraction always needs the reflection code too (Fresnel, total internal reflection).
  if (f.refraction) {
    f.reflection = true;
    f.stack = kRayStack;
  }
  f.vertex_normals = f.geometry && !s.normals.empty() && s.options.smooth_normals;
  f.vertex_colors = f.geometry && !s.colors.empty();
  f.texcoords = f.texcoords && f.geometry && !s.texcoords.empty();
  f.camera = camera_kind(s.camera);
  return f;
}

}  // namespace rt
