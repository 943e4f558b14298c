// The path integrator (integrator/PathIntegrator.h) against answers nobody here computed with
// its code: closed furnaces (the geometric series of the albedo), a white sphere that vanishes
// under a uniform sky, a diffuse floor under the sky, an area light shrinking towards a point
// light, and the independent reference path tracer (support/ReferencePathTracer.h) pixel by
// pixel. Deliberately broken integrators (TracerOptions::mutation) must fail the same tests.
// Then bitwise identity: every backend gives the cpu backend's bits.
//
// Statistics. A render's pixels are independent estimates (each has its own Philox counters),
// so over P pixels the image mean is normal to a good approximation (central limit theorem,
// P >= 256), with a standard error estimated from the pixels' spread. A bound of 5 standard
// errors fails a correct integrator with probability below 6e-7 (two-sided normal tail).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Image.h"
#include "support/ReferencePathTracer.h"

namespace rt {
namespace {

using testing::ReferenceImage;
using testing::ReferenceOptions;
using testing::ReferencePathTracer;

// The mean colour of spp samples (and with aovs the first hit's depth, primitive and normal).
RenderResult render(const Scene& scene, int spp, const std::string& backend = "cpu",
                    const TracerOptions& options = {}, bool aovs = false) {
  Grid grid = build_grid_for(scene, backend);
  Tracer tracer(scene, grid, options);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = backend;
  rs.width = scene.width;
  rs.height = scene.height;
  rs.spp = spp;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = rs.outputs.albedo = aovs;
  return tracer.render(rs, scene.camera);
}

// The mean colour of spp samples and each pixel's variance of it (FrameOutputs::variance).
RenderResult render_with_variance(const Scene& scene, int spp) {
  Grid grid = build_grid_for(scene);
  Tracer tracer(scene, grid);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = scene.width;
  rs.height = scene.height;
  rs.spp = spp;
  rs.outputs.variance = true;
  return tracer.render(rs, scene.camera);
}

Material with_shader(const std::string& name, const std::string& shader) {
  Material m;
  m.name = name;
  m.shader = shader;
  return m;
}

Material diffuse(const std::string& name, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f)) {
  Material m = with_shader(name, "diffuse");
  m.set("diffuse", albedo);
  m.emission = emission;
  return m;
}

// A closed box seen from inside, every wall of albedo a emitting Le.
Scene furnace(float a, float le, int max_depth) {
  Scene s;
  s.name = "furnace";
  add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f),
          s.add_material(diffuse("wall", glm::vec3(a), glm::vec3(le))), {}, /*inward=*/true);
  s.camera = Camera{{0.1f, 0.2f, 0.3f}, {0.5f, -0.3f, -1.0f}, {0, 1, 0}, 90.0f};
  s.has_camera = true;
  s.width = s.height = 32;
  s.background = glm::vec3(5.0f);  // never seen: the box is closed
  s.options.integrator = Integrator::Path;
  s.options.max_depth = max_depth;
  return s;
}

double series(double a, double le, int depth) {
  double sum = 0.0, ak = 1.0;
  for (int k = 0; k <= depth; ++k, ak *= a) sum += le * ak;
  return sum;
}

