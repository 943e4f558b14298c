// Self-checks of the reference path tracer (support/ReferencePathTracer.h), the ground truth
// of the path integrator's tests: scenes whose radiance is known exactly (closed furnaces,
// a floor under a uniform sky, emitters filling the view) and one whose radiance is known in
// expectation with a bound derived below, determinism, and the Cornell box it provides.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "rill/rt/scene/Scene.h"
#include "support/ReferencePathTracer.h"

namespace rt::testing {
namespace {

rt::Material ref_diffuse(const std::string& name, const glm::vec3& albedo,
                         const glm::vec3& emission = glm::vec3(0.0f), bool two_sided = false) {
  rt::Material m;
  m.name = name;
  m.shader = "diffuse";
  m.set("diffuse", albedo);
  if (emission != glm::vec3(0.0f)) set_emission(m, emission, two_sided);
  return m;
}

// A closed box [-1, 1]^3 with the camera inside, its faces' normals pointing in (inward) or
// out, every face of the one material.
rt::Scene ref_closed_box(const rt::Material& m, bool inward, const glm::vec3& background,
                         int max_depth) {
  rt::Scene s;
  rt::add_box(s, glm::vec3(-1.0f), glm::vec3(1.0f), s.add_material(m), {}, inward);
  s.camera = rt::Camera{{0.2f, -0.1f, 0.5f}, {0.0f, 0.3f, -1.0f}, {0.0f, 1.0f, 0.0f}, 70.0f};
  s.has_camera = true;
  s.background = background;
  s.options.max_depth = max_depth;
  return s;
}

ReferenceImage ref_render(const rt::Scene& s, int w, int h, int n, uint64_t seed = 1,
                          int threads = 0) {
  return ReferencePathTracer(s).render(ReferenceOptions{w, h, n, seed, threads});
}

// Every pixel's mean is `expected` to 1e-12 and its variance 0 to 1e-24.
void expect_exact(const ReferenceImage& img, const glm::dvec3& expected, const std::string& what) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(img.mean_at(x, y)[c], expected[c], 1e-12)
            << what << ": pixel (" << x << ", " << y << ") channel " << c;
        ASSERT_LE(img.variance_at(x, y)[c], 1e-24)
            << what << ": pixel (" << x << ", " << y << ") channel " << c;
      }
}

// A furnace: every wall diffuse of albedo a and emission Le, facing the camera inside. No
// path escapes, and at each vertex k = 0..D the path adds throughput a^k times Le, so every
// path (not only the mean) is Le (1 + a + ... + a^D): with a = 0.5 and D = 3, 1.875. a = 0.5
// and Le = 1 make every partial sum exact in double, so only a path that escaped or missed a
// vertex could differ; the background (7) would show where one escaped.
TEST(ReferencePathTracer, FurnaceGivesTheGeometricSeriesInEveryPath) {
  const rt::Material wall = ref_diffuse("wall", glm::vec3(0.5f), glm::vec3(1.0f));
  expect_exact(ref_render(ref_closed_box(wall, true, glm::vec3(7.0f), 3), 16, 12, 64),
               glm::dvec3(1.875), "D = 3");
  // Le (1 - a^(D+1)) / (1 - a) for the other depths: 1, 1.5, 1.75, ..
  for (int depth : {0, 1, 2, 6}) {
    const double expected = 2.0 * (1.0 - std::ldexp(1.0, -(depth + 1)));
    expect_exact(ref_render(ref_closed_box(wall, true, glm::vec3(7.0f), depth), 8, 8, 16),
                 glm::dvec3(expected), "D = " + std::to_string(depth));
  }
}

// The same box without emission under a background of 1: nothing escapes, so 0.
TEST(ReferencePathTracer, ClosedBoxWithoutEmissionIsBlackWhateverTheBackground) {
  const rt::Material wall = ref_diffuse("wall", glm::vec3(0.9f));
  expect_exact(ref_render(ref_closed_box(wall, true, glm::vec3(1.0f), 5), 16, 12, 64),
               glm::dvec3(0.0), "closed box");
}

