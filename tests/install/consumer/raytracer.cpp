// A user of an installed rill::raytracer: registers a shader of its own, switches the Cornell
// box's red wall to it, renders a small image on the cpu backend and checks that the wall
// shows the shader's colour and the rest of the box its usual shading.
#include <rill/rt/Tracer.h>
#include <rill/rt/shaders/Registry.h>

#include <algorithm>
#include <cstdio>
#include <exception>

namespace {

// The shader's colour, exactly: a flat, unlit shader whose colour is its parameter "color".
const glm::vec3 kFlat(0.25f, 0.5f, 1.0f);

void register_flat() {
  rt::SurfaceShader flat;
  flat.name = "consumer_flat";
  flat.doc = "the colour `color`, unlit";
  flat.params = {
      {"color", rt::ParamType::Color, rt::ParamValue::of(glm::vec3(1.0f)), "its colour"}};
  flat.emitted = [](const rt::ShadingPoint& sp) { return sp.color("color"); };
  rt::register_shader(flat);
}

}  // namespace

int main() try {
  register_flat();
  rt::Scene scene = rt::builtin_scene("cornell");
  for (rt::Material& m : scene.materials)
    if (m.name == "red") {
      m.shader = "consumer_flat";
      m.params["color"] = rt::ParamValue::of(kFlat);
    }
  rt::Tracer tracer(scene, rt::build_grid_for(scene));
  rt::RenderSettings rs;
  rs.outputs.prim = true;  // which pixels hit, read below
  rs.backend = "cpu";
  rs.width = rs.height = 32;
  rs.spp = 1;
  const rt::RenderResult image = tracer.render(rs, scene.camera);

  int flat = 0, lit = 0;  // pixels of the shader's colour; hits of any other colour
  for (size_t p = 0; p < image.color.size(); ++p) {
    if (image.color[p] == kFlat)
      ++flat;
    else if (image.prim[p] >= 0)
      ++lit;
  }
  std::vector<std::string> used = tracer.shaders();  // the shaders generated into the kernel
  std::sort(used.begin(), used.end());
  const bool uses_shader = used == std::vector<std::string>{"consumer_flat", "phong"};
  // The red wall is the left fifth of the view; the rest is white and green.
  const bool ok = uses_shader && flat > 32 && lit > 5 * flat / 2;
  std::printf("raytracer consumer: %dx%d, %d pixels of the user shader, %d other hits: %s\n",
              image.width, image.height, flat, lit, ok ? "OK" : "WRONG");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "raytracer consumer: %s\n", e.what());
  return 1;
}
