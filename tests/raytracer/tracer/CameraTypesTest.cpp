// The orthographic and thin-lens cameras (docs/camera.md): their rays recomputed here from the
// documented formulas, independently of Camera.cpp, and compared bit for bit with the host's
// and with each backend's; the lens point's Philox against Random123's known answers and its
// disk against uniformity; aperture 0 as the pinhole's bits; every strategy's bits the same;
// what the cameras image against analytic answers (an orthographic square's pixel count, the
// thin lens's sharp focal plane and its circle of confusion); bad values.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/film/Film.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Camera.h"

namespace rt {
namespace {

using testing::expect_identical;

// ---- docs/camera.md, written out again here, independently of Camera.cpp ----------------

float d_dot(glm::vec3 a, glm::vec3 b) {
  return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
glm::vec3 d_normalize(glm::vec3 v) {
  const float l = std::sqrt(d_dot(v, v));
  return glm::vec3(v.x / l, v.y / l, v.z / l);
}
glm::vec3 d_cross(glm::vec3 a, glm::vec3 b) {
  return glm::vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
// s * v + w, componentwise, the product first.
glm::vec3 d_add_scaled(glm::vec3 w, float s, glm::vec3 v) {
  glm::vec3 r;
  for (int k = 0; k < 3; ++k) r[k] = w[k] + s * v[k];
  return r;
}

// Philox4x32-10 by its paper's definition: the 64-bit products split into high and low words.
std::array<uint32_t, 4> d_philox(std::array<uint32_t, 4> x, std::array<uint32_t, 2> key) {
  for (int r = 0; r < 10; ++r) {
    const uint64_t a = static_cast<uint64_t>(0xD2511F53u) * x[0];
    const uint64_t b = static_cast<uint64_t>(0xCD9E8D57u) * x[2];
    x = {uint32_t(b >> 32) ^ x[1] ^ key[0], uint32_t(b & 0xffffffffu),
         uint32_t(a >> 32) ^ x[3] ^ key[1], uint32_t(a & 0xffffffffu)};
    key[0] += 0x9E3779B9u;
    key[1] += 0xBB67AE85u;
  }
  return x;
}

// The lens point of pixel (i, j), sample k: Philox of (i, j, k, 0) under (seed, "Lens"), the
// first two words' high 24 bits as floats, the concentric mapping with its polynomials.
glm::vec2 d_lens(uint32_t seed, int i, int j, int k) {
  const auto w = d_philox({uint32_t(i), uint32_t(j), uint32_t(k), 0u}, {seed, 0x4c656e73u});
  const float u = float(w[0] >> 8) * 0x1p-24f, v = float(w[1] >> 8) * 0x1p-24f;
  const float a = u * 2.0f - 1.0f, b = v * 2.0f - 1.0f;
  float r = b, q = a;
  if (std::fabs(a) > std::fabs(b)) r = a, q = b;
  if (r != 0.0f) q = q / r;
  const float p = q * 0x1.921fb6p-1f;
  const float p2 = p * p;
  float s = 0x1.71de3ap-19f;
  s = -0x1.a01a02p-13f + p2 * s;
  s = 0x1.111112p-7f + p2 * s;
  s = -0x1.555556p-3f + p2 * s;
  s = 1.0f + p2 * s;
  s = p * s;
  float c = -0x1.27e4fcp-22f;
  c = 0x1.a01a02p-16f + p2 * c;
  c = -0x1.6c16c2p-10f + p2 * c;
  c = 0x1.555556p-5f + p2 * c;
  c = -0.5f + p2 * c;
  c = 1.0f + p2 * c;
  return std::fabs(a) > std::fabs(b) ? glm::vec2(r * c, r * s) : glm::vec2(r * s, r * c);
}

struct DesignRay {
  glm::vec3 o, d;
};

DesignRay design(const Camera& c, int W, int H, int i, int j, glm::vec2 off, uint32_t seed, int k) {
  const glm::vec3 forward = d_normalize(c.look_at - c.eye);
  const glm::vec3 right = d_normalize(d_cross(forward, c.up));
  const glm::vec3 up = d_cross(right, forward);
  const float a = float(W) / float(H);
  float t;
  if (c.projection == Projection::Orthographic)
    t = c.ortho_height * 0.5f;
  else
    t = float(std::tan(double(c.fov_y * 0.5f * 0.0174532924f)));
  const float sx = ((((float(i) + off.x) / float(W)) * 2.0f - 1.0f) * t) * a;
  const float sy = (1.0f - ((float(j) + off.y) / float(H)) * 2.0f) * t;
  if (c.projection == Projection::Orthographic)
    return {d_add_scaled(d_add_scaled(c.eye, sx, right), sy, up), forward};
  const glm::vec3 v = c.look_at - c.eye;
  const float focus = c.focus_distance > 0.0f ? c.focus_distance : std::sqrt(d_dot(v, v));
  const float R = c.aperture, kk = R / focus;
  const glm::vec2 l = c.aperture > 0.0f ? d_lens(seed, i, j, k) : glm::vec2(0.0f);
  const float ex = sx - kk * l.x, ey = sy - kk * l.y;
  const glm::vec3 d = d_normalize(d_add_scaled(d_add_scaled(forward, ex, right), ey, up));
  if (c.aperture == 0.0f) return {c.eye, d};
  return {d_add_scaled(d_add_scaled(c.eye, R * l.x, right), R * l.y, up), d};
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

Camera ortho_camera(glm::vec3 eye, glm::vec3 at, glm::vec3 up, float height) {
  Camera c{eye, at, up, 45.0f};
  c.projection = Projection::Orthographic;
  c.ortho_height = height;
  return c;
}

Camera lens_camera(glm::vec3 eye, glm::vec3 at, glm::vec3 up, float fov, float R, float focus) {
  Camera c{eye, at, up, fov};
  c.aperture = R;
  c.focus_distance = focus;
  return c;
}

// Orthographic and thin-lens cameras of odd views: a tiny height far from the origin, the
// default focus distance, a wide lens focused close.
std::vector<Camera> test_cameras() {
  return {
      ortho_camera({1.5f, 2.25f, 7.0f}, {-0.3f, 0.7f, 0.1f}, {0.1f, 1.0f, 0.05f}, 3.7f),
      ortho_camera({-3e3f, 10.0f, 1e-3f}, {2.0f, -1.0f, 0.5f}, {0.0f, 0.0f, 1.0f}, 1e-3f),
      lens_camera({1.5f, 2.25f, 7.0f}, {-0.3f, 0.7f, 0.1f}, {0.1f, 1.0f, 0.05f}, 53.7f, 0.3f, 0),
      lens_camera({0.1f, 0.2f, 0.3f}, {0.3f, 0.2f, 0.1f}, {1, 1, 1}, 170.0f, 2.5f, 0.7f),
  };
}

// ---- host ---------------------------------------------------------------------------------

// Random123's known-answer vectors for Philox4x32-10 (kat_vectors), then lens_point against
// the design.
TEST(CameraTypes, TheLensPointIsPhiloxAndTheConcentricMapping) {
  EXPECT_EQ(d_philox({0, 0, 0, 0}, {0, 0}),
            (std::array<uint32_t, 4>{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}));
  EXPECT_EQ(d_philox({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff}),
            (std::array<uint32_t, 4>{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}));
  EXPECT_EQ(d_philox({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0}),
            (std::array<uint32_t, 4>{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}));
  for (uint32_t seed : {0u, 7u, 0xdeadbeefu})
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 20; ++j)
        for (int i = 0; i < 20; ++i) {
          const glm::vec2 a = lens_point(seed, i, j, k), b = d_lens(seed, i, j, k);
          ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << i << " " << j << " " << k;
        }
  // The mapping's corners and centre: (0.5, 0.5) is the centre, (1, 0.5) nearly (1, 0).
  EXPECT_EQ(lens_disk(glm::vec2(0.5f)), glm::vec2(0.0f));
  EXPECT_EQ(lens_disk(glm::vec2(0.75f, 0.5f)), glm::vec2(0.5f, 0.0f));
  EXPECT_EQ(lens_disk(glm::vec2(0.5f, 0.25f)), glm::vec2(0.0f, -0.5f));
}

// The concentric mapping is area-preserving: lens points are uniform on the unit disk. Over N
// points, E[r^2] = 1/2 with variance 1/12, and each of the 8 sectors of 45 degrees holds 1/8
// of them with variance (1/8)(7/8) / N; the bounds are 6 standard deviations (a false alarm
// about once in 10^8 per check), and the points stay within the disk up to rounding.
TEST(CameraTypes, LensPointsAreUniformOnTheDisk) {
  constexpr int kN = 64 * 64 * 16;
  double r2 = 0;
  std::array<int, 8> sector{};
  for (int k = 0; k < 16; ++k)
    for (int j = 0; j < 64; ++j)
      for (int i = 0; i < 64; ++i) {
        const glm::vec2 p = lens_point(3, i, j, k);
        const double q = double(p.x) * p.x + double(p.y) * p.y;
        ASSERT_LE(q, 1.0 + 1e-6);
        r2 += q;
        const double angle = std::atan2(double(p.y), double(p.x)) + M_PI;
        sector[std::min(7, static_cast<int>(angle / (M_PI / 4)))] += 1;
      }
  EXPECT_NEAR(r2 / kN, 0.5, 6 * std::sqrt(1.0 / 12 / kN));
  for (int s : sector) EXPECT_NEAR(double(s) / kN, 0.125, 6 * std::sqrt(0.125 * 0.875 / kN));
}

TEST(CameraTypes, HostRaysMatchTheFormulas) {
  const std::vector<Camera> cams = test_cameras();
  const glm::vec2 offsets[] = {{0.5f, 0.5f}, {0.0f, 0.9999f}, {0.3125f, 0.7f}};
  for (const Camera& c : cams) {
    const CameraFrame f = camera_frame(c, 37, 23);
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 23; ++j)
        for (int i = 0; i < 37; ++i) {
          const CameraRay got =
              camera_ray(f, i, j, offsets[k].x, offsets[k].y, lens_point(11, i, j, k));
          const DesignRay want = design(c, 37, 23, i, j, offsets[k], 11, k);
          ASSERT_TRUE(same_bits(got.origin, want.o) && same_bits(got.direction, want.d))
              << camera_kind_name(f.kind) << " pixel " << i << " " << j;
        }
  }
}

// The megakernel skips the camera rays of pixels outside pixels_seeing_box: for these
// cameras too, every pixel whose ray (at any offset and lens point) meets the box lies inside.
TEST(CameraTypes, PixelsSeeingABoxHoldEveryRayThatMeetsIt) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec2 offsets[] = {{0.0f, 0.0f}, {0.9999f, 0.9999f}, {0.5f, 0.5f}};
  int cut = 0, hits = 0;
  for (int c = 0; c < 200; ++c) {
    const int W = 41 + c % 23, H = 29 + c % 17;
    const glm::vec3 eye(4 * u(rng), 4 * u(rng), 6 + 2 * u(rng)), at(u(rng), u(rng), u(rng));
    const glm::vec3 up(0.2f * u(rng), 1.0f, 0.2f * u(rng));
    const Camera cam = c % 2 ? ortho_camera(eye, at, up, 1.0f + 3 * std::fabs(u(rng)))
                             : lens_camera(eye, at, up, 40.0f, 0.05f + std::fabs(u(rng)),
                                           c % 4 ? 3.0f + 4 * std::fabs(u(rng)) : 0.0f);
    const glm::vec3 centre(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const glm::vec3 half(0.05f + 0.5f * std::fabs(u(rng)), 0.05f + 0.5f * std::fabs(u(rng)),
                         0.05f + 0.5f * std::fabs(u(rng)));
    const glm::vec3 lo = centre - half, hi = centre + half;
    const CameraFrame f = camera_frame(cam, W, H);
    const PixelRect r = pixels_seeing_box(f, lo, hi);
    cut += !(r.first == glm::ivec2(0) && r.end == glm::ivec2(W, H));
    for (int k = 0; k < 8; ++k)
      for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
          const glm::vec2 o = offsets[k % 3];
          const CameraRay ray = camera_ray(f, i, j, o.x, o.y, lens_point(1, i, j, k));
          if (!testing::ray_meets_box(glm::dvec3(ray.origin), glm::dvec3(ray.direction),
                                      glm::dvec3(lo), glm::dvec3(hi)))
            continue;
          ++hits;
          ASSERT_TRUE(i >= r.first.x && i < r.end.x && j >= r.first.y && j < r.end.y)
              << "camera " << c << " (" << camera_kind_name(f.kind) << "): pixel (" << i << ", "
              << j << ") sees the box outside [" << r.first.x << ", " << r.end.x << ") x ["
              << r.first.y << ", " << r.end.y << ")";
        }
  }
  EXPECT_GT(cut, 150);  // not vacuous: most rectangles leave pixels out
  EXPECT_GT(hits, 10000);
}

std::string scene_error(const std::string& text) {
  try {
    (void)parse_json_scene(text, ".", "cam.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(CameraTypes, BadValuesNameTheKey) {
  const std::string base = R"({"builtin": "thesis-a", "camera": )";
  const std::pair<std::string, std::string> cases[] = {
      {R"({"type": "fisheye"})", "camera.type must be \"perspective\" or \"orthographic\""},
      {R"({"type": 3})", "camera.type must be"},
      {R"({"type": "orthographic"})", "needs camera.height"},
      {R"({"type": "orthographic", "height": 0})", "camera.height must be > 0"},
      {R"({"type": "orthographic", "height": -2})", "camera.height must be > 0"},
      {R"({"type": "orthographic", "height": "tall"})", "camera.height"},
      {R"({"height": 2})", "camera.height is the orthographic view's height"},
      {R"({"type": "orthographic", "height": 2, "aperture": 0.1})",
       "camera.aperture is for a perspective camera"},
      {R"({"type": "orthographic", "height": 2, "focus_distance": 3})",
       "camera.focus_distance is for a perspective camera"},
      {R"({"aperture": -0.1})", "camera.aperture must be >= 0"},
      {R"({"aperture": 1e39})", "camera.aperture"},
      {R"({"aperture": [1]})", "camera.aperture"},
      {R"({"focus_distance": 0})", "camera.focus_distance must be > 0"},
      {R"({"focus_distance": -1})", "camera.focus_distance must be > 0"},
      {R"({"aperture": 0.1, "keys": [{"time": 0, "aperture": 0.2}]})", "aperture"},
  };
  for (const auto& [cam, needle] : cases) {
    SCOPED_TRACE(cam);
    const std::string e = scene_error(base + cam + "}");
    EXPECT_NE(e.find("cam.json"), std::string::npos) << e;
    EXPECT_NE(e.find(needle), std::string::npos) << e;
  }
  // And the good ones read back as written.
  const Scene s = parse_json_scene(
      base + R"({"type": "orthographic", "height": 3.5, "eye": [0, 0, 9]}})", ".", "cam.json");
  EXPECT_EQ(s.camera.projection, Projection::Orthographic);
  EXPECT_EQ(s.camera.ortho_height, 3.5f);
  const Scene l =
      parse_json_scene(base + R"({"aperture": 0.25, "focus_distance": 4}})", ".", "cam.json");
  EXPECT_EQ(camera_kind(l.camera), CameraKind::ThinLens);
  EXPECT_EQ(l.camera.aperture, 0.25f);
  EXPECT_EQ(l.camera.focus_distance, 4.0f);
}

// ---- every backend ------------------------------------------------------------------------

class CameraTypesRender : public ::testing::TestWithParam<std::string> {};

Scene with_camera(const std::string& builtin, const Camera& c) {
  Scene s = builtin_scene(builtin);
  s.camera = c;
  s.validate();
  return s;
}

TEST_P(CameraTypesRender, RaysBitForBit) {
  RT_REQUIRE_BACKEND(GetParam());
  const std::vector<Camera> cams = test_cameras();
  const glm::ivec2 sizes[] = {{32, 32}, {37, 23}, {1, 1}};
  int n = 0;
  for (const Camera& c : cams) {
    Scene s = with_camera("thesis-a", c);
    s.options.seed = 12345 + n;
    Grid g = build_grid(s, 2);
    Tracer tracer(s, g);
    for (const glm::ivec2& sz : sizes)
      for (int k = 0; k < 3; ++k) {
        const glm::vec2 off = k == 0 ? glm::vec2(0.5f) : sample_offset(k);
        std::vector<glm::vec3> origins;
        const std::vector<glm::vec3> dirs =
            tracer.camera_rays(GetParam(), c, sz.x, sz.y, off, &origins, k);
        ASSERT_EQ(dirs.size(), size_t(sz.x) * sz.y);
        ASSERT_EQ(origins.size(), dirs.size());
        for (int j = 0; j < sz.y; ++j)
          for (int i = 0; i < sz.x; ++i) {
            const DesignRay want = design(c, sz.x, sz.y, i, j, off, uint32_t(s.options.seed), k);
            const size_t p = size_t(j) * sz.x + i;
            ASSERT_TRUE(same_bits(origins[p], want.o) && same_bits(dirs[p], want.d))
                << "camera " << n << " size " << sz.x << "x" << sz.y << " sample " << k
                << " pixel (" << i << ", " << j << ")";
          }
      }
    ++n;
  }
}

RenderResult render(Tracer& tracer, const Scene& s, const std::string& backend, Strategy strategy,
                    MegakernelLoop loop = MegakernelLoop::Auto, int spp = 0) {
  RenderSettings rs;
  rs.backend = backend;
  rs.strategy = strategy;
  rs.loop = loop;
  rs.spp = spp;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
  return tracer.render(rs, s.camera);
}

// aperture 0 is the pinhole, whatever the focus distance: the same kernels, the same bits.
TEST_P(CameraTypesRender, ApertureZeroIsThePinholesBits) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene pin = builtin_scene("thesis-a");
  Camera c = pin.camera;
  c.aperture = 0.0f;
  c.focus_distance = 3.0f;
  const Scene zero = with_camera("thesis-a", c);
  Grid g1 = build_grid(pin, 0), g2 = build_grid(zero, 0);
  Tracer a(pin, g1), b(zero, g2);
  EXPECT_EQ(a.source(GetParam()), b.source(GetParam()));
  expect_identical(render(a, pin, GetParam(), Strategy::Megakernel, MegakernelLoop::Auto, 2),
                   render(b, zero, GetParam(), Strategy::Megakernel, MegakernelLoop::Auto, 2),
                   "aperture 0");
}

// Whitted: the megakernel's two loops and multipass give one image; the path integrator: the
// megakernel and the wavefront. With 2 samples, so the second sample's lens point is used.
TEST_P(CameraTypesRender, EveryStrategyGivesTheSameBits) {
  RT_REQUIRE_BACKEND(GetParam());
  const std::string be = GetParam();
  const Scene a = builtin_scene("thesis-a");
  const Camera cams[] = {
      ortho_camera(a.camera.eye, a.camera.look_at, a.camera.up, 4.0f),
      lens_camera(a.camera.eye, a.camera.look_at, a.camera.up, a.camera.fov_y, 0.2f, 0.0f)};
  for (const Camera& c : cams) {
    SCOPED_TRACE(camera_kind_name(camera_kind(c)));
    Scene s = with_camera("thesis-a", c);
    s.width = 48;
    s.height = 36;
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    const RenderResult seg = render(t, s, be, Strategy::Megakernel, MegakernelLoop::Segment, 2);
    expect_identical(seg, render(t, s, be, Strategy::Megakernel, MegakernelLoop::Ray, 2), "ray");
    expect_identical(seg, render(t, s, be, Strategy::Multipass, MegakernelLoop::Auto, 2),
                     "multipass");
    Camera pc = c;
    Scene p = builtin_scene("cornell-path");
    pc.eye = p.camera.eye, pc.look_at = p.camera.look_at, pc.up = p.camera.up;
    if (c.projection == Projection::Orthographic) pc.ortho_height = 600.0f;
    p.camera = pc;
    p.width = 40;
    p.height = 40;
    p.options.max_depth = 3;
    Grid pg = build_grid(p, 0);
    Tracer pt(p, pg);
    expect_identical(render(pt, p, be, Strategy::Megakernel, MegakernelLoop::Auto, 2),
                     render(pt, p, be, Strategy::Wavefront, MegakernelLoop::Auto, 2), "wavefront");
    if (be != "cpu") {  // and the CPU backend's bits (strict mode)
      expect_identical(seg, render(t, s, "cpu", Strategy::Megakernel, MegakernelLoop::Segment, 2),
                       "cpu");
    }
  }
}

// A square of side L facing an orthographic camera covers the pixels whose centres lie within
// it on the image plane, whatever its distance: counted in the primitive AOV against the count
// of centres computed in double (the square is placed so that no centre lies within 1e-3
// pixels of an edge).
TEST_P(CameraTypesRender, AnOrthographicSquareCoversItsPixelsAtAnyDistance) {
  RT_REQUIRE_BACKEND(GetParam());
  const int W = 64, H = 48;
  const float height = 3.0f, L = 1.37f;
  const glm::vec2 centre(0.21f, -0.13f);
  auto inside = [&](int n, int size, double half_extent, double c, double flip) {
    int count = 0;
    for (int p = 0; p < n; ++p) {
      const double s = flip * ((p + 0.5) / size * 2 - 1) * half_extent;
      const double d = std::fabs(s - c) - L / 2.0;
      EXPECT_GT(std::fabs(d), 1e-3 * 2 * half_extent / size);
      count += d < 0;
    }
    return count;
  };
  const int want = inside(W, W, height / 2.0 * W / H, centre.x, 1.0) *
                   inside(H, H, height / 2.0, centre.y, -1.0);
  for (float z : {-1.0f, -40.0f}) {
    Scene s;
    s.name = "square";
    Material m;
    m.name = "m";
    m.shader = "diffuse";
    const int mat = s.add_material(m);
    const float x0 = centre.x - L / 2, x1 = centre.x + L / 2, y0 = centre.y - L / 2,
                y1 = centre.y + L / 2;
    add_quad(s, {x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}, mat);
    s.camera = ortho_camera({0, 0, 2}, {0, 0, 0}, {0, 1, 0}, height);
    s.has_camera = true;
    s.width = W;
    s.height = H;
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    const RenderResult r = render(t, s, GetParam(), Strategy::Megakernel);
    int covered = 0;
    for (int32_t p : r.prim) covered += p >= 0;
    EXPECT_EQ(covered, want) << "square at z = " << z;
  }
}

// The thin lens images an emitting half-plane x >= 0 at depth zq (the path integrator takes a
// camera ray's emission whole, so a pixel is the fraction of its samples that meet the plane,
// times its emission 1). Seen from the screen, the lens of radius R focused at f spreads a
// point at depth z over a disk of radius rho = R |1/f - 1/z| (docs/camera.md): the edge's
// profile is the fraction F(x / rho) of the unit disk left of x, averaged over the pixel's
// sample offsets. On the focal plane (rho = 0) it is a step: every pixel but the edge's own
// is 0 or 1 exactly. Off it, each column's mean over the rows against the predicted profile:
// the samples' lens points are independent, so a column of 12 rows x 64 samples has a
// standard deviation of at most 0.5 / sqrt(768) = 0.018; the bound is 5 of them, 0.09, and
// the blur must span the predicted width (the profile's 5%-95% columns).
TEST_P(CameraTypesRender, TheThinLensBlursByTheCircleOfConfusion) {
  RT_REQUIRE_BACKEND(GetParam());
  const int W = 64, H = 12, spp = 64;
  const float zq = 4.0f, R = 0.4f, fov = 20.0f;
  auto scene_at = [&](float focus) {
    Scene s;
    s.name = "edge";
    Material m;
    m.name = "light";
    m.shader = "diffuse";
    m.set("diffuse", glm::vec3(0.0f));
    m.emission = glm::vec3(1.0f);
    const int mat = s.add_material(m);
    const float e = 0.0137f;  // the edge a little off a column boundary
    add_quad(s, {e, -50, -zq}, {50, -50, -zq}, {50, 50, -zq}, {e, 50, -zq}, mat);
    s.camera = lens_camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, fov, R, focus);
    s.has_camera = true;
    s.width = W;
    s.height = H;
    s.options.integrator = Integrator::Path;
    s.options.max_depth = 1;
    s.options.spp = spp;
    s.background = glm::vec3(0.0f);
    return s;
  };
  const CameraFrame f = camera_frame(scene_at(zq).camera, W, H);
  const double px = 2.0 * f.tan_half * f.aspect / W;  // a pixel's width in screen units
  const double edge = 0.0137 / zq;
  auto disk_left = [](double x) {  // the fraction of the unit disk with abscissa < x
    if (x <= -1) return 0.0;
    if (x >= 1) return 1.0;
    return 0.5 + (x * std::sqrt(1 - x * x) + std::asin(x)) / M_PI;
  };
  // On the focal plane: a step.
  {
    const Scene s = scene_at(zq);
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    const RenderResult r = render(t, s, GetParam(), Strategy::Megakernel);
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i) {
        const double left = (i / double(W) * 2 - 1) * f.tan_half * f.aspect;
        if (edge > left && edge < left + px) continue;  // the edge's own column
        const float v = r.color[size_t(j) * W + i].x;
        EXPECT_EQ(v, left >= edge ? 1.0f : 0.0f) << "pixel " << i << " " << j;
      }
  }
  // Focused at 2: rho = R |1/2 - 1/4| = 0.1 screen units, 2.3 pixels.
  const float focus = 2.0f;
  const double rho = R * std::fabs(1.0 / focus - 1.0 / zq);
  ASSERT_GT(rho / px, 2.0);
  const Scene s = scene_at(focus);
  Grid g = build_grid(s, 0);
  Tracer t(s, g);
  const RenderResult r = render(t, s, GetParam(), Strategy::Megakernel);
  int blurred = 0;
  for (int i = 0; i < W; ++i) {
    double want = 0;
    for (int k = 0; k < spp; ++k) {
      const glm::vec2 o = k == 0 ? glm::vec2(0.5f) : sample_offset(k);
      const double sx = ((i + o.x) / W * 2 - 1) * f.tan_half * f.aspect;
      want += disk_left((sx - edge) / rho);
    }
    want /= spp;
    double got = 0;
    for (int j = 0; j < H; ++j) got += r.color[size_t(j) * W + i].x;
    got /= H;
    EXPECT_NEAR(got, want, 0.09) << "column " << i;
    blurred += want > 0.05 && want < 0.95;
  }
  // The profile's 5%-95% span is 2 x 0.86 rho (F(0.86) = 0.95) plus a pixel.
  EXPECT_GE(blurred, static_cast<int>(std::floor(2 * 0.86 * rho / px)) - 1);
}

// A tracer's kernels make its scene's kind of camera ray; another kind is an error.
TEST_P(CameraTypesRender, AnotherKindOfCameraIsAnError) {
  RT_REQUIRE_BACKEND(GetParam());
  const Scene s = builtin_scene("thesis-a");
  Grid g = build_grid(s, 0);
  Tracer t(s, g);
  Camera c = s.camera;
  c.aperture = 0.1f;
  RenderSettings rs;
  rs.backend = GetParam();
  try {
    (void)t.render(rs, c);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a thin lens camera"), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, CameraTypesRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