// The image mean over pixels and channels and its standard error (from the pixels' spread).
struct Mean {
  double mean = 0, se = 0;
};
Mean image_mean(const RenderResult& r) {
  const double n = static_cast<double>(r.color.size());
  double sum = 0, sum2 = 0;
  for (const glm::vec3& c : r.color) {
    const double v = (double(c.x) + c.y + c.z) / 3.0;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n, var = std::max(sum2 / n - mean * mean, 0.0) * n / (n - 1);
  return {mean, std::sqrt(var / n)};
}

// Without light sampling every path of a Lambertian furnace returns the same value: each
// bounce's weight is eval / pdf = a (to rounding, ~1e-7 relative), and with max_depth 2
// Russian roulette (from depth 3) never starts. So every pixel is Le (1 + a + a^2).
TEST(PathFurnace, WithoutLightSamplingEveryPixelIsTheGeometricSeries) {
  Scene s = furnace(0.5f, 1.0f, 2);
  s.options.nee = false;
  const RenderResult r = render(s, 2);
  const double want = series(0.5, 1.0, 2);
  for (size_t p = 0; p < r.color.size(); ++p)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(r.color[p][c], want, 1e-5 * want) << "pixel " << p;
}

// With next-event estimation, with and without MIS, and with Russian roulette (max_depth 6):
// random per path, but unbiased, so the image mean is the series within 5 standard errors.
TEST(PathFurnace, WithLightSamplingTheMeanIsTheGeometricSeries) {
  for (bool mis : {true, false}) {
    Scene s = furnace(0.7f, 0.5f, 6);
    s.options.mis = mis;
    const Mean m = image_mean(render(s, 8));
    const double want = series(0.7, 0.5, 6);
    EXPECT_LT(std::abs(m.mean - want), 5 * m.se + 1e-6 * want)
        << "mis " << mis << ": mean " << m.mean << " se " << m.se << " want " << want;
    EXPECT_GT(m.se, 0.0) << "light sampling makes the paths random";
  }
}

// A sphere of albedo 1 under a uniform sky B: light bounces off it and leaves (a convex
// object never sees itself), with nothing absorbed, so every pixel is B: the sphere vanishes.
// Faceted: with interpolated normals a cosine-weighted direction about the shading normal can
// point into the geometric surface, where the BSDF is 0 (no light leaks) and energy is lost.
TEST(PathFurnace, AWhiteSphereUnderAUniformSkyVanishes) {
  Scene s;
  add_sphere(s, glm::vec3(0.0f), 1.0f, 24, 16, s.add_material(diffuse("white", glm::vec3(1.0f))),
             /*smooth=*/false);
  s.camera = Camera{{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 50.0f};
  s.has_camera = true;
  s.width = s.height = 24;
  s.background = glm::vec3(0.6f, 0.8f, 1.0f);
  s.options.integrator = Integrator::Path;
  s.options.max_depth = 4;
  const RenderResult r = render(s, 2);
  for (size_t p = 0; p < r.color.size(); ++p)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(r.color[p][c], s.background[c], 1e-5f) << "pixel " << p << " channel " << c;
}

// A diffuse floor of albedo a under a sky of radiance B: its radiance is a B (the cosine-
// weighted hemisphere above it sees only sky), exactly per path up to rounding.
TEST(PathFurnace, ADiffuseFloorUnderAUniformSkyIsAlbedoTimesSky) {
  Scene s;
  const glm::vec3 a(0.2f, 0.5f, 0.8f), sky(1.5f, 1.0f, 0.5f);
  add_quad(s, {-100, 0, 100}, {100, 0, 100}, {100, 0, -100}, {-100, 0, -100},
           s.add_material(diffuse("floor", a)));
  s.camera = Camera{{0, 1, 0}, {0, 0, -0.5f}, {0, 1, 0}, 60.0f};
  s.has_camera = true;
  s.width = s.height = 16;
  s.background = sky;
  s.options.integrator = Integrator::Path;
  s.options.max_depth = 3;
  const RenderResult r = render(s, 2);
  for (size_t p = 0; p < r.color.size(); ++p)
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(r.color[p][c], a[c] * sky[c], 1e-5f) << "pixel " << p << " channel " << c;
}

// A square area light of side w, radiance Le, facing down at height h over a black-walled
// diffuse floor, against a point light of intensity Le w^2 at its centre: the irradiance right
// under them differs by the light's extent, relatively about (w / h)^2 (a disk of radius r
// gives 1 / (1 + r^2 / h^2)). As w shrinks the two pixels under the light agree.
TEST(PathLights, ASmallAreaLightApproachesAPointLightOfTheSameIntensity) {
  auto scene = [](float w, bool point) {
    Scene s;
    add_quad(s, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, {-5, 0, -5},
             s.add_material(diffuse("floor", glm::vec3(0.5f))));
    const float le = 1.0f / (w * w);  // intensity Le w^2 = 1
    if (point) {
      s.lights.push_back(Light{{0, 1, 0}, glm::vec3(1.0f)});
    } else {
      const float h = w / 2;
      add_quad(s, {-h, 1, -h}, {h, 1, -h}, {h, 1, h}, {-h, 1, h},
               s.add_material(diffuse("lamp", glm::vec3(0.0f), glm::vec3(le))));
    }
    s.camera = Camera{{0, 0.5f, 0.0001f}, {0, 0, 0}, {0, 0, -1}, 2.0f};  // looking straight down
    s.has_camera = true;
    s.width = s.height = 4;
    s.background = glm::vec3(0.0f);
    s.options.integrator = Integrator::Path;
    s.options.max_depth = 1;
    return s;
  };
  const double point = image_mean(render(scene(0.0f, true), 4)).mean;
  EXPECT_NEAR(point, 0.5 / M_PI, 1e-3 * 0.5 / M_PI) << "E = I / h^2 = 1, L = a E / pi";
  double previous = 1.0;
  for (float w : {0.4f, 0.2f, 0.05f}) {
    const Mean area = image_mean(render(scene(w, false), 64));
    const double rel = std::abs(area.mean - point) / point;
    // The extent's bias is below (w/h)^2 = w^2; the noise below 5 standard errors.
    EXPECT_LT(rel, w * w + 5 * area.se / point) << "w " << w;
    EXPECT_LT(rel, previous + 5 * area.se / point) << "w " << w;
    previous = rel;
  }
}

// ---- Against the reference path tracer ---------------------------------------------------

// Rill's mean and the variance of that mean per pixel and channel, from K independent
// renders (seeds first_seed .. first_seed + K - 1) of n samples each (batch means: the variance of
// the mean is the batches' sample variance over K).
struct Estimate {
  std::vector<glm::dvec3> mean, var;
};
Estimate rill_estimate(Scene s, int batches, int spp, const TracerOptions& options,
                       uint32_t first_seed = 1) {
  Estimate e;
  std::vector<glm::dvec3> sum, sum2;
  for (int k = 0; k < batches; ++k) {
    s.options.seed = first_seed + static_cast<uint32_t>(k);
    const RenderResult r = render(s, spp, "cpu", options);
    sum.resize(r.color.size(), glm::dvec3(0.0));
    sum2.resize(r.color.size(), glm::dvec3(0.0));
    for (size_t p = 0; p < r.color.size(); ++p) {
      sum[p] += glm::dvec3(r.color[p]);
      sum2[p] += glm::dvec3(r.color[p]) * glm::dvec3(r.color[p]);
    }
  }
  const double K = batches;
  for (size_t p = 0; p < sum.size(); ++p) {
    const glm::dvec3 m = sum[p] / K;
    e.mean.push_back(m);
    e.var.push_back(glm::max((sum2[p] / K - m * m) * (K / (K - 1)), glm::dvec3(0.0)) / K);
  }
  return e;
}

// Per pixel and channel z = (rill - reference) / sqrt(var_rill + var_reference). With K = 16
// batches Rill's variance has 15 degrees of freedom, so z would be about Student-t with 15 or
// more: P(|t_15| > 4.5) = 4.3e-4, 0.33 expected beyond 4.5 over N = 768 pixel channels. The
// reference's BSDF-only estimates near the light are heavy-tailed, so their sample variances
// run low: over 20 independent seed sets (DISABLED_FalseFailureRateOverSeeds, 2026-12-07) the
// count averaged 0.85. At most 6 are allowed: for a Poisson count of mean 0.85,
// P(X >= 7) = 1.5e-5. Also the image mean, the average of the N differences, must lie within
// 5 of its standard errors.
struct Agreement {
  int beyond = 0;  // pixel channels with |z| > 4.5
  double z_mean = 0;
  bool passes() const { return beyond <= 6 && std::abs(z_mean) < 5.0; }
};
Agreement agree(const Estimate& rill, const ReferenceImage& ref) {
  Agreement a;
  double diff = 0, var = 0;
  for (size_t p = 0; p < rill.mean.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double d = rill.mean[p][c] - ref.mean[p][c], v = rill.var[p][c] + ref.variance[p][c];
      diff += d;
      var += v;
      if (v > 0 ? std::abs(d) > 4.5 * std::sqrt(v) : std::abs(d) > 1e-6) ++a.beyond;
    }
  a.z_mean = var > 0 ? diff / std::sqrt(var) : (diff == 0 ? 0.0 : 1e9);
  return a;
}

class PathReference : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    scene_ = new Scene(builtin_scene("cornell-path"));
    scene_->width = scene_->height = 16;
    ReferenceOptions o;
    o.paths_per_pixel = 4096;
    o.seed = 7;
    reference_ = new ReferenceImage(ReferencePathTracer(*scene_).render(o));
  }
  static void TearDownTestSuite() {
    delete scene_;
    delete reference_;
  }
  static Scene* scene_;
  static ReferenceImage* reference_;
};
Scene* PathReference::scene_ = nullptr;
ReferenceImage* PathReference::reference_ = nullptr;

