// Renders, per backend: camera rays bit for bit as docs/camera.md defines them, depth and
// primitive-id AOVs against a brute-force double-precision reference, every output
// bitwise identical to the CPU backend's (strict mode), and scenes with bad geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <random>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/Camera.h"

namespace rt {
namespace {
using testing::expect_identical;

class Render : public ::testing::TestWithParam<std::string> {};

// docs/camera.md, written out again here, independently of Camera.cpp.
glm::vec3 design_ray(const Camera& c, int W, int H, int i, int j) {
  auto dot = [](glm::vec3 a, glm::vec3 b) { return (a.x * b.x + a.y * b.y) + a.z * b.z; };
  auto normalize = [&](glm::vec3 v) {
    float l = std::sqrt(dot(v, v));
    return glm::vec3(v.x / l, v.y / l, v.z / l);
  };
  auto cross = [](glm::vec3 a, glm::vec3 b) {
    return glm::vec3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
  };
  glm::vec3 forward = normalize(c.look_at - c.eye);
  glm::vec3 right = normalize(cross(forward, c.up));
  glm::vec3 true_up = cross(right, forward);
  float a = static_cast<float>(W) / static_cast<float>(H);
  float arg = c.fov_y * 0.5f * 0.0174532924f;
  float t = static_cast<float>(std::tan(static_cast<double>(arg)));
  float sx = ((static_cast<float>(i) + 0.5f) / static_cast<float>(W) * 2.0f - 1.0f) * t * a;
  float sy = (1.0f - (static_cast<float>(j) + 0.5f) / static_cast<float>(H) * 2.0f) * t;
  glm::vec3 d;
  for (int k = 0; k < 3; ++k) d[k] = (forward[k] + sx * right[k]) + sy * true_up[k];
  return normalize(d);
}

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(Camera, HostFrameMatchesTheFormula) {
  Camera c{{1.5f, 2.25f, 7.0f}, {-0.3f, 0.7f, 0.1f}, {0.1f, 1.0f, 0.05f}, 53.7f};
  CameraFrame f = camera_frame(c, 37, 23);
  for (int j = 0; j < 23; ++j)
    for (int i = 0; i < 37; ++i)
      ASSERT_TRUE(same_bits(camera_ray(f, i, j), design_ray(c, 37, 23, i, j)));
  // t is tan evaluated in double, rounded once.
  EXPECT_EQ(f.tan_half,
            static_cast<float>(std::tan(static_cast<double>(53.7f * 0.5f * 0.0174532924f))));
}

// pixels_seeing_box is what lets the megakernel skip a pixel's camera ray: every pixel whose
// ray, at any sample offset, meets the box must lie inside its rectangle.
TEST(Camera, PixelsSeeingABoxHoldEveryRayThatMeetsIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float fovs[] = {0.002f, 45.0f, 90.0f, 150.0f};  // 0.002: rounding spans many pixels
  const glm::vec2 offsets[] = {
      {0.0f, 0.0f}, {0.9999f, 0.0f}, {0.0f, 0.9999f}, {0.9999f, 0.9999f}, {0.5f, 0.5f}};
  int cut = 0, whole = 0, inside_hits = 0;
  for (int c = 0; c < 400; ++c) {
    const int W = 41 + c % 23, H = 29 + c % 17;
    Camera cam{{4 * u(rng), 4 * u(rng), 6 + 2 * u(rng)},
               {u(rng), u(rng), u(rng)},
               {0.2f * u(rng), 1.0f, 0.2f * u(rng)},
               fovs[c % 4]};
    const glm::vec3 centre(2 * u(rng), 2 * u(rng), 2 * u(rng));
    const glm::vec3 half(0.05f + std::fabs(u(rng)), 0.05f + std::fabs(u(rng)),
                         c % 5 == 0 ? 0.0f : 0.05f + std::fabs(u(rng)));  // some flat
    const glm::vec3 lo = centre - half, hi = centre + half;
    const CameraFrame f = camera_frame(cam, W, H);
    const PixelRect r = pixels_seeing_box(f, lo, hi);
    const bool all = r.first == glm::ivec2(0) && r.end == glm::ivec2(W, H);
    (all ? whole : cut) += 1;
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i)
        for (const glm::vec2 o : offsets) {
          const glm::vec3 d = camera_ray(f, i, j, o.x, o.y);
          if (!testing::ray_meets_box(glm::dvec3(f.eye), glm::dvec3(d), glm::dvec3(lo),
                                      glm::dvec3(hi)))
            continue;
          const bool inside = i >= r.first.x && i < r.end.x && j >= r.first.y && j < r.end.y;
          ASSERT_TRUE(inside) << "camera " << c << ": pixel (" << i << ", " << j
                              << ") sees the box but lies outside [" << r.first.x << ", " << r.end.x
                              << ") x [" << r.first.y << ", " << r.end.y << ")";
          inside_hits += !all;
        }
  }
  // Not vacuous: most boxes leave pixels out, and their rectangles hold rays that meet them.
  EXPECT_GT(cut, 200);
  EXPECT_GT(inside_hits, 1000);
  EXPECT_GT(whole, 0);  // boxes around or beside the eye
}

// tiles_seeing_boxes: every pixel whose ray, at any sample offset, meets one of the boxes
// lies in a tile marked seen, and the union of the boxes' rectangles holds them all.
TEST(Camera, TilesSeeingBoxesHoldEveryRayThatMeetsOne) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const glm::vec2 offsets[] = {{0.0f, 0.0f}, {0.9999f, 0.9999f}, {0.5f, 0.5f}};
  int unseen_tiles = 0, tiles = 0, hits = 0;
  for (int c = 0; c < 150; ++c) {
    const int W = 60 + c % 29, H = 40 + c % 31;
    Camera cam{{4 * u(rng), 4 * u(rng), 6 + 2 * u(rng)},
               {u(rng), u(rng), u(rng)},
               {0.2f * u(rng), 1.0f, 0.2f * u(rng)},
               c % 3 == 0 ? 90.0f : 40.0f};
    std::vector<Aabb> boxes;
    for (int b = 0; b < 1 + c % 6; ++b) {
      const glm::vec3 centre(3 * u(rng), 3 * u(rng), 3 * u(rng));
      const glm::vec3 half(0.02f + 0.3f * std::fabs(u(rng)), 0.02f + 0.3f * std::fabs(u(rng)),
                           0.02f + 0.3f * std::fabs(u(rng)));
      boxes.push_back(Aabb{centre - half, centre + half});
    }
    const CameraFrame f = camera_frame(cam, W, H);
    const TileMask m = tiles_seeing_boxes(f, boxes);
    ASSERT_EQ(m.tiles, glm::ivec2((W + 7) / 8, (H + 7) / 8));
    for (int32_t v : m.seen) unseen_tiles += v == 0;
    tiles += static_cast<int>(m.seen.size());
    for (int j = 0; j < H; ++j)
      for (int i = 0; i < W; ++i)
        for (const glm::vec2 o : offsets) {
          const glm::vec3 d = camera_ray(f, i, j, o.x, o.y);
          bool meets = false;
          for (const Aabb& b : boxes)
            meets = meets || testing::ray_meets_box(glm::dvec3(f.eye), glm::dvec3(d),
                                                    glm::dvec3(b.lo), glm::dvec3(b.hi));
          if (!meets) continue;
          ++hits;
          ASSERT_EQ(m.seen[static_cast<size_t>((j >> m.shift) * m.tiles.x + (i >> m.shift))], 1)
              << "camera " << c << ": pixel (" << i << ", " << j << ") sees a box";
          ASSERT_TRUE(i >= m.bounds.first.x && i < m.bounds.end.x && j >= m.bounds.first.y &&
                      j < m.bounds.end.y);
        }
  }
  EXPECT_GT(hits, 10000);                  // rays met the boxes
  EXPECT_GT(unseen_tiles, tiles * 3 / 4);  // and most tiles were left out
}