// Emission is one-sided: with the faces' normals pointing out, the camera and every path
// inside see only back sides, so 0; two-sided, the furnace's 1.875 again.
TEST(ReferencePathTracer, EmissionIsOneSidedUnlessTwoSided) {
  const rt::Material one = ref_diffuse("one", glm::vec3(0.5f), glm::vec3(1.0f));
  expect_exact(ref_render(ref_closed_box(one, false, glm::vec3(0.0f), 3), 8, 8, 64),
               glm::dvec3(0.0), "one-sided, seen from behind");
  const rt::Material two = ref_diffuse("two", glm::vec3(0.5f), glm::vec3(1.0f), true);
  expect_exact(ref_render(ref_closed_box(two, false, glm::vec3(0.0f), 3), 8, 8, 64),
               glm::dvec3(1.875), "two-sided, seen from behind");
}

// A floor of albedo a at y = 0 (normal up), far larger than the view, under a uniform sky B,
// the camera above it looking down (`up` along -z), and optionally a wall plane x = 2 facing
// the floor (normal -x), 1e6 wide and high, black (albedo 0) with emission Le.
rt::Scene ref_floor(const glm::vec3& albedo, const glm::vec3& sky, int max_depth,
                    const glm::vec3* wall_emission = nullptr) {
  rt::Scene s;
  const int floor = s.add_material(ref_diffuse("floor", albedo));
  rt::add_quad(s, {-10.0f, 0.0f, -10.0f}, {-10.0f, 0.0f, 10.0f}, {10.0f, 0.0f, 10.0f},
               {10.0f, 0.0f, -10.0f}, floor);
  if (wall_emission != nullptr) {
    const int wall = s.add_material(ref_diffuse("wall", glm::vec3(0.0f), *wall_emission));
    const float big = 1e6f;
    rt::add_quad(s, {2.0f, -1.0f, -big}, {2.0f, -1.0f, big}, {2.0f, big, big}, {2.0f, big, -big},
                 wall);
  }
  s.camera = rt::Camera{{0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 30.0f};
  s.has_camera = true;
  s.background = sky;
  s.options.max_depth = max_depth;
  return s;
}

// With only sky above the floor, every path is camera -> floor -> sky: throughput a, then
// a * B, exactly (variance 0). Without a bounce (D = 0) the floor, which does not emit, is 0.
TEST(ReferencePathTracer, FloorUnderUniformSkyIsAlbedoTimesSky) {
  const glm::vec3 a(0.5f, 0.25f, 0.75f), sky(1.0f, 2.0f, 0.5f);
  expect_exact(ref_render(ref_floor(a, sky, 1), 12, 10, 64), glm::dvec3(a) * glm::dvec3(sky),
               "D = 1");
  expect_exact(ref_render(ref_floor(a, sky, 4), 6, 6, 64), glm::dvec3(a) * glm::dvec3(sky),
               "D = 4");
  expect_exact(ref_render(ref_floor(a, sky, 0), 6, 6, 16), glm::dvec3(0.0), "D = 0");
}

// The floor with the emitting wall, D = 1: the camera sees floor points P with |P.x| <=
// tan(15 deg) < 0.27. A bounce direction w (cosine-weighted, w.y > 0) with w.x <= 0 escapes
// (B); one with w.x > 0 meets the plane x = 2 at a distance s <= 2.27 / w.x and sees the
// wall's Le unless it meets the plane beyond the wall's extent (1e6). P(w.x > 0) = 1/2
// exactly (the distribution is symmetric in x), and those beyond have w.x < 2.27e-6: a strip
// of the unit disk onto which cosine-weighted directions project uniformly, of probability
// below 2 * 2.27e-6 * 2 / pi < 1e-5. So the mean is
// mu = a (B + Le) / 2, up to a bias |a (Le - B)| 1e-5 = 1e-5 here, and each path is a B or
// a Le with probability 1/2: sigma^2 = (a (Le - B))^2 / 4 = 0.25 (a = 0.5, B = 1, Le = 3).
// - Each pixel's mean (n = 4096, normal to a good approximation) is within 5 reported
//   standard errors (+ the bias): a two-sided 5-sigma excursion has probability 5.7e-7, so
//   one in 64 pixels 3.7e-5 (the seed is fixed: the test either always passes or never).
// - The image's mean (64 independent pixels) within 4 standard errors: probability 6.3e-5.
// - The reported variance of the mean is s^2 / n with s^2 = n / (n - 1) p^ (1 - p^) (a (Le -
//   B))^2 for the fraction p^ of wall paths: p^ (1 - p^) = 1/4 - (p^ - 1/2)^2, and within 5
//   sigma |p^ - 1/2| <= 5 / (2 sqrt(n)) = 0.039, so s^2 / sigma^2 is in [0.994, 1.0003]:
//   checked to 1 %, which the scale of n (4096) or of n - 1 against n would miss badly.
TEST(ReferencePathTracer, WallHalfTheSkyGivesTheMeanOfSkyAndWall) {
  const float a = 0.5f, sky = 1.0f, le = 3.0f;
  const glm::vec3 wall(le);
  const int n = 4096;
  const ReferenceImage img = ref_render(ref_floor(glm::vec3(a), glm::vec3(sky), 1, &wall), 8, 8, n);
  const double mu = a * (sky + le) / 2.0, bias = 1e-5;
  const double sigma2 = (a * (le - sky)) * (a * (le - sky)) / 4.0;
  glm::dvec3 sum(0.0), sum_var(0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const glm::dvec3 m = img.mean_at(x, y), v = img.variance_at(x, y);
      sum += m;
      sum_var += v;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(m[c], mu, 5.0 * std::sqrt(v[c]) + bias)
            << "pixel (" << x << ", " << y << ") channel " << c;
        EXPECT_NEAR(v[c] * n / sigma2, 1.0, 0.01)
            << "pixel (" << x << ", " << y << ") channel " << c;
      }
    }
  const double pixels = img.width * img.height;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(sum[c] / pixels, mu, 4.0 * std::sqrt(sum_var[c]) / pixels + bias) << c;
}