TEST_F(PathReference, TheCornellBoxAgreesWithTheReferencePixelByPixel) {
  for (bool nee : {true, false}) {
    Scene s = *scene_;
    s.options.nee = nee;
    const Agreement a = agree(rill_estimate(s, 16, 64, {}), *reference_);
    EXPECT_TRUE(a.passes()) << "nee " << nee << ": " << a.beyond
                            << " pixel channels beyond 4.5 sigma, image mean at " << a.z_mean
                            << " sigma";
  }
}

// Off CI (--gtest_also_run_disabled_tests): the comparison's false-failure rate over 20
// independent seed sets for Rill and 5 references (the measurement the bound above rests on).
// Each run fails a correct integrator with probability about 1.5e-5, so the expected count of
// failures is 0.
TEST_F(PathReference, DISABLED_FalseFailureRateOverSeeds) {
  int failures = 0, beyond = 0, runs = 0;
  for (uint64_t ref_seed = 100; ref_seed < 105; ++ref_seed) {
    ReferenceOptions o;
    o.paths_per_pixel = 4096;
    o.seed = ref_seed;
    const ReferenceImage ref = ReferencePathTracer(*scene_).render(o);
    for (uint32_t base = 0; base < 4; ++base) {
      // Seeds 1001 + 100 base ..: disjoint from the other runs' and the tests'.
      const Estimate e = rill_estimate(*scene_, 16, 64, {}, 1001 + 100 * base);
      const Agreement a = agree(e, ref);
      failures += a.passes() ? 0 : 1;
      beyond += a.beyond;
      ++runs;
    }
  }
  std::printf(
      "%d runs: %d failed (expected 0), %.2f pixel channels beyond 4.5 sigma per run "
      "(the bound assumes 0.85)\n",
      runs, failures, static_cast<double>(beyond) / runs);
  EXPECT_EQ(failures, 0);
}

