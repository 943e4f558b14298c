// Spot and directional lights and Whitted's inverse-square falloff (scene/Scene.h, Light;
// kernel/LightShape.h) in both integrators, against the formulas pixel by pixel: a floor seen
// straight down, where each pixel's centre (the only sample at spp 1, in both integrators)
// is a known floor point, lit by one delta light. Nothing is random there: the path
// integrator's one light sample is the light (probability 1) and its bounce ray leaves for a
// black sky, so its pixels are exact too, up to float rounding (1e-4 relative allows the
// camera ray's few ulps of position, amplified at most ~40 times by the cone's steepest slope
// at 20/30 degrees). Then a directional light's shadow (its shadow rays have no end, with and
// without a light buffer), the kernels of scenes without these lights (unchanged), and every
// backend and strategy giving the cpu's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/kernel/LightShape.h"

namespace rt {
// Named: the unity build puts other test files' anonymous helpers in the same unit.
namespace light_types_test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kCamY = 2.0f;  // the camera's height over the floor
constexpr float kKd = 0.6f;    // the floor's diffuse reflectance

// A floor (y = 0, half-size 4) of diffuse reflectance kKd seen from (0, kCamY, 0) straight down
// with a 90 degree field of view: pixel (c, r)'s centre is the floor point (x(c), 0, +-x(r))
// with x(c) = kCamY (2 (c + 0.5) / W - 1) (the sign of z left open: the tests' lights are
// symmetric in z). No ambient light, a black background. Under Whitted the floor is phong
// without highlight, under path the Lambertian `diffuse` shader: Kd E cos and Kd / pi E cos.
Scene floor_scene(Integrator integrator, int size) {
  Scene s;
  s.name = "light-types-floor";
  Material m;
  m.name = "floor";
  m.shader = integrator == Integrator::Path ? "diffuse" : "phong";
  m.set("diffuse", glm::vec3(kKd));
  if (integrator == Integrator::Whitted) m.set("specular", glm::vec3(0.0f));
  const int floor = s.add_material(m);
  add_quad(s, {-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, floor);
  s.camera = Camera{{0.0f, kCamY, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 90.0f};
  s.has_camera = true;
  s.width = s.height = size;
  s.background = glm::vec3(0.0f);
  s.options.ambient = 0.0f;
  s.options.integrator = integrator;
  s.options.max_depth = integrator == Integrator::Path ? 1 : 0;
  return s;
}

double pixel_x(int c, int w) {
  return kCamY * (2.0 * (c + 0.5) / w - 1.0);
}

RenderResult render(const Scene& scene, const std::string& backend = "cpu",
                    MegakernelLoop loop = MegakernelLoop::Auto,
                    const Strategy& strategy = Strategy::Megakernel) {
  const Grid grid = build_grid_for(scene, backend);
  Tracer tracer(scene, grid);
  RenderSettings rs = testing::compared_settings(scene, backend);
  rs.loop = loop;
  rs.strategy = strategy;
  return tracer.render(rs, scene.camera);
}

// The path integrator's light sample leaves from the floor point raised by the scene's
// epsilon (Shading::offset_origin near zero: 2e-5 of the scene's diagonal, here the floor's,
// sqrt(128)), which changes r^2 by ~3e-4 relative: the formula is evaluated from there.
const double kPathLift = 2e-5 * std::sqrt(128.0);

// What the floor point p sends up from light l (colour's first channel), by the formulas of
// docs/scene-format.md and docs/path-tracing.md, in double.
double expected(const Light& l, Integrator integrator, glm::dvec3 p) {
  if (integrator == Integrator::Path) p.y += kPathLift;
  const glm::dvec3 axis = glm::normalize(glm::dvec3(l.direction));
  glm::dvec3 L;
  double d2 = 1.0;
  if (l.type == LightType::Directional) {
    L = -axis;
  } else {
    const glm::dvec3 to = glm::dvec3(l.position) - p;
    d2 = glm::dot(to, to);
    L = to / std::sqrt(d2);
  }
  const double cos_i = std::max(L.y, 0.0);
  const double cone = spot_cone_factor(l, glm::dot(-L, axis));
  const double c = l.color.x;
  if (integrator == Integrator::Path) {
    const double falloff = l.type == LightType::Directional ? 1.0 : 1.0 / d2;
    return kKd / kPi * c * cone * falloff * cos_i;
  }
  const double falloff = l.falloff == Falloff::InverseSquare ? 1.0 / d2 : 1.0;
  return kKd * c * cone * falloff * cos_i;
}

// Every pixel against the formula; returns how many pixels were lit fully (spot factor 1),
// partly (in the soft edge) and not at all.
struct Regions {
  int full = 0, edge = 0, dark = 0;
};
Regions expect_formula(const Scene& s, const RenderResult& r) {
  Regions regions;
  const Light& l = s.lights.at(0);
  int bad = 0;
  for (int row = 0; row < r.height; ++row)
    for (int col = 0; col < r.width; ++col) {
      // z's sign does not matter: the lights here are symmetric in z.
      const glm::dvec3 p(pixel_x(col, r.width), 0.0, pixel_x(row, r.height));
      const double want = expected(l, s.options.integrator, p);
      const double got = r.color[static_cast<size_t>(row * r.width + col)].x;
      if (l.type == LightType::Spot) {
        glm::dvec3 to = glm::dvec3(l.position) - p;
        const double cone = spot_cone_factor(
            l, glm::dot(-to / glm::length(to), glm::normalize(glm::dvec3(l.direction))));
        (cone == 1.0 ? regions.full : cone == 0.0 ? regions.dark : regions.edge) += 1;
      }
      if (want == 0.0 ? got != 0.0 : !(std::fabs(got - want) <= 1e-4 * want + 1e-7)) {
        if (++bad <= 5)
          ADD_FAILURE() << "pixel (" << col << ", " << row << ") at x " << p.x << ", z " << p.z
                        << ": " << got << ", the formula " << want;
      }
    }
  EXPECT_EQ(bad, 0);
  return regions;
}

Light spot(float inner, float outer, glm::vec3 direction = {0.4f, -1.0f, 0.0f}) {
  Light l;
  l.type = LightType::Spot;
  l.position = glm::vec3(0.2f, 1.5f, 0.0f);
  l.direction = direction;
  l.inner_deg = inner;
  l.outer_deg = outer;
  l.color = glm::vec3(2.0f);
  return l;
}

// A spot's pixels: full light within the inner cone, none outside the outer one (exactly 0:
// nothing else lights the floor), the smoothstep between, each pixel as the formula says, in
// both integrators (Whitted: Kd I cone cos, no falloff unless asked; path: Kd / pi I cone cos
// / r^2), with and without inverse-square falloff under Whitted, and a hard-edged cone.
TEST(LightTypes, ASpotsPixelsInsideOutsideAndInItsEdgeMatchTheFormula) {
  for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
    for (Falloff falloff : {Falloff::None, Falloff::InverseSquare}) {
      if (integrator == Integrator::Path && falloff == Falloff::InverseSquare) continue;
      SCOPED_TRACE(std::string(integrator_name(integrator)) + ", falloff " + falloff_name(falloff));
      Scene s = floor_scene(integrator, 40);
      s.lights = {spot(20.0f, 30.0f)};
      s.lights[0].falloff = falloff;
      const Regions r = expect_formula(s, render(s));
      // The image covers all three regions, the edge with many pixels.
      EXPECT_GT(r.full, 20);
      EXPECT_GT(r.edge, 20);
      EXPECT_GT(r.dark, 100);
    }
  }
  Scene hard = floor_scene(Integrator::Whitted, 40);
  hard.lights = {spot(25.0f, 25.0f, {0.0f, -1.0f, 0.0f})};
  const Regions r = expect_formula(hard, render(hard));
  EXPECT_EQ(r.edge, 0);
  EXPECT_GT(r.full, 20);
}

// A directional light of irradiance E at 35 degrees from the normal lights a Lambertian floor
// uniformly: radiance E cos / pi * albedo under path (exact: a delta light sampled with
// probability 1), Kd E cos under Whitted; every pixel.
TEST(LightTypes, ADirectionalLightOnALambertianFloorGivesECosOverPiTimesAlbedo) {
  const double theta = 35.0 * kPi / 180.0;
  for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
    SCOPED_TRACE(integrator_name(integrator));
    Scene s = floor_scene(integrator, 16);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction =
        glm::vec3(static_cast<float>(std::sin(theta)), -static_cast<float>(std::cos(theta)), 0.0f);
    sun.color = glm::vec3(3.0f);
    s.lights = {sun};
    const RenderResult r = render(s);
    const double want = (integrator == Integrator::Path ? kKd / kPi : kKd) * 3.0 * std::cos(theta);
    for (size_t p = 0; p < r.color.size(); ++p)
      ASSERT_NEAR(r.color[p].x, want, 1e-5 * want) << "pixel " << p;
    expect_formula(s, r);
  }
}

// Among other lights, a delta light is chosen with probability below 1 and its sample divided
// by it; the area light's samples then weigh against BSDF samples by MIS while the delta
// lights' weigh 1. So the image of a spot, a directional light and an area light together is,
// in expectation, the image of the two delta lights (exact, as above) plus that of the area
// light alone. Per pixel d = all - deltas - area has mean 0; pixels are independent (their own
// Philox counters), so over 1024 pixels the mean of d is normal to a good approximation and
// 5 standard errors (from d's spread) fail a correct integrator with probability below 6e-7.
// A delta light weighted by MIS, or not divided by its probability, moves the mean by a large
// fraction of the delta lights' image. Checked by hand: a mutant that does not divide the
// directional light (chosen with probability ~0.9 here) by its probability failed at 11
// standard errors, and a linear cone in place of the smoothstep failed the spot's formula test.
TEST(LightTypes, DeltaLightsAmongAreaLightsAddUpUnderPath) {
  auto scene = [](bool deltas, bool area) {
    Scene s = floor_scene(Integrator::Path, 32);
    s.options.spp = 64;
    // The lamp (its front facing down) is there in all three, black where it does not emit:
    // it hides and shadows the same floor in each.
    Material lamp;
    lamp.name = "lamp";
    lamp.shader = "diffuse";
    lamp.set("diffuse", glm::vec3(0.0f));
    lamp.emission = glm::vec3(area ? 4.0f : 0.0f);
    const int m = s.add_material(lamp);
    add_quad(s, {-1.0f, 1.2f, -0.3f}, {-0.4f, 1.2f, -0.3f}, {-0.4f, 1.2f, 0.3f},
             {-1.0f, 1.2f, 0.3f}, m);
    if (deltas) {
      Light sun;
      sun.type = LightType::Directional;
      sun.direction = glm::vec3(0.3f, -1.0f, 0.2f);
      sun.color = glm::vec3(0.5f);
      s.lights = {spot(20.0f, 30.0f), sun};
    }
    return s;
  };
  const RenderResult all = render(scene(true, true)), deltas = render(scene(true, false)),
                     area = render(scene(false, true));
  double sum = 0.0, sum2 = 0.0, delta_sum = 0.0;
  const double n = static_cast<double>(all.color.size());
  for (size_t p = 0; p < all.color.size(); ++p) {
    const double d = double(all.color[p].x) - deltas.color[p].x - area.color[p].x;
    sum += d;
    sum2 += d * d;
    delta_sum += deltas.color[p].x;
  }
  const double mean = sum / n, se = std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / (n - 1));
  EXPECT_LT(std::fabs(mean), 5.0 * se) << "mean " << mean << ", standard error " << se;
  // The test has power: the delta lights' image is far above the bound.
  EXPECT_GT(delta_sum / n, 20.0 * se);
}