// The image's orientation and the camera's framing (docs/camera.md): four emitting quads
// facing the camera, which looks at their common corner, fill the view, with Le 1 at the top
// left, 2 top right, 3 bottom left, 4 bottom right; D = 0. With an even width and height the
// image's middle lines fall on pixel edges, so each pixel sees one quad only, exactly. A wide
// image (aspect 1.5) checks that the aspect scales the width, not the height: the quads end
// at |x| = 2.2 and |y| = 1.5, and the view at distance 5 reaches |x| = 5 tan(15 deg) 1.5 =
// 2.01 and |y| = 1.34; scaling the height instead would reach |y| = 2.01 and see the
// background (9).
TEST(ReferencePathTracer, PixelsRunRightAndDownFromTheTopLeft) {
  rt::Scene s;
  const float xs[3] = {-2.2f, 0.0f, 2.2f}, ys[3] = {1.5f, 0.0f, -1.5f};
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 2; ++col) {
      const float le = float(1 + col + 2 * row);
      const int m = s.add_material(
          ref_diffuse("q" + std::to_string(row * 2 + col), glm::vec3(0.5f), glm::vec3(le)));
      // Counter-clockwise seen from +z: the normal points at the camera.
      rt::add_quad(s, {xs[col], ys[row + 1], 0.0f}, {xs[col + 1], ys[row + 1], 0.0f},
                   {xs[col + 1], ys[row], 0.0f}, {xs[col], ys[row], 0.0f}, m);
    }
  s.camera = rt::Camera{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 30.0f};
  s.has_camera = true;
  s.background = glm::vec3(9.0f);
  s.options.max_depth = 0;
  const ReferenceImage img = ref_render(s, 12, 8, 32);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double expected = 1 + (x >= img.width / 2 ? 1 : 0) + (y >= img.height / 2 ? 2 : 0);
      ASSERT_EQ(img.mean_at(x, y), glm::dvec3(expected)) << "pixel (" << x << ", " << y << ")";
    }
}