// The mutants must fail the comparison that the integrator passes.
TEST_F(PathReference, BrokenIntegratorsAreRejected) {
  for (PathMutation m :
       {PathMutation::NeeTwice, PathMutation::NoMisAtHits, PathMutation::NoRouletteBoost}) {
    TracerOptions o;
    o.mutation = m;
    const Agreement a = agree(rill_estimate(*scene_, 16, 64, o), *reference_);
    EXPECT_FALSE(a.passes()) << "mutation " << static_cast<int>(m) << " passed: " << a.beyond
                             << " beyond 4.5 sigma, image mean at " << a.z_mean << " sigma";
    std::printf("mutation %d: %d pixel channels beyond 4.5 sigma, image mean at %.1f sigma\n",
                static_cast<int>(m), a.beyond, a.z_mean);
  }
}

// ---- Progressive rendering ---------------------------------------------------------------

// Resuming from k samples to n gives the render of n at once, bit for bit, in both strategies
// that run the path integrator, its variance too when the sums kept their squares; a render stopped
// after a pass (after_pass) is the render of that many samples.
TEST(PathProgressive, ResumedAndStoppedRendersAreTheRendersOfTheirSamples) {
  Scene s = builtin_scene("cornell-path");
  s.width = 10;
  s.height = 8;
  Grid grid = build_grid_for(s);
  Tracer tracer(s, grid);
  for (const Strategy& strategy : {Strategy::Megakernel, Strategy::Wavefront}) {
    SCOPED_TRACE(strategy.name);
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.strategy = strategy;
    rs.width = s.width;
    rs.height = s.height;
    rs.spp = 7;
    const RenderResult once = tracer.render(rs, s.camera);
    EXPECT_EQ(once.spp, 7);
    RenderSettings first = rs;
    first.spp = 3;
    first.outputs.accumulation = true;
    const RenderResult part = tracer.render(first, s.camera);
    ASSERT_EQ(part.accumulation.samples, 3);
    RenderSettings rest = rs;
    rest.resume = &part.accumulation;
    const RenderResult resumed = tracer.render(rest, s.camera);
    EXPECT_EQ(resumed.spp, 7);
    // (Its ray count is the resumed samples' only.)
    ASSERT_EQ(resumed.color.size(), once.color.size());
    EXPECT_EQ(
        std::memcmp(resumed.color.data(), once.color.data(), once.color.size() * sizeof(glm::vec3)),
        0);
    // With the variance: the resumed render goes on adding to the saved squares, so its
    // variance is the render at once's too; from sums without squares it has none.
    RenderSettings with_var = rs;
    with_var.outputs.variance = true;
    const RenderResult once_var = tracer.render(with_var, s.camera);
    RenderSettings first_var = first;
    first_var.outputs.variance = true;
    const RenderResult part_var = tracer.render(first_var, s.camera);
    ASSERT_EQ(part_var.accumulation.squares.size(), part_var.accumulation.sum.size());
    EXPECT_TRUE(part.accumulation.squares.empty());
    RenderSettings rest_var = with_var;
    rest_var.resume = &part_var.accumulation;
    const RenderResult resumed_var = tracer.render(rest_var, s.camera);
    ASSERT_EQ(resumed_var.variance.size(), once_var.variance.size());
    EXPECT_EQ(std::memcmp(resumed_var.variance.data(), once_var.variance.data(),
                          once_var.variance.size() * sizeof(glm::vec3)),
              0);
    rest_var.resume = &part.accumulation;
    EXPECT_TRUE(tracer.render(rest_var, s.camera).variance.empty());
    // Stopped after the fourth pass: the render of 4 samples. (Passes of one sample: the
    // megakernel's otherwise take up to 16, PathRegeneration.* stops those.)
    RenderSettings stop = rs;
    stop.path_samples_per_launch = 1;
    stop.after_pass = [](int done) { return done < 4; };
    RenderSettings four = rs;
    four.spp = 4;
    const RenderResult stopped = tracer.render(stop, s.camera);
    EXPECT_EQ(stopped.spp, 4);
    testing::expect_identical(stopped, tracer.render(four, s.camera), "stopped at 4");
  }
}

// ---- Scene contract ---------------------------------------------------------------------

