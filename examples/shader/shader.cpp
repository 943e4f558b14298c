// Write your own surface shader: "toon" (cel shading) lights a surface in a few flat bands
// and adds a bright rim where it turns away from the viewer. It is registered under its name,
// two materials of the built-in textured scene switch to it, and the render goes to a PNG.
//
//   rill-shader-example [OUT.png [SIZE]]     (default shader.png, 256)
//
// Exit status 1 when the toon surfaces do not show the shader's few flat colours.
#include <rill/rt/Tracer.h>
#include <rill/rt/scene/Image.h>
#include <rill/rt/shaders/Registry.h>

#include <cstdio>
#include <exception>
#include <set>
#include <string>
#include <tuple>

using rill::Float;

rt::SurfaceShader toon_shader() {
  rt::SurfaceShader toon;
  toon.name = "toon";
  toon.doc = "cel shading: light in flat bands, and a bright rim";
  toon.params = {
      {"color", rt::ParamType::Color, rt::ParamValue::of(glm::vec3(0.9f, 0.4f, 0.1f)), "colour"},
      {"bands", rt::ParamType::Number, rt::ParamValue::of(3.0f), "levels of light"},
      {"rim", rt::ParamType::Number, rt::ParamValue::of(0.3f),
       "rim where cos(normal, view) < rim"}};
  // Without the light loop: ambient light, and the rim where the surface turns away.
  toon.emitted = [](const rt::ShadingPoint& sp) {
    Float rim = select(dot(sp.s.nf, sp.s.V) < sp.number("rim"), Float(0.6f), Float(0.0f));
    return sp.color("color") * sp.ambient() + rim;
  };
  // Each light the tracer found unshadowed: its diffuse light, rounded down to a band.
  toon.reflected = [](const rt::ShadingPoint& sp, const rt::LightSample& light) {
    Float bands = sp.number("bands");
    Float level = floor(max(dot(sp.s.nf, light.L), 0.0f) * bands) / bands;
    return sp.color("color") * level * light.color;
  };
  return toon;  // no scatter: the path ends here, no reflected or transmitted rays
}

int main(int argc, char** argv) try {
  const std::string out = argc > 1 ? argv[1] : "shader.png";
  const int size = argc > 2 ? std::stoi(argv[2]) : 256;
  rt::register_shader(toon_shader());

  rt::Scene scene = rt::builtin_scene("textured");
  for (rt::Material& m : scene.materials) {
    if (m.name != "marble" && m.name != "striped") continue;
    rt::Material toon;
    toon.name = m.name;
    toon.shader = "toon";
    if (m.name == "striped") {  // a blue box with two bands; the sphere keeps the defaults
      toon.params["color"] = rt::ParamValue::of(glm::vec3(0.2f, 0.4f, 0.9f));
      toon.params["bands"] = rt::ParamValue::of(2.0f);
    }
    m = toon;
  }
  rt::Tracer tracer(scene, rt::build_grid_for(scene));
  rt::RenderSettings settings;  // cpu, megakernel, strict
  settings.width = settings.height = size;
  settings.outputs.prim = true;  // which material each pixel shows, counted below
  rt::RenderResult image = tracer.render(settings, scene.camera);
  rt::write_png(out, image.width, image.height, image.color);

  // Toon surfaces take a handful of flat colours (bands x lights x rim); Phong takes hundreds.
  int pixels = 0;
  std::set<std::tuple<float, float, float>> colors;
  for (size_t p = 0; p < image.color.size(); ++p) {
    if (image.prim[p] < 0) continue;
    const int material = scene.material[static_cast<size_t>(image.prim[p])];
    if (scene.materials[static_cast<size_t>(material)].shader != "toon") continue;
    ++pixels;
    colors.insert({image.color[p].r, image.color[p].g, image.color[p].b});
  }
  const bool ok = pixels > size * size / 50 && colors.size() >= 3 && colors.size() <= 40;
  std::printf("%s: %dx%d, %d toon pixels in %zu colours: %s\n", out.c_str(), image.width,
              image.height, pixels, colors.size(), ok ? "OK" : "WRONG");
  return ok ? 0 : 1;
} catch (const std::exception& e) {
  std::fprintf(stderr, "rill-shader-example: %s\n", e.what());
  return 1;
}