// The same seed gives the same bits whatever the threads; another seed another image.
TEST(ReferencePathTracer, SameSeedSameImageWhateverTheThreads) {
  const rt::Scene s = path_cornell();
  const ReferenceImage a = ref_render(s, 8, 6, 32, 5, 1), b = ref_render(s, 8, 6, 32, 5, 3),
                       c = ref_render(s, 8, 6, 32, 6, 2);
  ASSERT_EQ(a.mean.size(), 48u);
  EXPECT_EQ(std::memcmp(a.mean.data(), b.mean.data(), a.mean.size() * sizeof(glm::dvec3)), 0);
  EXPECT_EQ(
      std::memcmp(a.variance.data(), b.variance.data(), a.variance.size() * sizeof(glm::dvec3)), 0);
  EXPECT_NE(std::memcmp(a.mean.data(), c.mean.data(), a.mean.size() * sizeof(glm::dvec3)), 0);
}

// path_cornell(): the built-in box's triangles and camera, diffuse materials of the same
// colours, no point light, and the light quad facing down; its image is finite, not
// negative and not black (a sanity check; the values are the comparison tests').
TEST(ReferencePathTracer, PathCornellIsTheBuiltinBoxWithAnAreaLight) {
  const rt::Scene builtin = rt::builtin_scene("cornell"), s = path_cornell();
  ASSERT_NO_THROW(s.validate());
  ASSERT_EQ(s.triangle_count(), builtin.triangle_count() + 2);
  for (size_t i = 0; i < builtin.positions.size(); ++i)
    ASSERT_EQ(s.positions[i], builtin.positions[i]) << i;
  for (size_t i = 0; i < builtin.triangle_count(); ++i) {
    const rt::Material& m = s.materials[s.material[i]];
    EXPECT_EQ(m.shader, "diffuse");
    EXPECT_EQ(m.params.at("diffuse").color,
              builtin.materials[builtin.material[i]].params.at("diffuse").color);
    EXPECT_EQ(emission_of(m), glm::dvec3(0.0));
  }
  for (size_t i = builtin.triangle_count(); i < s.triangle_count(); ++i) {
    const glm::vec3* p = &s.positions[3 * i];
    EXPECT_LT(glm::cross(p[1] - p[0], p[2] - p[0]).y, 0.0f) << "the light faces down";
    EXPECT_EQ(emission_of(s.materials[s.material[i]]), glm::dvec3(17.0, 12.0, 4.0));
  }
  EXPECT_TRUE(s.lights.empty());
  EXPECT_EQ(s.camera.eye, builtin.camera.eye);

  const ReferenceImage img = ref_render(s, 16, 16, 1024);
  glm::dvec3 sum(0.0);
  for (size_t i = 0; i < img.mean.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(img.mean[i][c]) && img.mean[i][c] >= 0.0) << i;
      ASSERT_TRUE(std::isfinite(img.variance[i][c]) && img.variance[i][c] >= 0.0) << i;
      sum[c] += img.mean[i][c];
    }
  for (int c = 0; c < 3; ++c) EXPECT_GT(sum[c] / double(img.mean.size()), 0.01) << c;
}

TEST(ReferencePathTracer, RefusesWhatItDoesNotImplement) {
  rt::Scene s = path_cornell();
  s.materials[0].shader = "phong";
  EXPECT_THROW(ReferencePathTracer{s}, std::invalid_argument);
  s = path_cornell();
  s.materials[0].params["diffuse"] = rt::ParamValue::of_texture(0);
  EXPECT_THROW(ReferencePathTracer{s}, std::invalid_argument);
  s = path_cornell();
  ReferenceOptions one;
  one.paths_per_pixel = 1;
  EXPECT_THROW(ReferencePathTracer(s).render(one), std::invalid_argument);
}

}  // namespace
}  // namespace rt::testing