TEST(PathScene, TheSeedChangesTheImageAndOnlyTheSeed) {
  Scene s = furnace(0.5f, 1.0f, 4);
  s.width = s.height = 8;
  const RenderResult a = render(s, 2), b = render(s, 2);
  s.options.seed = 99;
  const RenderResult c = render(s, 2);
  EXPECT_EQ(std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec3)), 0);
  EXPECT_NE(std::memcmp(a.color.data(), c.color.data(), a.color.size() * sizeof(glm::vec3)), 0);
}

TEST(PathScene, AShaderWithoutABsdfIsRefusedNamingTheMaterial) {
  SurfaceShader toon;
  toon.name = "path-test-toon";
  toon.reflected = [](const ShadingPoint&, const LightSample& l) { return l.color; };
  if (find_shader(toon.name) == nullptr) register_shader(toon);
  Scene s = furnace(0.5f, 1.0f, 2);
  s.materials[0].name = "cel";
  s.materials[0].shader = "path-test-toon";
  s.materials[0].params.clear();
  Grid grid = build_grid_for(s);
  const std::string e = testing::error_of([&] { Tracer t(s, grid); });
  EXPECT_NE(e.find("material 'cel'"), std::string::npos) << e;
  EXPECT_NE(e.find("path-test-toon"), std::string::npos) << e;
  EXPECT_NE(e.find("BSDF"), std::string::npos) << e;
}

TEST(PathScene, BadValuesAreErrorsNamingTheKey) {
  auto error = [](const std::string& json) {
    return testing::error_of([&] { (void)parse_json_scene(json, ".", "s.json"); });
  };
  const std::string base =
      R"({"meshes": [{"shape": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "m"}], )";
  EXPECT_NE(error(base + R"("materials": {"m": {"shader": "diffuse", "emission": [1, -1, 0]}}})")
                .find("materials.m.emission"),
            std::string::npos);
  EXPECT_NE(error(base + R"("materials": {"m": {"shader": "diffuse", "emission": [1, 1e39, 0]}}})")
                .find("emission"),
            std::string::npos);
  EXPECT_NE(error(base + R"("materials": {"m": {"shader": "ggx", "roughness": 1.5}}})")
                .find("roughness must be in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error(base + R"("materials": {"m": {}}, "options": {"integrator": "bidir"}})")
                .find("options.integrator: unknown integrator 'bidir' (whitted, path)"),
            std::string::npos);
  EXPECT_NE(
      error(base + R"("materials": {"m": {}}, "options": {"spp": 2000000}})").find("options.spp"),
      std::string::npos);
  EXPECT_NE(error(base + R"("materials": {"m": {}}, "options": {"max_depth": 65}})")
                .find("options.max_depth"),
            std::string::npos);
  EXPECT_NE(error(base + R"("materials": {"m": {}}, "options": {"light_samples": 0}})")
                .find("options.light_samples"),
            std::string::npos);
}

TEST(PathScene, AnEmitterWithoutAreaIsAnError) {
  Scene s;
  s.add_material(diffuse("lamp", glm::vec3(0.5f), glm::vec3(1.0f)));
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 0);  // collinear: no area
  s.add_material(diffuse("floor", glm::vec3(0.5f)));
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  s.options.integrator = Integrator::Path;
  Grid grid = build_grid_for(s);
  const std::string e = testing::error_of([&] { Tracer t(s, grid); });
  EXPECT_NE(e.find("material 'lamp' emits light, but its triangles have no area"),
            std::string::npos)
      << e;
}

// ---- Emission textures ------------------------------------------------------------------

// A texture whose two colours are the same is that colour everywhere: the furnace whose walls
// emit it through a texture (scale 1) is the furnace with that constant emission, bit for bit
// (the light table's powers come from the texture's mean, the same number), with light
// sampling on, whose draws read the texture at the point drawn.
TEST(PathEmissionTexture, AUniformTextureRendersTheConstantEmissionsBits) {
  const Scene plain = furnace(0.6f, 0.75f, 4);
  Scene textured = plain;
  Texture flat;
  flat.name = "flat";
  flat.type = "checker";
  flat.color1 = flat.color2 = glm::vec3(0.75f);
  textured.textures.push_back(flat);
  textured.materials[0].emission = glm::vec3(1.0f);
  textured.materials[0].emission_texture = 0;
  const RenderResult a = render(plain, 4), b = render(textured, 4);
  ASSERT_EQ(a.color.size(), b.color.size());
  EXPECT_EQ(std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec3)), 0);
}