// Whitted's point light with inverse-square falloff: the pixel right under it (the centre of
// an odd-sized image) at heights h and 2h gives 4 times the light (Kd C / h^2); without
// falloff (the default, today's images) the same at both.
TEST(LightTypes, InverseSquareFalloffUnderWhittedGivesTheRatioOfTheSquaredDistances) {
  auto centre = [](float h, Falloff falloff) {
    Scene s = floor_scene(Integrator::Whitted, 33);
    Light l;
    l.position = glm::vec3(0.0f, h, 0.0f);
    l.falloff = falloff;
    s.lights = {l};
    const RenderResult r = render(s);
    if (falloff == Falloff::InverseSquare) expect_formula(s, r);
    return static_cast<double>(r.color[static_cast<size_t>(16 * 33 + 16)].x);
  };
  const double near = centre(0.5f, Falloff::InverseSquare),
               far = centre(1.0f, Falloff::InverseSquare);
  EXPECT_NEAR(near, kKd / 0.25, 1e-5);
  EXPECT_NEAR(near / far, 4.0, 4e-5);
  EXPECT_EQ(centre(0.5f, Falloff::None), centre(1.0f, Falloff::None));
  EXPECT_NEAR(centre(1.0f, Falloff::None), kKd, 1e-6);
}

// A directional light at 45 degrees past an opaque half-plane x < 0 at height 1: the floor is
// in shadow for x < 1 (the half-plane's edge moved 1 along the light) and lit beyond. The
// camera sees the floor for x > 0 (its rays pass the plane at x / 2). Shadow rays have no end
// (one that stopped early would light the shadow); with a light buffer (a directional light's
// cells all walk the grid) the image is the same bits.
TEST(LightTypes, ADirectionalLightCastsItsShadowAlongItsDirection) {
  for (Integrator integrator : {Integrator::Whitted, Integrator::Path}) {
    SCOPED_TRACE(integrator_name(integrator));
    Scene s = floor_scene(integrator, 40);
    add_quad(s, {-4, 1, -4}, {0, 1, -4}, {0, 1, 4}, {-4, 1, 4}, s.material[0]);
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::vec3(1.0f, -1.0f, 0.0f);
    s.lights = {sun};
    s.options.light_buffer = kLightBufferOff;
    const RenderResult r = render(s);
    const double lit = (integrator == Integrator::Path ? kKd / kPi : kKd) * std::sqrt(0.5);
    int shadowed = 0, bright = 0;
    for (int col = 0; col < r.width; ++col) {
      const double x = pixel_x(col, r.width);
      if (x < 0.05 || std::fabs(x - 1.0) < 0.05) continue;
      for (int row = 0; row < r.height; ++row) {
        const float got = r.color[static_cast<size_t>(row * r.width + col)].x;
        if (x < 1.0) {
          ASSERT_EQ(got, 0.0f) << "column " << col;
          ++shadowed;
        } else {
          ASSERT_NEAR(got, lit, 1e-5 * lit) << "column " << col;
          ++bright;
        }
      }
    }
    EXPECT_GT(shadowed, 200);
    EXPECT_GT(bright, 200);
    if (integrator == Integrator::Whitted) {
      s.lights.push_back(spot(20.0f, 30.0f));  // a light the buffer serves, beside the sun's
      const RenderResult without = render(s);
      s.options.light_buffer = 8;
      testing::expect_identical(render(s), without, "light buffer");
    }
  }
}

