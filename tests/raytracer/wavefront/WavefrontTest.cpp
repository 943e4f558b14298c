// The wavefront strategy (raytracer/rill/rt/wavefront/), per backend: the path integrator's
// images are bitwise the megakernel's, AOVs and ray counts included, on the Cornell box with
// its area light and on a scene of point lights, glass and GGX (with and without next-event
// estimation, the latter launching no shadow kernel), and a window's pixels are the whole
// render's. Host only: it refuses Whitted's tracer, and the multipass strategy the path
// integrator, each with a message that says what to use instead.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

class Wavefront : public ::testing::TestWithParam<std::string> {};

RenderSettings settings(const std::string& backend, int width, int height, int spp) {
  RenderSettings rs;
  rs.backend = backend;
  rs.width = width;
  rs.height = height;
  rs.spp = spp;
  return rs;
}

// The wavefront render is the megakernel's, bit for bit (colour compared with memcmp, the
// AOVs and the ray count as RenderCompare.h does).
void expect_same_as_megakernel(Tracer& t, const Scene& s, RenderSettings rs,
                               const std::string& what) {
  rs.strategy = Strategy::Megakernel;
  const RenderResult mega = t.render(rs, s.camera);
  rs.strategy = Strategy::Wavefront;
  const RenderResult wave = t.render(rs, s.camera);
  ASSERT_EQ(mega.color.size(), static_cast<size_t>(rs.width) * rs.height) << what;
  ASSERT_EQ(wave.color.size(), mega.color.size()) << what;
  EXPECT_EQ(
      std::memcmp(wave.color.data(), mega.color.data(), mega.color.size() * sizeof(glm::vec3)), 0)
      << what;
  testing::expect_identical(mega, wave, what);
  EXPECT_GT(wave.rays, int64_t{rs.width} * rs.height) << what;
  ASSERT_EQ(wave.passes.size(), 4u) << what;
  EXPECT_EQ(wave.passes[0].name, "camera");
  EXPECT_EQ(wave.passes[0].calls, rs.spp) << what;
}

TEST_P(Wavefront, CornellPathIsTheMegakernelsImage) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = builtin_scene("cornell-path");
  ASSERT_EQ(s.options.integrator, Integrator::Path);
  Tracer t(s, build_grid_for(s));
  expect_same_as_megakernel(t, s, settings(GetParam(), 24, 24, 4), "cornell-path");
}

// A floor, a glass sphere and a GGX sphere under a point light, path traced: point lights
// (delta light samples), refraction and a rough specular lobe.
Scene glass_and_ggx(bool nee) {
  Scene s;
  s.name = "wavefront-glass-ggx";
  Material floor;
  floor.name = "floor";
  floor.shader = "diffuse";
  floor.set("diffuse", glm::vec3(0.7f, 0.6f, 0.5f));
  Material glass;
  glass.name = "glass";
  glass.shader = "glass";
  glass.set("transmit", 0.9f);
  Material metal;
  metal.name = "metal";
  metal.shader = "ggx";
  metal.set("roughness", 0.4f).set("diffuse", glm::vec3(0.2f, 0.3f, 0.6f));
  const int f = s.add_material(floor), g = s.add_material(glass), m = s.add_material(metal);
  add_quad(s, {-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}, f);
  add_sphere(s, {-1.1f, 1.0f, 0.0f}, 1.0f, 12, 6, g);
  add_sphere(s, {1.1f, 1.0f, -0.5f}, 1.0f, 12, 6, m);
  s.lights = {Light{{2, 5, 3}, glm::vec3(30.0f)}};
  s.background = glm::vec3(0.2f, 0.25f, 0.3f);
  s.camera = Camera{{0.0f, 2.0f, 6.0f}, {0.0f, 0.8f, 0.0f}, {0.0f, 1.0f, 0.0f}, 50.0f};
  s.has_camera = true;
  s.options.integrator = Integrator::Path;
  s.options.max_depth = 4;
  s.options.nee = nee;
  return s;
}

TEST_P(Wavefront, PointLightsGlassAndGgxAreTheMegakernelsImageAndWindowsItsPixels) {
  RT_REQUIRE_BACKEND(GetParam());
  for (const bool nee : {true, false}) {
    const std::string what = nee ? "glass and ggx" : "glass and ggx without NEE";
    const Scene s = glass_and_ggx(nee);
    Tracer t(s, build_grid_for(s));
    RenderSettings rs = settings(GetParam(), 20, 14, 2);
    expect_same_as_megakernel(t, s, rs, what);
    if (!nee) continue;
    // A window's pixels are the whole render's: the random numbers are keyed by the pixel's
    // place in the whole image.
    rs.strategy = Strategy::Wavefront;
    const RenderResult whole = t.render(rs, s.camera);
    rs.window = {5, 3, 9, 7};
    const RenderResult part = t.render(rs, s.camera);
    ASSERT_EQ(part.width, 9);
    ASSERT_EQ(part.height, 7);
    for (int y = 0; y < part.height; ++y)
      for (int x = 0; x < part.width; ++x) {
        const size_t p = static_cast<size_t>(y) * part.width + x;
        const size_t q = static_cast<size_t>(y + 3) * whole.width + (x + 5);
        EXPECT_EQ(std::memcmp(&part.color[p], &whole.color[q], sizeof(glm::vec3)), 0)
            << "window pixel (" << x << ", " << y << ")";
        EXPECT_EQ(part.prim[p], whole.prim[q]);
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Wavefront, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

// The message of the std::runtime_error that rendering with `strategy` throws.
std::string refusal(const Scene& s, const Strategy& strategy) {
  Tracer t(s, build_grid_for(s));
  RenderSettings rs;
  rs.width = 4;
  rs.height = 4;
  rs.strategy = strategy;
  try {
    t.render(rs, s.camera);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << strategy.name << " rendered";
  return {};
}

TEST(WavefrontStrategy, RefusesWhittedAndMultipassRefusesThePathIntegrator) {
  const Scene whitted = builtin_scene("cornell");
  ASSERT_EQ(whitted.options.integrator, Integrator::Whitted);
  EXPECT_EQ(refusal(whitted, Strategy::Wavefront),
            "the wavefront strategy runs the path integrator; use megakernel or multipass for "
            "whitted");
  const std::string multipass = refusal(builtin_scene("cornell-path"), Strategy::Multipass);
  EXPECT_NE(multipass.find("multipass runs the Whitted tracer, not the path integrator"),
            std::string::npos)
      << multipass;
}

}  // namespace
}  // namespace rt