TEST(Camera, TilesSeeingBoxesGrowOnLargeImages) {
  const Camera cam{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  const std::vector<Aabb> box{Aabb{glm::vec3(-0.1f), glm::vec3(0.1f)}};
  const TileMask small = tiles_seeing_boxes(camera_frame(cam, 1920, 1080), box);
  EXPECT_EQ(small.shift, 3);
  const TileMask big = tiles_seeing_boxes(camera_frame(cam, 16384, 16384), box);
  EXPECT_EQ(big.shift, 5);  // 512 x 512 tiles
  EXPECT_LE(big.seen.size(), size_t{1} << 18);
  // No boxes, or only boxes behind the eye: nothing is seen.
  const TileMask none = tiles_seeing_boxes(camera_frame(cam, 64, 48), {});
  EXPECT_TRUE(none.bounds.empty());
  EXPECT_EQ(std::count(none.seen.begin(), none.seen.end(), 1), 0);
  const TileMask behind =
      tiles_seeing_boxes(camera_frame(cam, 64, 48),
                         {Aabb{glm::vec3(-1.0f, -1.0f, 6.0f), glm::vec3(1.0f, 1.0f, 7.0f)}});
  EXPECT_EQ(std::count(behind.seen.begin(), behind.seen.end(), 1), 0);
}

TEST(Camera, PixelsSeeingABoxSpecialCases) {
  const Camera cam{{0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
  const CameraFrame f = camera_frame(cam, 64, 48);
  auto is_whole = [](const PixelRect& r) {
    return r.first == glm::ivec2(0) && r.end == glm::ivec2(64, 48);
  };
  // A small box ahead: a small rectangle around the image's centre.
  const PixelRect ahead = pixels_seeing_box(f, glm::vec3(-0.1f), glm::vec3(0.1f));
  EXPECT_FALSE(ahead.empty());
  EXPECT_LT(ahead.end.x - ahead.first.x, 16);
  EXPECT_LE(ahead.first.x, 31);
  EXPECT_GE(ahead.end.x, 33);
  // Around the eye, beside it, or not finite: the whole image.
  EXPECT_TRUE(
      is_whole(pixels_seeing_box(f, glm::vec3(-1.0f, -1.0f, 4.0f), glm::vec3(1.0f, 1.0f, 6.0f))));
  EXPECT_TRUE(
      is_whole(pixels_seeing_box(f, glm::vec3(3.0f, -1.0f, 4.0f), glm::vec3(4.0f, 1.0f, 6.0f))));
  EXPECT_TRUE(is_whole(pixels_seeing_box(f, glm::vec3(-1.0f), glm::vec3(1.0f, 1.0f, INFINITY))));
  EXPECT_TRUE(is_whole(pixels_seeing_box(f, glm::vec3(NAN), glm::vec3(1.0f))));
  // Behind the eye, or beside the image: no pixel. An empty box (lo > hi): none either.
  EXPECT_TRUE(
      pixels_seeing_box(f, glm::vec3(-1.0f, -1.0f, 7.0f), glm::vec3(1.0f, 1.0f, 8.0f)).empty());
  EXPECT_TRUE(
      pixels_seeing_box(f, glm::vec3(40.0f, -0.1f, -0.1f), glm::vec3(41.0f, 0.1f, 0.1f)).empty());
  EXPECT_TRUE(pixels_seeing_box(f, glm::vec3(1.0f), glm::vec3(0.0f)).empty());
}

TEST_P(Render, CameraRaysBitForBit) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("thesis-a");
  Grid g = build_grid(s, 2);
  Tracer tracer(s, g);
  const Camera cams[] = {
      s.camera,
      Camera{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 0.0f}, 90.0f},
      Camera{{1.5f, 2.25f, 7.0f}, {-0.3f, 0.7f, 0.1f}, {0.1f, 1.0f, 0.05f}, 53.7f},
      Camera{{-3e3f, 10.0f, 1e-3f}, {2.0f, -1.0f, 0.5f}, {0.0f, 0.0f, 1.0f}, 1.0f},
      Camera{{0.1f, 0.2f, 0.3f}, {0.3f, 0.2f, 0.1f}, {1.0f, 1.0f, 1.0f}, 170.0f},
  };
  const glm::ivec2 sizes[] = {{32, 32}, {37, 23}, {5, 64}, {64, 3}, {1, 1}};
  int n = 0;
  for (const Camera& c : cams)
    for (const glm::ivec2& sz : sizes) {
      std::vector<glm::vec3> got = tracer.camera_rays(GetParam(), c, sz.x, sz.y);
      ASSERT_EQ(got.size(), static_cast<size_t>(sz.x * sz.y));
      for (int j = 0; j < sz.y; ++j)
        for (int i = 0; i < sz.x; ++i) {
          glm::vec3 want = design_ray(c, sz.x, sz.y, i, j);
          const glm::vec3& d = got[static_cast<size_t>(j * sz.x + i)];
          ASSERT_TRUE(same_bits(d, want))
              << "camera " << n << " size " << sz.x << "x" << sz.y << " pixel (" << i << ", " << j
              << "): " << d.x << " " << d.y << " " << d.z << " vs " << want.x << " " << want.y
              << " " << want.z;
        }
      ++n;
    }
}

// The brute-force double-precision reference for the camera rays: closest hit over every
// triangle. Pixels whose answer is fragile (the ray passes within 1e-5 of a triangle edge in
// barycentric terms, or two surfaces lie within 1e-5 relative distance) are not compared.
struct Reference {
  std::vector<int32_t> prim;
  std::vector<double> depth;
  std::vector<uint8_t> fragile;
};

Reference reference(const Scene& s, int W, int H) {
  Reference r;
  CameraFrame f = camera_frame(s.camera, W, H);
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < W; ++i) {
      glm::dvec3 o(f.eye), d(camera_ray(f, i, j));
      double best = INFINITY, second = INFINITY;
      int32_t id = -1;
      bool fragile = false;
      for (size_t k = 0; k < s.triangle_count(); ++k) {
        const glm::vec3* p = &s.positions[3 * k];
        if (!triangle_usable(p[0], p[1], p[2])) continue;
        double t, margin;
        if (!testing::hit_triangle_d(o, d, glm::dvec3(p[0]), glm::dvec3(p[1]), glm::dvec3(p[2]), t,
                                     margin))
          continue;
        if (std::fabs(margin) < 1e-5) fragile = true;
        if (margin < 0) continue;
        if (t < best) {
          second = best;
          best = t;
          id = static_cast<int32_t>(k);
        } else if (t < second) {
          second = t;
        }
      }
      if (id >= 0 && second - best < 1e-5 * best) fragile = true;
      r.prim.push_back(id);
      r.depth.push_back(best);
      r.fragile.push_back(fragile);
    }
  return r;
}