// The Cornell box's light through a noise texture (a solid texture: no texture coordinates
// needed), black to 2 (17, 12, 4) over cells of 2.5 cm. Light sampling, which reads the texture
// where it draws a point, and BSDF sampling alone, which reads it where a path happens to hit,
// estimate the same image. Statistic: the red channel summed over the image, S, whose variance
// is the sum of the pixels' variances of their means (the variance AOV; the pixels are
// independent); Z = (S_nee - S_bsdf) / sqrt(V_nee + V_bsdf) is normal (central limit theorem
// over 16 x 16 pixels of 64 samples each), so |Z| < 5 fails a correct integrator with
// probability below 6e-7. Light sampling that took the material's scale instead of the
// texture's value at the point drawn gave Z = -7.1 when this was written.
TEST(PathEmissionTexture, LightSamplingReadsTheTextureWhereItDraws) {
  Scene s = builtin_scene("cornell-path");
  s.width = s.height = 16;
  Texture noise;
  noise.name = "noise";
  noise.type = "noise";
  noise.color1 = glm::vec3(0.0f);
  noise.color2 = glm::vec3(34.0f, 24.0f, 8.0f);
  noise.scale = 40.0f;
  s.textures.push_back(noise);
  for (Material& m : s.materials)
    if (m.emits()) m.emission = glm::vec3(1.0f), m.emission_texture = 0;
  auto red_sum = [&](bool nee) {
    Scene v = s;
    v.options.nee = nee;
    const RenderResult r = render_with_variance(v, 64);
    double sum = 0, var = 0;
    for (size_t p = 0; p < r.color.size(); ++p) sum += r.color[p].x, var += r.variance[p].x;
    return std::pair{sum, var};
  };
  const auto [nee, nee_var] = red_sum(true);
  const auto [bsdf, bsdf_var] = red_sum(false);
  const double z = (nee - bsdf) / std::sqrt(nee_var + bsdf_var);
  std::printf("red summed over the image: light sampling %.4g, BSDF sampling %.4g, z %.2f\n", nee,
              bsdf, z);
  EXPECT_GT(nee, 0.0);
  EXPECT_LT(std::abs(z), 5.0) << "light sampling " << nee << ", BSDF sampling " << bsdf;
}

TEST(PathEmissionTexture, JsonAndMtlNameTheTexture) {
  const std::string base =
      R"({"meshes": [{"shape": "quad", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]], "material": "m"}], )"
      R"("textures": {"t": {"type": "checker", "color1": 0, "color2": 1, "scale": 4}}, )";
  const Scene s = parse_json_scene(
      base +
          R"("materials": {"m": {"shader": "diffuse", "emission": {"texture": "t", "scale": [2, 3, 4]}}}})",
      ".", "s.json");
  const Material& m = s.materials[static_cast<size_t>(s.material[0])];
  EXPECT_EQ(m.emission_texture, 0);
  EXPECT_EQ(m.emission, glm::vec3(2.0f, 3.0f, 4.0f));
  auto error = [&](const std::string& materials) {
    return testing::error_of([&] { (void)parse_json_scene(base + materials, ".", "s.json"); });
  };
  EXPECT_NE(error(R"("materials": {"m": {"emission": {"texture": "u"}}}})")
                .find("materials.m.emission: unknown texture 'u' (textures: t)"),
            std::string::npos);
  EXPECT_NE(error(R"("materials": {"m": {"emission": {"texture": "t", "gain": 2}}}})")
                .find("materials.m.emission: unknown key 'gain' (texture, scale)"),
            std::string::npos);
  EXPECT_NE(error(R"("materials": {"m": {"emission": {"texture": "t", "scale": -1}}}})")
                .find("materials.m.emission"),
            std::string::npos);
  // OBJ/MTL: map_Ke is the emission texture, scaled by Ke.
  testing::TempDir dir;
  const std::vector<unsigned char> texel{255, 128, 0};
  write_png_rgb8(dir.path("glow.png"), 1, 1, texel);
  dir.file("m.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 2 2 2\nmap_Ke glow.png\n");
  dir.file("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl lamp\nf 1 2 3\n");
  const Scene obj = load_scene(dir.path("m.obj"));
  const Material& lamp = obj.materials[static_cast<size_t>(obj.material[0])];
  ASSERT_EQ(lamp.emission_texture, 0);
  EXPECT_EQ(lamp.emission, glm::vec3(2.0f));
  EXPECT_EQ(obj.textures.at(0).texels.at(0).x, 1.0f);
}

// ---- AOVs ----------------------------------------------------------------------------------

