// The wavefront strategy (raytracer/rill/rt/wavefront/), per backend: the path integrator's
// images are bitwise the megakernel's, AOVs and ray counts included, on the Cornell box with
// its area light and on a scene of point lights, glass and GGX (with and without next-event
// estimation, the latter launching no shadow kernel), and a window's pixels are the whole
// render's; the bounce rays it reads back start where the path's last ray hit. Host only: it
// refuses Whitted's tracer, and the multipass strategy the path integrator, each with a
// message that says what to use instead.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

class Wavefront : public ::testing::TestWithParam<std::string> {};

RenderSettings settings(const std::string& backend, int width, int height, int spp) {
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
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
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
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

// The bounce rays read back from the wavefront (render/BounceRays.h; rill-bench-trace's bounce
// section) are the path tracer's own: on the Cornell box, each ray after two scatterings
// starts where the same path's ray after one scattering hits (traced again here by the
// tracer's intersector: the origin is that hit offset off the surface by some ulps), heads in
// a unit direction, and there are some but at most as many as after one scattering. Reading
// them back leaves the image as it was, and the megakernel refuses the request.
TEST(WavefrontStrategy, BounceRaysStartWhereTheLastBounceHit) {
  const Scene s = builtin_scene("cornell-path");
  Tracer t(s, build_grid_for(s));
  RenderSettings rs = settings("cpu", 16, 16, 2);
  rs.strategy = Strategy::Wavefront;
  const RenderResult plain = t.render(rs, s.camera);
  BounceRays one, two;
  one.bounce = 1;
  two.bounce = 2;
  rs.bounce_rays = &one;
  const RenderResult read_back = t.render(rs, s.camera);
  ASSERT_EQ(read_back.color.size(), plain.color.size());
  EXPECT_EQ(std::memcmp(read_back.color.data(), plain.color.data(),
                        plain.color.size() * sizeof(glm::vec3)),
            0);
  rs.bounce_rays = &two;
  (void)t.render(rs, s.camera);
  ASSERT_GT(two.size(), 0u);
  EXPECT_LE(two.size(), one.size());
  EXPECT_LE(one.size(), size_t{16 * 16 * 2});
  ASSERT_EQ(two.directions.size(), two.size());
  ASSERT_EQ(two.pixels.size(), two.size());
  ASSERT_EQ(two.samples.size(), two.size());

  std::vector<int32_t> prim;
  std::vector<float> dist;
  t.intersect("cpu", one.origins, one.directions, prim, dist);
  // How far off its surface Shading::offset_origin moves an origin: each coordinate by the
  // scene's epsilon e (within 1/32 of 0) or by 8 ulps, which is less than e = max(2e-5 of the
  // scene's diagonal, 1e-6 of its largest coordinate) (Shading::upload), so sqrt(3) e in
  // all; the hit point (from the barycentrics) and o + t d here round by some ulps of the
  // coordinates more, which 1e-5 of them covers 80 times over.
  glm::vec3 lo(s.positions[0]), hi(s.positions[0]);
  for (const glm::vec3& p : s.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const float mag = std::max(glm::length(lo), glm::length(hi));
  const float e = std::max(2e-5f * glm::length(hi - lo), 1e-6f * mag);
  const float tolerance = std::sqrt(3.0f) * e + 1e-5f * mag;
  std::map<std::pair<int32_t, int32_t>, size_t> first;  // (sample, pixel) -> ray after one
  for (size_t j = 0; j < one.size(); ++j) first[{one.samples[j], one.pixels[j]}] = j;
  for (size_t i = 0; i < two.size(); ++i) {
    EXPECT_NEAR(glm::length(two.directions[i]), 1.0f, 1e-5f) << "ray " << i;
    const auto it = first.find({two.samples[i], two.pixels[i]});
    ASSERT_NE(it, first.end()) << "ray " << i << ": its path had no ray after one scattering";
    const size_t j = it->second;
    ASSERT_GE(prim[j], 0) << "ray " << i << ": its path's last ray hit nothing";
    const glm::vec3 hit = one.origins[j] + dist[j] * one.directions[j];
    EXPECT_LT(glm::length(two.origins[i] - hit), tolerance) << "ray " << i;
    if (i > 0) {  // sample after sample, pixels in order
      EXPECT_LT(std::make_pair(two.samples[i - 1], two.pixels[i - 1]),
                std::make_pair(two.samples[i], two.pixels[i]));
    }
  }

  rs.strategy = Strategy::Megakernel;
  EXPECT_THROW(t.render(rs, s.camera), std::runtime_error);
}

}  // namespace
}  // namespace rt