// An OBJ with polygons (fanned) and a smooth sphere, loaded from a file.
Scene obj_scene(const testing::TempDir& dir) {
  std::string obj =
      "v -2 0 -2\nv 2 0 -2\nv 2.5 0 0\nv 2 0 2\nv -2 0 2\nv -2.5 0 0\n"  // a hexagon floor
      "v -1 0 -1\nv 1 0 -1\nv 0 1.5 0\nv 1 0 1\nv -1 0 1\n"              // a pyramid
      "o floor\nf 1 2 3 4 5 6\n"
      "o pyramid\nf 7 8 9\nf 8 10 9\nf 10 11 9\nf 11 7 9\nf 7 11 10 8\n";
  dir.file("scene.obj", obj);
  std::string json = dir.file("scene.json", R"({
    "camera": {"eye": [1.5, 2.5, 5], "look_at": [0, 0.5, 0], "fov_y": 40},
    "image": {"width": 32, "height": 24},
    "meshes": [{"file": "scene.obj"},
               {"shape": "sphere", "center": [1.4, 0.6, 0.9], "radius": 0.6, "slices": 12, "stacks": 6,
                "smooth": false}],
    "lights": [{"position": [3, 5, 4]}]
  })");
  return load_json(json);
}

// Renders, and checks the AOVs against the reference.
RenderResult render_checked(const Scene& s, const std::string& backend, int W, int H) {
  Grid g = build_grid(s, s.options.grid);
  Tracer tracer(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = backend;
  rs.width = W;
  rs.height = H;
  RenderResult r = tracer.render(rs, s.camera);
  Reference ref = reference(s, W, H);
  int compared = 0, hits = 0;
  for (size_t p = 0; p < ref.prim.size(); ++p) {
    EXPECT_TRUE(std::isfinite(r.color[p].x) && std::isfinite(r.color[p].y) &&
                std::isfinite(r.color[p].z))
        << "pixel " << p;
    if (ref.fragile[p]) continue;
    ++compared;
    EXPECT_EQ(r.prim[p], ref.prim[p]) << s.name << " pixel " << p % W << ", " << p / W;
    if (ref.prim[p] < 0) {
      EXPECT_TRUE(std::isinf(r.depth[p]) && r.depth[p] > 0) << "pixel " << p;
    } else {
      ++hits;
      EXPECT_NEAR(r.depth[p], ref.depth[p], 2e-5 * ref.depth[p]) << s.name << " pixel " << p;
    }
  }
  EXPECT_GT(compared, static_cast<int>(ref.prim.size() * 8 / 10))
      << s.name << ": too many fragile pixels";
  EXPECT_GT(hits, 0) << s.name;
  return r;
}

TEST_P(Render, AovsMatchReferenceAndImagesMatchCpu) {
  RT_REQUIRE_BACKEND(GetParam());
  testing::TempDir dir;
  std::vector<Scene> scenes = {builtin_scene("thesis-a"), builtin_scene("cornell"),
                               builtin_scene("glass"), builtin_scene("textured"), obj_scene(dir)};
  const int W = 32, H = 24;
  for (Scene& s : scenes) {
    SCOPED_TRACE(s.name);
    RenderResult r = render_checked(s, GetParam(), W, H);
    if (GetParam() != "cpu") {
      Grid g = build_grid(s, s.options.grid);
      Tracer cpu(s, g);
      RenderSettings rs;
      rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
      rs.width = W;
      rs.height = H;
      expect_identical(cpu.render(rs, s.camera), r, s.name + ": cpu vs " + GetParam());
    }
  }
}

// Several samples per pixel, a small max depth and a forced grid size change nothing in how
// the backends agree.
TEST_P(Render, OptionsKeepBackendsIdentical) {
  RT_REQUIRE_BACKEND(GetParam());
  if (GetParam() == "cpu") GTEST_SKIP() << "compares other backends with cpu";
  Scene s = builtin_scene("glass");
  Grid g = build_grid(s, 9);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = 16;
  rs.height = 12;
  rs.spp = 3;
  rs.max_depth = 2;
  RenderResult a = t.render(rs, s.camera);
  rs.backend = GetParam();
  RenderResult b = t.render(rs, s.camera);
  expect_identical(a, b, "glass, spp 3, depth 2, grid 9");
}

// A tracer that rendered other frames (other depth, other samples, a miss-only view) renders
// the same frame as a fresh tracer, bit for bit: whatever a tracer keeps between frames
// (compiled kernels, warm-up state, and any buffers it may reuse) must not show through.
TEST_P(Render, FramesBackToBackEqualFreshFrames) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("glass");
  Grid g = build_grid(s, 9);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = 16;
  rs.height = 12;
  rs.max_depth = 2;
  Tracer fresh(s, g);
  const RenderResult want = fresh.render(rs, s.camera);
  Tracer reused(s, g);
  RenderSettings other = rs;
  other.max_depth = 0;
  other.spp = 2;
  reused.render(other, s.camera);
  Camera away = s.camera;
  away.look_at = away.eye + (away.eye - s.camera.look_at);  // the other way: mostly misses
  reused.render(rs, away);
  expect_identical(want, reused.render(rs, s.camera), "glass after two other frames");
}