// The kernels: the shapes' arrays only in a scene with such lights (the built-in scenes and
// Whitted point lights without falloff keep their kernels: raytracer.whitted_sources_unchanged
// compares the generated sources byte for byte).
TEST(LightTypes, OnlyAScenesWithShapedLightsHasTheirCode) {
  auto ir = [](const Scene& s) {
    Tracer t(s, build_grid(s, 0));
    return std::make_pair(t.features().light_shapes, t.program(MegakernelLoop::Ray).print());
  };
  for (const char* name : {"thesis-a", "cornell", "cornell-path"}) {
    const auto [shaped, code] = ir(builtin_scene(name));
    EXPECT_FALSE(shaped) << name;
    EXPECT_EQ(code.find("light_shape"), std::string::npos) << name;
  }
  Scene s = floor_scene(Integrator::Whitted, 8);
  s.lights = {Light{}};
  s.lights[0].position = glm::vec3(0, 1, 0);
  EXPECT_FALSE(ir(s).first);
  s.lights[0].falloff = Falloff::InverseSquare;
  EXPECT_TRUE(ir(s).first);
  EXPECT_NE(ir(s).second.find("light_shape"), std::string::npos);
  // The path integrator's point lights fall off anyway: no shapes for falloff alone.
  Scene p = floor_scene(Integrator::Path, 8);
  p.lights = s.lights;
  EXPECT_FALSE(ir(p).first);
  p.lights = {spot(20.0f, 30.0f)};
  EXPECT_TRUE(ir(p).first);
  EXPECT_NE(ir(p).second.find("plight_shape"), std::string::npos);
}

