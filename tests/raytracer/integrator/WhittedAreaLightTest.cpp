// Whitted's area lights (kernel/Shading.h, Features::area_lights): emitting materials light a
// Whitted scene with options.light_samples shadow rays per shaded point. Against answers
// derived here: a half-blocked emitter casts a penumbra between its umbra and full light; an
// emitter is seen with its emission from the front and not from behind (one-sided); the
// sample count changes the noise, not the mean; a small distant emitter lights like the
// point light of matching colour Le A / (pi D^2). Then the kernels: a scene without emitters
// has none of their code, both megakernel loops and every backend give the cpu's bits, and
// the multipass strategy refuses such a scene naming the reason.
//
// Statistics as in PathIntegratorTest: each pixel's samples have their own Philox counters, so
// pixels are independent estimates and an image mean over P >= 256 pixels is normal to a good
// approximation; 5 standard errors fail a correct tracer with probability below 6e-7.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

constexpr double kPi = 3.14159265358979323846;

Material phong(const std::string& name, float kd, glm::vec3 emission = glm::vec3(0.0f)) {
  Material m;
  m.name = name;
  m.shader = "phong";
  m.set("diffuse", glm::vec3(kd));
  m.set("specular", glm::vec3(0.0f));
  m.emission = emission;
  return m;
}

// A square of half-size s at height h, its front (emitting side) facing down.
void add_ceiling_quad(Scene& s, float half, float h, int mat, float x0 = 0.0f) {
  add_quad(s, {x0 - half, h, -half}, {x0 + half, h, -half}, {x0 + half, h, half},
           {x0 - half, h, half}, mat);
}