// A frame's split (FrameTimes): the kernels' own time is part of the launch step, for both
// strategies; -1 only where the backend cannot time a kernel (Mesa's compute stage).
TEST_P(Render, KernelTimeIsPartOfTheLaunch) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("thesis-b");
  Grid g = build_grid(s, 8);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = 32;
  rs.height = 24;
  rs.spp = 2;
  const std::string d = rill::backend(GetParam()).description();
  const bool untimed = GetParam() == "glsl-compute" && !rill::backend(GetParam()).runs_on_gpu();
  for (Strategy strategy : {Strategy::Megakernel, Strategy::Multipass}) {
    rs.strategy = strategy;
    t.render(rs, s.camera);  // compiles
    const RenderResult r = t.render(rs, s.camera);
    if (untimed) {
      EXPECT_EQ(r.times.kernel, -1.0) << d;
      continue;
    }
    EXPECT_GT(r.times.kernel, 0.0) << d;
    EXPECT_LE(r.times.kernel, r.times.launch) << d;
  }
}

// First-use honesty (RenderResult::cold, first_launch_ms): a tracer's first frame of a
// strategy, backend and size is cold and times its first launches apart from the trace; the
// same frame again is warm with no first launch; another size is cold again, and so is a frame
// of another strategy. Multipass warms nothing up (first_launch_ms stays 0) but is cold too.
TEST_P(Render, FirstFrameIsColdAndItsFirstLaunchIsApart) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = builtin_scene("thesis-b");
  Grid g = build_grid(s, 8);
  Tracer t(s, g);
  RenderSettings rs;
  rs.backend = GetParam();
  rs.width = 16;
  rs.height = 12;
  const RenderResult first = t.render(rs, s.camera);
  EXPECT_TRUE(first.cold);
  EXPECT_GT(first.first_launch_ms, 0.0);
  EXPECT_LE(first.first_launch_ms, first.compile_ms);  // part of the time before the trace
  const RenderResult again = t.render(rs, s.camera);
  EXPECT_FALSE(again.cold);
  EXPECT_EQ(again.first_launch_ms, 0.0);
  expect_identical(first, again, "the warm frame");
  RenderSettings other = rs;
  other.width = 8;
  const RenderResult resized = t.render(other, s.camera);
  EXPECT_TRUE(resized.cold);
  EXPECT_GT(resized.first_launch_ms, 0.0);
  EXPECT_FALSE(t.render(other, s.camera).cold);
  other.strategy = Strategy::Multipass;
  EXPECT_TRUE(t.render(other, s.camera).cold);
  EXPECT_FALSE(t.render(other, s.camera).cold);
}