// The built-in Cornell box (Whitted's, or cornell-path's with its area light) with every kind
// of light added to its own: a spot with inverse-square falloff, a directional light and a
// point light, with shadows.
Scene mixed_scene(Integrator integrator) {
  Scene s = builtin_scene(integrator == Integrator::Path ? "cornell-path" : "cornell");
  s.width = 20;
  s.height = 16;
  s.options.max_depth = 3;
  s.options.spp = 2;
  Light a = spot(15.0f, 35.0f, {0.1f, -1.0f, 0.2f});
  a.position = glm::vec3(300.0f, 500.0f, 250.0f);
  // About 1 at the floor 300 mm away: intensity under path, and under Whitted with falloff.
  a.color = glm::vec3(integrator == Integrator::Path ? 2.0e5f : 8.0e4f);
  a.falloff = Falloff::InverseSquare;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = glm::vec3(0.3f, -1.0f, 0.5f);
  sun.color = glm::vec3(0.4f, 0.35f, 0.3f);
  Light point;
  point.position = glm::vec3(200.0f, 300.0f, 200.0f);
  point.color = glm::vec3(integrator == Integrator::Path ? 3.0e4f : 0.3f);
  s.lights.insert(s.lights.end(), {a, sun, point});
  return s;
}

class LightTypesBackends : public ::testing::TestWithParam<std::string> {};