// The albedo AOV is the first hit's reflectance as its shader defines it (SurfaceShader::albedo):
// a diffuse wall's colour, ggx's F0 plus its weighted base, 0 for a miss; in both strategies
// that run the path integrator.
TEST(PathAovs, TheAlbedoIsTheFirstHitsReflectance) {
  Scene s = builtin_scene("cornell-path");
  s.width = 12;
  s.height = 10;
  Material& white = s.materials[0];
  ASSERT_EQ(white.name, "white");
  white.shader = "ggx";  // the white walls become plastic
  white.params.clear();
  white.set("specular", glm::vec3(0.04f, 0.05f, 0.06f)).set("diffuse", glm::vec3(0.5f, 0.6f, 0.7f));
  Grid grid = build_grid_for(s);
  Tracer tracer(s, grid);
  for (const Strategy& strategy : {Strategy::Megakernel, Strategy::Wavefront}) {
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.strategy = strategy;
    rs.width = s.width;
    rs.height = s.height;
    rs.spp = 1;
    rs.outputs.albedo = true;
    const RenderResult r = tracer.render(rs, s.camera);
    ASSERT_EQ(r.albedo.size(), r.prim.size()) << strategy.name;
    int walls = 0;
    for (size_t p = 0; p < r.prim.size(); ++p) {
      glm::vec3 want(0.0f);
      if (r.prim[p] >= 0) {
        const Material& m =
            s.materials[static_cast<size_t>(s.material[static_cast<size_t>(r.prim[p])])];
        if (m.shader == "ggx") {
          const glm::vec3 f0 = m.params.at("specular").color;
          want = f0 + m.params.at("diffuse").color * (1.0f - std::max({f0.x, f0.y, f0.z}));
          ++walls;
        } else {
          want = m.params.at("diffuse").color;
        }
      }
      ASSERT_EQ(r.albedo[p], want) << strategy.name << " pixel " << p << " prim " << r.prim[p];
    }
    EXPECT_GT(walls, 0);
  }
}

// FrameOutputs::variance: each pixel's variance of its mean. Where every sample is the same
// (a furnace without light sampling, depth 2: PathFurnace above) it is 0 to rounding. With
// light sampling, two renders of independent seeds give pixel means m1, m2 whose
// (m1 - m2)^2 / 2 has the expectation of the pixel's variance of the mean, as the variance
// estimate itself does: over P = 1024 pixels the two averages agree. Their relative standard
// errors: (m1 - m2)^2 / 2 is sigma^2/n times a chi-square of 1 degree (relative sd sqrt 2), so
// its average has sqrt(2 / 1024) = 4.4%; the estimates (n - 1 = 7 degrees each) average to
// sqrt(2 / 7 / 1024) = 1.7%; together 4.7%, and 5 of them, 24%, bound the difference for
// normal samples. Path samples have heavier tails, so 30% is allowed.
TEST(PathAovs, TheVarianceIsEachPixelsVarianceOfItsMean) {
  auto render_var = [](Scene s, uint32_t seed) {
    s.options.seed = seed;
    return render_with_variance(s, 8);
  };
  Scene exact = furnace(0.5f, 1.0f, 2);
  exact.options.nee = false;
  const RenderResult e = render_var(exact, 0);
  ASSERT_EQ(e.variance.size(), e.color.size());
  for (const glm::vec3& v : e.variance)
    for (int c = 0; c < 3; ++c) ASSERT_LE(v[c], 1e-10f);
  const Scene noisy = furnace(0.7f, 0.5f, 6);
  const RenderResult a = render_var(noisy, 1), b = render_var(noisy, 2);
  double spread = 0, estimate = 0;
  for (size_t p = 0; p < a.color.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.color[p][c]) - b.color[p][c];
      spread += d * d / 2;
      estimate += (double(a.variance[p][c]) + b.variance[p][c]) / 2;
    }
  std::printf("variance of the mean, summed over pixels: from two seeds %.6g, estimated %.6g\n",
              spread, estimate);
  EXPECT_GT(estimate, 0.0);
  EXPECT_LT(std::abs(spread - estimate), 0.3 * estimate)
      << "spread " << spread << " estimate " << estimate;
}

// ---- Only the effects a scene calls for ------------------------------------------------

// The path kernel's cpu source holds light sampling only with some light, area-light sampling
// only with emitters, and GGX's code only with a ggx material: each effect the scene adds makes
// the generated source larger (measured on 2026-12-07: 83, 137, 152 and 212 KB).
TEST(PathFeatures, TheKernelHoldsOnlyWhatTheSceneCallsFor) {
  auto source_of = [](Scene s) {
    s.width = s.height = 4;
    Grid grid = build_grid_for(s);
    Tracer tracer(s, grid);
    return tracer.source("cpu", rill::Accuracy::Strict);
  };
  Scene area = builtin_scene("cornell-path");
  Scene point = area;
  point.materials.back().emission = glm::vec3(0.0f);  // the lamp no longer emits
  point.lights.push_back(Light{{0.278f, 0.54f, 0.28f}, glm::vec3(1.0f)});
  Scene dark = point;
  dark.lights.clear();
  Scene ggx = area;
  ggx.materials[0].shader = "ggx";  // the white walls
  ggx.materials[0].params.clear();
  const std::string a = source_of(area), p = source_of(point), d = source_of(dark),
                    g = source_of(ggx);
  EXPECT_LT(d.size(), p.size());
  EXPECT_LT(p.size(), a.size());
  EXPECT_LT(a.size(), g.size()) << "GGX's code only with a ggx material";
  std::printf(
      "path kernel source (cpu, bytes): no lights %zu, point light %zu, area light %zu, "
      "area light and ggx %zu\n",
      d.size(), p.size(), a.size(), g.size());
}