TEST_P(Render, BadGeometryAndEmptyScenes) {
  RT_REQUIRE_BACKEND(GetParam());
  // NaN, infinite and degenerate triangles are never hit; the rest renders normally.
  Scene s = builtin_scene("cornell");
  const float nan = std::nanf("");
  const size_t good = s.triangle_count();
  s.add_triangle({nan, 0, 0}, {0.3f, 0.3f, 0.3f}, {0.2f, 0.4f, 0.2f}, 0);
  s.add_triangle({0.1f, 0.1f, 0.1f}, {INFINITY, 0.2f, 0.2f}, {0.2f, 0.4f, 0.2f}, 0);
  s.add_triangle({0.1f, 0.1f, 0.1f}, {0.2f, 0.2f, 0.2f}, {0.3f, 0.3f, 0.3f}, 0);
  s.add_triangle({0.28f, 0.27f, 0.0f}, {0.28f, 0.27f, 0.0f}, {0.28f, 0.27f, 0.0f}, 0);
  RenderResult r = render_checked(s, GetParam(), 24, 24);
  for (int32_t p : r.prim) EXPECT_LT(p, static_cast<int32_t>(good));

  // An empty scene (and one with only degenerate triangles): background, misses.
  for (int k = 0; k < 2; ++k) {
    Scene e = builtin_scene("empty");
    e.background = glm::vec3(0.25f, 0.5f, 0.75f);
    if (k == 1) {
      e.add_material(Material{});
      e.add_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0);
      e.lights.push_back(Light{});
    }
    Grid g = build_grid(e, 0);
    Tracer t(e, g);
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.backend = GetParam();
    rs.width = 8;
    rs.height = 4;
    RenderResult er = t.render(rs, e.camera);
    for (size_t p = 0; p < er.color.size(); ++p) {
      EXPECT_EQ(er.color[p], e.background);
      EXPECT_EQ(er.prim[p], -1);
      EXPECT_TRUE(std::isinf(er.depth[p]));
    }
  }
}