// Every backend gives the cpu's bits: Whitted in both megakernel loops (each against the cpu's
// other one), the path integrator; on cpu the other strategies give the megakernel's.
TEST_P(LightTypesBackends, ImagesAreTheCpusBits) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene whitted = mixed_scene(Integrator::Whitted);
  const RenderResult cpu_ray = render(whitted, "cpu", MegakernelLoop::Ray);
  EXPECT_GT(cpu_ray.rays, int64_t{whitted.width} * whitted.height * 4);
  testing::expect_identical(render(whitted, GetParam(), MegakernelLoop::Segment), cpu_ray,
                            "whitted, segment loop vs cpu's ray loop");
  const Scene path = mixed_scene(Integrator::Path);
  const RenderResult cpu_path = render(path, "cpu");
  testing::expect_identical(render(path, GetParam()), cpu_path, "path");
  if (GetParam() == "cpu") {
    testing::expect_identical(render(whitted, "cpu", MegakernelLoop::Auto, Strategy::Multipass),
                              render(whitted, "cpu", MegakernelLoop::Auto, Strategy::Megakernel),
                              "multipass");
    testing::expect_identical(render(path, "cpu", MegakernelLoop::Auto, Strategy::Wavefront),
                              cpu_path, "wavefront");
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, LightTypesBackends,
                         ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace light_types_test
}  // namespace rt