// ---- Every backend: the cpu backend's bits ----------------------------------------------

class PathRender : public ::testing::TestWithParam<std::string> {};

// Point and area lights (one two-sided), every built-in shader's BSDF (glass's delta lobes and
// its diffuse part, a mirror, ggx rough and at roughness 0 with a diffuse base, phong with
// reflection), MIS on and off, and with `textured` the lamp's emission through a noise texture.
Scene mixed_scene(bool mis, bool textured = false) {
  Scene s;
  const int floor = s.add_material(diffuse("floor", glm::vec3(0.6f, 0.5f, 0.4f)));
  add_quad(s, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3}, floor);
  add_quad(s, {-3, 0, -2}, {3, 0, -2}, {3, 3, -2}, {-3, 3, -2}, floor);
  Material lamp = diffuse("lamp", glm::vec3(0.2f), glm::vec3(4.0f, 3.5f, 3.0f));
  lamp.two_sided = true;
  if (textured) {
    Texture noise;
    noise.name = "noise";
    noise.type = "noise";
    noise.color1 = glm::vec3(0.2f);
    noise.scale = 3.0f;
    s.textures.push_back(noise);
    lamp.emission_texture = 0;
  }
  add_quad(s, {-0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, 0.5f}, {-0.5f, 2.5f, 0.5f},
           s.add_material(lamp));
  Material glass = with_shader("glass", "glass");
  glass.set("transmit", 0.8f).set("reflect", 0.1f);
  add_sphere(s, {-1.2f, 0.6f, 0}, 0.6f, 16, 12, s.add_material(glass));
  Material metal = with_shader("metal", "ggx");
  metal.set("roughness", 0.25f).set("specular", glm::vec3(0.9f, 0.6f, 0.3f));
  add_sphere(s, {0.2f, 0.5f, 0.3f}, 0.5f, 16, 12, s.add_material(metal));
  Material plastic = with_shader("plastic", "ggx");
  plastic.set("roughness", 0.0f)
      .set("specular", glm::vec3(0.04f))
      .set("diffuse", glm::vec3(0.1f, 0.3f, 0.8f));
  add_box(s, {1.0f, 0, -0.5f}, {1.8f, 0.8f, 0.3f}, s.add_material(plastic));
  Material mirror = with_shader("mirror", "mirror");
  add_quad(s, {2.5f, 0, -1.5f}, {2.5f, 0, 1.5f}, {2.5f, 2, 1.5f}, {2.5f, 2, -1.5f},
           s.add_material(mirror));
  Material shiny = with_shader("shiny", "phong");
  shiny.set("reflect", 0.4f);
  add_box(s, {-2.5f, 0, 0.8f}, {-1.9f, 0.5f, 1.4f}, s.add_material(shiny));
  s.lights.push_back(Light{{1.5f, 2.0f, 1.5f}, glm::vec3(2.0f, 2.0f, 1.5f)});
  s.camera = Camera{{0, 1.5f, 5}, {0, 0.7f, 0}, {0, 1, 0}, 45.0f};
  s.has_camera = true;
  s.width = 24;
  s.height = 16;
  s.background = glm::vec3(0.05f, 0.05f, 0.1f);
  s.options.integrator = Integrator::Path;
  s.options.max_depth = 6;
  s.options.mis = mis;
  return s;
}

TEST_P(PathRender, ImagesAreTheCpuBackendsBits) {
  std::string why;
  if (!testing::backend_available(GetParam(), why)) GTEST_SKIP() << why;
  for (bool mis : {true, false}) {
    const Scene s = mixed_scene(mis);
    const RenderResult want = render(s, 3, "cpu", {}, true),
                       got = render(s, 3, GetParam(), {}, true);
    testing::expect_identical(got, want, GetParam() + (mis ? " mis" : " no mis"));
    ASSERT_EQ(got.albedo.size(), want.albedo.size());
    EXPECT_EQ(
        std::memcmp(got.albedo.data(), want.albedo.data(), want.albedo.size() * sizeof(glm::vec3)),
        0)
        << "albedo";
  }
  testing::expect_identical(render(mixed_scene(true, true), 3, GetParam(), {}, true),
                            render(mixed_scene(true, true), 3, "cpu", {}, true),
                            GetParam() + " textured lamp");
  Scene cornell = builtin_scene("cornell-path");
  cornell.width = cornell.height = 16;
  testing::expect_identical(render(cornell, 2, GetParam(), {}, true),
                            render(cornell, 2, "cpu", {}, true), GetParam() + " cornell-path");
}

INSTANTIATE_TEST_SUITE_P(Backends, PathRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