// The thesis's multipass strategy, built from the same DSL functions, gives the same bits
// as the single kernel: colour, AOVs and ray counts.
TEST_P(Render, MultipassMatchesMegakernel) {
  RT_REQUIRE_BACKEND(GetParam());
  // thesis-a twice: on its automatic grid, and with a subgrid in every voxel listing more
  // than 2 triangles (multipass walks a subgrid within one intersector pass).
  for (const char* name : {"thesis-a", "thesis-a+subgrids", "thesis-b", "cornell", "textured"}) {
    const bool subgrids = std::string(name) == "thesis-a+subgrids";
    Scene s = builtin_scene(subgrids ? "thesis-a" : name);
    if (std::string(name) == "thesis-b") s.lights.resize(1);  // fewer passes
    Grid g = build_grid(s, 0, subgrids ? 2 : kSubgridMin);
    if (subgrids) {
      EXPECT_GT(g.subgrids, 0);
    }
    Tracer t(s, g);
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.backend = GetParam();
    rs.width = 20;
    rs.height = 14;
    rs.max_depth = 2;
    RenderResult a = t.render(rs, s.camera);
    rs.strategy = Strategy::Multipass;
    RenderResult b = t.render(rs, s.camera);
    EXPECT_GT(b.launches, 5) << name;
    expect_identical(a, b, std::string(name) + ": megakernel vs multipass on " + GetParam());
  }
  // Glass needs the single kernel's ray stack: a clear error.
  Scene glass = builtin_scene("glass");
  Grid g = build_grid(glass, 0);
  Tracer t(glass, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = rs.height = 4;
  rs.strategy = Strategy::Multipass;
  EXPECT_THROW(t.render(rs, glass.camera), std::runtime_error);
}

// A floor 2000 wide seen from 0.1 above its edge through a 5-degree lens: the triangle test's
// rounding, in ulps of the vertices' distance from the eye, is largest here, and a pixel is
// 4e-5 radians. Every row next to the edge's projection must be as multipass (which traces
// every pixel) has it. (A reviewer's float32 model of the test put hits 4e-5 beyond the edge,
// several pixels here; this kernel's test did not show it, with or without hit_margin.)
TEST_P(Render, SkippedPixelsKeepHitsJustBeyondAnEdge) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s;
  const int mat = s.add_material(Material{});
  s.add_triangle({-1000.0f, 0.0f, -1000.0f}, {1000.0f, 0.0f, 0.0f}, {-1000.0f, 0.0f, 0.0f}, mat);
  s.camera = Camera{{0.3f, 0.1f, 0.05f}, {0.3f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, 5.0f};
  s.has_camera = true;
  const Grid g = build_grid(s, 0);
  Tracer t(s, g);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = 2000;
  rs.height = 2000;
  rs.window = {968, 0, 64, 2000};  // the middle columns, every row
  rs.outputs = {false, false, false, true, false};
  const RenderResult mega = t.render(rs, s.camera);
  rs.strategy = Strategy::Multipass;
  const RenderResult multi = t.render(rs, s.camera);
  ASSERT_EQ(mega.prim.size(), multi.prim.size());
  size_t hits = 0, differ = 0;
  for (size_t i = 0; i < mega.prim.size(); ++i) {
    hits += multi.prim[i] >= 0;
    differ += mega.prim[i] != multi.prim[i];
  }
  EXPECT_GT(hits, 1000u);
  EXPECT_LT(hits, mega.prim.size());  // the edge is in view
  EXPECT_EQ(differ, 0u) << "of " << hits << " hits";
}

// The megakernel skips the camera rays of pixels outside the scene's box on screen, and a
// render reads back only the outputs asked for: none of it changes a bit. Multipass, which
// traces every pixel, is the reference, at sizes and sample counts where the box covers part
// of the image.
TEST_P(Render, SkippedPixelsAndAovsChangeNothing) {
  RT_REQUIRE_BACKEND(GetParam());
  for (const char* name : {"thesis-a", "cornell"}) {
    Scene s = builtin_scene(name);
    if (std::string(name) == "cornell") s.camera.eye.z += 6.0f;  // the room small in the image
    Grid g = build_grid(s, 0);
    Tracer t(s, g);
    RenderSettings rs;
    rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
    rs.backend = GetParam();
    rs.width = 40;
    rs.height = 26;
    rs.max_depth = 2;
    rs.spp = 2;
    rs.outputs = {true, true, true, true, true};
    const PixelRect seen =
        pixels_seeing_box(camera_frame(s.camera, rs.width, rs.height), g.lo, g.hi);
    const int64_t inside = int64_t{seen.end.x - seen.first.x} * (seen.end.y - seen.first.y);
    EXPECT_GT(inside, 0) << name;
    EXPECT_LT(inside, int64_t{rs.width} * rs.height * 3 / 4) << name << ": nothing skipped";
    const RenderResult mega = t.render(rs, s.camera);
    rs.strategy = Strategy::Multipass;
    const RenderResult multi = t.render(rs, s.camera);
    expect_identical(mega, multi, std::string(name) + ": megakernel vs multipass on " + GetParam());
    EXPECT_EQ(mega.rgb8, multi.rgb8) << name;
    // Without AOVs: the same colour, image and ray count, and no AOV read back.
    rs.strategy = Strategy::Megakernel;
    rs.outputs = {true, true, false, false, false};
    const RenderResult plain = t.render(rs, s.camera);
    EXPECT_TRUE(plain.depth.empty() && plain.prim.empty() && plain.normal.empty()) << name;
    ASSERT_EQ(plain.color.size(), mega.color.size());
    EXPECT_EQ(
        std::memcmp(plain.color.data(), mega.color.data(), plain.color.size() * sizeof(glm::vec3)),
        0)
        << name;
    EXPECT_EQ(plain.rgb8, mega.rgb8) << name;
    EXPECT_EQ(plain.rays, mega.rays) << name;
    // Only the 8-bit image, of two samples and of one.
    rs.outputs = {false, true, false, false, false};
    const RenderResult encoded2 = t.render(rs, s.camera);
    EXPECT_TRUE(encoded2.color.empty()) << name;
    EXPECT_EQ(encoded2.rgb8, mega.rgb8) << name;
    EXPECT_EQ(encoded2.rays, mega.rays) << name;
    rs.spp = 1;
    const RenderResult encoded1 = t.render(rs, s.camera);
    rs.outputs = {true, true, false, false, false};
    const RenderResult film1 = t.render(rs, s.camera);
    EXPECT_FALSE(encoded1.rgb8.empty()) << name;
    EXPECT_EQ(encoded1.rgb8, film1.rgb8) << name;
    EXPECT_EQ(encoded1.rays, film1.rays) << name;
    // A window of the image, only its 8-bit image read back: the whole image's pixels.
    rs.outputs = {false, true, false, false, false};
    rs.window = {3, 5, 29, 17};
    const RenderResult part = t.render(rs, s.camera);
    ASSERT_EQ(part.rgb8.size(), size_t{29 * 17 * 3}) << name;
    for (int y = 0; y < 17; ++y)
      ASSERT_EQ(std::memcmp(&part.rgb8[size_t(y) * 29 * 3],
                            &film1.rgb8[(size_t(y + 5) * 40 + 3) * 3], 29 * 3),
                0)
          << name << ", window row " << y;
  }
}

// What a render reads back and how many samples it takes are launch-time choices: renders
// that differ only in them run one compiled kernel. After a first render, the others compile
// nothing at all (no miss of the in-process kernel cache: the megakernel, the film's kernels
// and the ray count's reduction are all there), and each image is bitwise the one of a fresh
// tracer that renders it first.
TEST_P(Render, OutputsAndSamplesShareOneKernel) {
  RT_REQUIRE_BACKEND(GetParam());
  for (const char* name :
       {"glass", "cornell-path"}) {  // Whitted with refraction; the path integrator
    const Scene s = builtin_scene(name);
    const Grid g = build_grid(s, 0);
    RenderSettings rs;
    rs.backend = GetParam();
    rs.width = 24;
    rs.height = 16;
    rs.max_depth = 3;
    // The film's kernels (sum, mean, 8-bit encoder) exist once any render has used them; a
    // first tracer of the scene at 2 samples with every output makes them all.
    {
      Tracer first(s, g);
      rs.spp = 2;
      rs.outputs = {true, true, true, true, true, true};
      (void)first.render(rs, s.camera);
      rs.spp = 1;
      (void)first.render(rs, s.camera);
    }
    struct Variant {
      FrameOutputs outputs;
      int spp;
    };
    const std::vector<Variant> variants = {
        {FrameOutputs{}, 1},                                     // the library's default
        {FrameOutputs{false, true, false, false, false}, 1},     // rill-trace --out
        {FrameOutputs{false, true, true, false, false}, 1},      // --out --depth
        {FrameOutputs{false, true, false, false, false}, 2},     // --out --spp 2
        {FrameOutputs{true, false, true, true, true, true}, 3},  // --pfm and every AOV
    };
    Tracer t(s, g);
    std::vector<std::string> sources;
    for (size_t i = 0; i < variants.size(); ++i) {
      rs.outputs = variants[i].outputs;
      rs.spp = variants[i].spp;
      const rill::CacheStats before = rill::kernel_cache_stats();
      const RenderResult r = t.render(rs, s.camera);
      const rill::CacheStats after = rill::kernel_cache_stats();
      if (i > 0) {
        EXPECT_EQ(after.misses, before.misses)
            << name << ", variant " << i << ": compiled a kernel on " << GetParam();
      }
      sources.push_back(
          t.source(GetParam(), rill::Accuracy::Strict, MegakernelLoop::Auto, rs.outputs, rs.spp));
      // The same image as a tracer whose first render this is.
      Tracer fresh(s, g);
      const RenderResult want = fresh.render(rs, s.camera);
      EXPECT_EQ(r.rgb8, want.rgb8) << name << ", variant " << i;
      ASSERT_EQ(r.color.size(), want.color.size()) << name << ", variant " << i;
      // Bit for bit (memcmp; an empty vector's null data is not memcmp's to read, even for 0).
      EXPECT_TRUE(r.color.empty() || std::memcmp(r.color.data(), want.color.data(),
                                                 r.color.size() * sizeof(glm::vec3)) == 0)
          << name << ", variant " << i;
      EXPECT_EQ(r.depth.size(), want.depth.size()) << name << ", variant " << i;
      EXPECT_TRUE(r.depth.empty() || std::memcmp(r.depth.data(), want.depth.data(),
                                                 r.depth.size() * sizeof(float)) == 0)
          << name << ", variant " << i;
      EXPECT_EQ(r.prim, want.prim) << name << ", variant " << i;
      EXPECT_EQ(r.rays, want.rays) << name << ", variant " << i;
      EXPECT_EQ(r.spp, rs.spp) << name << ", variant " << i;
      // Each output is there exactly when asked for.
      EXPECT_EQ(r.rgb8.empty(), !rs.outputs.rgb8) << name << ", variant " << i;
      EXPECT_EQ(r.color.empty(), !rs.outputs.color) << name << ", variant " << i;
      EXPECT_EQ(r.depth.empty(), !rs.outputs.depth) << name << ", variant " << i;
    }
    for (size_t i = 1; i < sources.size(); ++i)
      EXPECT_EQ(sources[i], sources[0]) << name << ", variant " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, Render, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