// A floor (y = 0, half-size 4) of diffuse Kd 0.5 seen from (0, cam_y, 0) straight down with a
// 90 degree field of view, so that the image's x maps linearly onto the floor's x in
// [-cam_y, cam_y] (column c at x = cam_y (2 (c + 0.5) / W - 1)); no ambient light, a black
// background.
Scene floor_scene(float cam_y, int size) {
  Scene s;
  s.name = "area-light-floor";
  const int floor = s.add_material(phong("floor", 0.5f));
  add_quad(s, {-4, 0, -4}, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, floor);
  s.camera = Camera{{0.0f, cam_y, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 90.0f};
  s.has_camera = true;
  s.width = s.height = size;
  s.background = glm::vec3(0.0f);
  s.options.ambient = 0.0f;
  s.options.max_depth = 0;
  return s;
}

RenderResult render(const Scene& scene, const std::string& backend = "cpu",
                    MegakernelLoop loop = MegakernelLoop::Auto) {
  const Grid grid = build_grid_for(scene, backend);
  Tracer tracer(scene, grid);
  EXPECT_TRUE(tracer.features().area_lights);
  RenderSettings rs = testing::compared_settings(scene, backend);
  rs.loop = loop;
  return tracer.render(rs, scene.camera);
}

double grey(const glm::vec3& c) {
  return (double(c.x) + c.y + c.z) / 3.0;
}

// The mean of column c over all rows.
double column_mean(const RenderResult& r, int c) {
  double sum = 0.0;
  for (int y = 0; y < r.height; ++y) sum += grey(r.color[static_cast<size_t>(y * r.width + c)]);
  return sum / r.height;
}

// A 1 x 1 emitter at height 2 over the floor, and above the camera (y = 0.9) an opaque
// half-plane x < 0 at height 1. A floor point (x, 0, z) sees the emitter point (xe, 2, ze)
// past the half-plane iff the segment crosses y = 1 at (x + xe) / 2 >= 0: for x < -0.5 none
// of the emitter (umbra, exactly 0: nothing else lights it), for x > 0.5 all of it, and at
// x = 0 exactly the half xe > 0, by symmetry half its irradiance there. The full irradiance
// at x = 0.8 is about 0.75 of that at x = 0 (cos^2 / d^2 against cos^4 / d^2 from 2 units),
// so the penumbra's middle is about 0.67 of the lit column: between 0.3 and 0.9 of it.
// A point light at the emitter's centre instead puts the shadow's edge at x = 0, hard.
TEST(WhittedAreaLight, SoftShadowHasAPenumbraBetweenUmbraAndFullLight) {
  Scene s = floor_scene(0.9f, 36);
  add_ceiling_quad(s, 0.5f, 2.0f, s.add_material(phong("light", 0.0f, glm::vec3(8.0f))));
  add_quad(s, {-4, 1, -4}, {0, 1, -4}, {0, 1, 4}, {-4, 1, 4}, s.add_material(phong("wall", 0.5f)));
  s.options.light_samples = 32;
  const RenderResult r = render(s);
  const int w = s.width;
  // Columns at x = -0.8, 0 (the two middle ones) and +0.8.
  const double umbra = column_mean(r, 2), lit = column_mean(r, w - 3);
  const double penumbra = 0.5 * (column_mean(r, w / 2 - 1) + column_mean(r, w / 2));
  EXPECT_EQ(umbra, 0.0);
  EXPECT_GT(lit, 0.0);
  EXPECT_GT(penumbra, 0.3 * lit) << "umbra " << umbra << " lit " << lit;
  EXPECT_LT(penumbra, 0.9 * lit) << "umbra " << umbra << " lit " << lit;
  // Brightness grows through the penumbra: column means rise from x = -0.5 to 0.5.
  double last = -1.0;
  for (int c = w / 2 - 8; c <= w / 2 + 8; c += 4) {
    const double m = column_mean(r, c);
    EXPECT_GT(m, last) << "column " << c;
    last = m;
  }
}

// An emitter of Kd 0 under no other light: where the camera sees its front, the pixel is its
// emission exactly (local colour 0 + Le, weight 1); from behind a one-sided emitter shows
// nothing (0), a two-sided one its emission.
TEST(WhittedAreaLight, AnEmitterIsSeenWithItsEmissionFromTheFrontOnly) {
  const glm::vec3 le(3.0f, 2.0f, 0.5f);
  for (bool two_sided : {false, true}) {
    for (float eye_y : {-1.0f, 3.0f}) {  // below (its front) and above (behind)
      Scene s;
      Material m = phong("light", 0.0f, le);
      m.two_sided = two_sided;
      add_ceiling_quad(s, 2.0f, 1.0f, s.add_material(m));
      s.camera = Camera{{0.0f, eye_y, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 40.0f};
      s.has_camera = true;
      s.width = s.height = 8;
      s.options.ambient = 0.0f;
      s.options.light_samples = 2;
      const RenderResult r = render(s);
      const bool front = eye_y < 1.0f;
      const glm::vec3 want = front || two_sided ? le : glm::vec3(0.0f);
      for (const glm::vec3& c : r.color) {
        ASSERT_EQ(c, want) << "two_sided " << two_sided << " eye y " << eye_y;
      }
    }
  }
}

// A 4 x 4 emitter at height 1 over the floor, seen from y = 0.5: a point's one-sample estimate
// varies a lot with where the sample falls (cos^2 / d^2 ranges over a factor of about 10).
// Paired per pixel, d = v(1 sample) - v(64 samples) has mean 0 whatever the pixel's expected
// value, and the pixels' d are independent: |mean d| < 5 se(d). And the noise: two renders
// of different seeds differ per pixel with variance 2 sigma_n^2, sigma_n^2 = sigma_1^2 / n;
// from 1 to 64 samples that variance must fall by a factor of 64, here over 1024 pixels
// (a variance estimated from P pixels is within about 3 sqrt(2 / P) = 13% of the truth), so
// more than 32 is a safe bound.
TEST(WhittedAreaLight, LightSamplesChangeTheNoiseNotTheMean) {
  auto scene = [](int samples, uint32_t seed) {
    Scene s = floor_scene(0.5f, 32);
    add_ceiling_quad(s, 2.0f, 1.0f, s.add_material(phong("light", 0.0f, glm::vec3(1.0f))));
    s.options.light_samples = samples;
    s.options.seed = seed;
    return s;
  };
  const RenderResult one = render(scene(1, 1)), one_b = render(scene(1, 2));
  const RenderResult many = render(scene(64, 1)), many_b = render(scene(64, 2));
  const double n = static_cast<double>(one.color.size());
  auto spread = [&](const RenderResult& a, const RenderResult& b, double& mean, double& var) {
    double sum = 0.0, sum2 = 0.0;
    for (size_t p = 0; p < a.color.size(); ++p) {
      const double d = grey(a.color[p]) - grey(b.color[p]);
      sum += d;
      sum2 += d * d;
    }
    mean = sum / n;
    var = std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1);
  };
  double mean_d = 0.0, var_d = 0.0;
  spread(one, many, mean_d, var_d);
  EXPECT_LT(std::abs(mean_d), 5.0 * std::sqrt(var_d / n)) << "var " << var_d;
  double m1 = 0.0, var1 = 0.0, m64 = 0.0, var64 = 0.0;
  spread(one, one_b, m1, var1);
  spread(many, many_b, m64, var64);
  EXPECT_GT(var1, 0.0);
  EXPECT_GT(var1, 32.0 * var64) << "1 sample " << var1 << ", 64 samples " << var64;
}

// A square emitter of side a = 1 and radiance Le at height D = 20, facing down, seen from a
// floor point (x, 0, z) with |x|, |z| <= 1: the irradiance is Le A cos_s cos_l / r^2 to first
// order, and the Lambertian floor's Whitted colour Kd E / pi (Shading.h). A Whitted point light
// of colour C at the emitter's centre gives Kd C cos_s, without falloff: C = Le A / (pi D^2)
// matches on the axis. Off the axis cos_l / r^2 = D / r^3 falls as 1 - 1.5 (x^2 + z^2) / D^2
// (at most 0.75%), the finite square changes E by O((a / D)^2) = 0.25%, and a sample's
// estimate varies across the square by about a / D * |x| / D = 0.25%, averaged over 16. So
// every pixel agrees within 1.5%.
TEST(WhittedAreaLight, ASmallDistantEmitterLightsLikeThePointLightOfMatchingColour) {
  const float le = 200.0f, a = 1.0f, D = 20.0f;
  Scene area = floor_scene(1.0f, 16);
  add_ceiling_quad(area, 0.5f * a, D, area.add_material(phong("light", 0.0f, glm::vec3(le))));
  Scene point = floor_scene(1.0f, 16);
  const float c = static_cast<float>(le * a * a / (kPi * D * D));
  point.lights.push_back(Light{{0.0f, D, 0.0f}, glm::vec3(c)});
  const RenderResult ra = render(area);
  Grid grid = build_grid_for(point, "cpu");
  Tracer pt(point, grid);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = rs.height = 16;
  const RenderResult rp = pt.render(rs, point.camera);
  for (size_t p = 0; p < ra.color.size(); ++p) {
    ASSERT_GT(rp.color[p].x, 0.0f);
    ASSERT_NEAR(ra.color[p].x / rp.color[p].x, 1.0, 0.015) << "pixel " << p;
  }
}

// The built-in Cornell box under Whitted with its emitting quad (cornell-path's) and few
// samples: small and quick, with both kinds of light (a point light added) and shadows.
Scene cornell_area(bool point_light) {
  Scene s = builtin_scene("cornell-path");
  s.options.integrator = Integrator::Whitted;
  s.options.light_samples = 3;
  s.options.spp = 2;
  s.options.max_depth = 2;
  s.width = 20;
  s.height = 16;
  if (point_light) s.lights.push_back(Light{{0.3f, 0.4f, 0.2f}, glm::vec3(0.3f)});
  return s;
}

// The kernels: the area lights' code (their tables light_cdf_area and mat_light, the random
// sequence's seed) only where a scene has emitters, in both loops' IR, so a scene without
// keeps the kernel it had (docs/benchmarks/2026-12-03-architecture/source-identity.sh checks
// the generated sources byte for byte). The arrays' names are the IR's (the C sources number
// them).
std::string ir_of_both_loops(const Tracer& t) {
  return t.program(MegakernelLoop::Ray).print() + t.program(MegakernelLoop::Segment).print();
}

TEST(WhittedAreaLight, OnlyAScenesWithEmittersHasTheirCode) {
  for (const char* name : {"thesis-a", "cornell"}) {
    const Scene s = builtin_scene(name);
    Tracer t(s, build_grid(s, 0));
    EXPECT_FALSE(t.features().area_lights) << name;
    const std::string ir = ir_of_both_loops(t);
    EXPECT_NE(ir.find("light_pos"), std::string::npos) << name << ": the point lights are";
    EXPECT_EQ(ir.find("light_cdf"), std::string::npos) << name;
    EXPECT_EQ(ir.find("mat_light"), std::string::npos) << name;
    EXPECT_EQ(ir.find("whitted_seed"), std::string::npos) << name;
  }
  const Scene s = cornell_area(false);
  Tracer t(s, build_grid(s, 0));
  EXPECT_TRUE(t.features().area_lights && t.features().shadows && !t.features().lights);
  const std::string ir = ir_of_both_loops(t);
  EXPECT_NE(ir.find("light_cdf_area"), std::string::npos);
  EXPECT_NE(ir.find("mat_light"), std::string::npos);
  EXPECT_NE(ir.find("whitted_seed"), std::string::npos);
  EXPECT_NE(t.source("cpu").find("whitted_seed"), std::string::npos);
  // Under the path integrator emitters are its lights, not Whitted's.
  Scene path = builtin_scene("cornell-path");
  EXPECT_FALSE(Tracer(path, build_grid(path, 0)).features().area_lights);
}

TEST(WhittedAreaLight, TheMultipassStrategyRefusesEmittersNamingWhy) {
  const Scene s = cornell_area(false);
  Tracer t(s, build_grid(s, 0));
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = s.width;
  rs.height = s.height;
  rs.strategy = Strategy::Multipass;
  std::string why;
  try {
    t.render(rs, s.camera);
    ADD_FAILURE() << "no error";
  } catch (const std::exception& e) {
    why = e.what();
  }
  EXPECT_NE(why.find("area lights"), std::string::npos) << why;
  EXPECT_NE(why.find("megakernel"), std::string::npos) << why;
}

class WhittedAreaLightBackends : public ::testing::TestWithParam<std::string> {};

// Both loops on every backend give the cpu's bits: the area light alone in one loop, with a
// point light beside it (the light loop's two kinds, and the light buffer's point light with
// area samples that skip it) in the other, each against the cpu's other loop. Two kernels
// per backend keep the compiles few.
TEST_P(WhittedAreaLightBackends, BothLoopsGiveTheCpusBits) {
  RT_REQUIRE_BACKEND(GetParam());
  for (bool point_light : {false, true}) {
    SCOPED_TRACE(point_light ? "area and point light" : "area light");
    const Scene s = cornell_area(point_light);
    const MegakernelLoop loop = point_light ? MegakernelLoop::Segment : MegakernelLoop::Ray;
    const MegakernelLoop other = point_light ? MegakernelLoop::Ray : MegakernelLoop::Segment;
    const RenderResult cpu = render(s, "cpu", other);
    const RenderResult here = render(s, GetParam(), loop);
    EXPECT_GT(cpu.rays, int64_t{s.width} * s.height * 2);
    testing::expect_identical(
        here, cpu,
        std::string(megakernel_loop_name(loop)) + " loop vs cpu's " + megakernel_loop_name(other));
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, WhittedAreaLightBackends,
                         ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
