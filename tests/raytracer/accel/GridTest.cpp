// The uniform grid: the exact triangle-box test, the voxel lists, the resolution heuristic,
// and (per backend) the kernel's 3D-DDA traversal against brute force on random rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"

namespace rt {
namespace {

glm::dvec3 rnd3(std::mt19937& r, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  return glm::dvec3(u(r), u(r), u(r));
}

TEST(Grid, TriangleBoxOverlapCases) {
  const glm::dvec3 c(0.0), h(1.0);
  auto tri = [](glm::dvec3 a, glm::dvec3 b, glm::dvec3 d) {
    return std::array<glm::dvec3, 3>{a, b, d};
  };
  auto overlap = [&](const std::array<glm::dvec3, 3>& t) {
    return triangle_box_overlap(c, h, t.data());
  };
  EXPECT_TRUE(overlap(tri({-0.5, -0.5, 0}, {0.5, -0.5, 0}, {0, 0.5, 0})));  // inside
  EXPECT_TRUE(overlap(tri({-5, -5, 0}, {5, -5, 0}, {0, 5, 0})));  // box inside the triangle
  EXPECT_TRUE(overlap(tri({1, -5, -5}, {1, 5, -5}, {1, 0, 5})));  // touching a face
  EXPECT_FALSE(overlap(tri({1.01, -5, -5}, {1.01, 5, -5}, {1.01, 0, 5})));  // just off a face
  EXPECT_FALSE(overlap(tri({2, 2, 2}, {3, 2, 2}, {2, 3, 2})));              // bounding boxes apart
  // Bounding boxes overlap, the plane misses the box: separated by the normal.
  EXPECT_FALSE(overlap(tri({3.1, 0, 0}, {0, 3.1, 0}, {0, 0, 3.1})));
  EXPECT_TRUE(overlap(tri({3, 0, 0}, {0, 3, 0}, {0, 0, 3})));  // touching the corner
  EXPECT_TRUE(overlap(tri({2.9, 0, 0}, {0, 2.9, 0}, {0, 0, 2.9})));
  // Separated only by an edge x axis product: a thin sliver passing a box edge.
  EXPECT_FALSE(overlap(tri({2.5, 0, -3}, {0, 2.5, -3}, {1.25, 1.25, 3})));
  EXPECT_TRUE(overlap(tri({1.9, 0, -3}, {0, 1.9, -3}, {0.95, 0.95, 3})));
}

// Against sampling: if a sampled point of the triangle lies in the box, the test must say
// overlap; if the test says no overlap, no sample may lie in the box.
TEST(Grid, TriangleBoxOverlapAgreesWithSampling) {
  std::mt19937 r(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int overlaps = 0;
  for (int k = 0; k < 3000; ++k) {
    glm::dvec3 t[3] = {rnd3(r, -2, 2), rnd3(r, -2, 2), rnd3(r, -2, 2)};
    glm::dvec3 c = rnd3(r, -1, 1), h = rnd3(r, 0.05, 1.0);
    bool ov = triangle_box_overlap(c, h, t);
    overlaps += ov;
    for (int s = 0; s < 200 && !ov; ++s) {
      double a = u(r), b = u(r);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      glm::dvec3 p = t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]);
      glm::dvec3 q = glm::abs(p - c);
      ASSERT_FALSE(q.x <= h.x && q.y <= h.y && q.z <= h.z) << "case " << k;
    }
  }
  EXPECT_GT(overlaps, 300);
}

// The (start, count) list of the leaf voxel holding point p: the top-level voxel, or the
// sub-voxel of its subgrid, located as the kernel locates them (float corner and sub-voxel
// size).
glm::ivec2 leaf_at(const Grid& g, const glm::dvec3& p, bool* in_subgrid = nullptr) {
  const glm::ivec3 v =
      glm::clamp(glm::ivec3(glm::floor((p - glm::dvec3(g.lo)) / glm::dvec3(g.cell))), glm::ivec3(0),
                 g.res - 1);
  const glm::ivec2 e = g.voxels[static_cast<size_t>(v.x + g.res.x * (v.y + g.res.y * v.z))];
  if (in_subgrid) *in_subgrid = e.y < 0;
  if (e.y >= 0) return e;
  const int m = -e.y;
  glm::ivec3 sv;
  for (int a = 0; a < 3; ++a) {
    const double corner = static_cast<double>(g.lo[a] + static_cast<float>(v[a]) * g.cell[a]);
    const double sub = static_cast<double>(g.cell[a] / static_cast<float>(m));
    sv[a] = std::clamp(static_cast<int>(std::floor((p[a] - corner) / sub)), 0, m - 1);
  }
  return g.voxels[static_cast<size_t>(e.x + sv.x + m * (sv.y + m * sv.z))];
}

TEST(Grid, EveryTriangleIsInTheVoxelsItTouches) {
  for (const char* name : {"thesis-b", "thesis-c"}) {
    Scene s = builtin_scene(name);
    for (int res : {0, 1, 7, 32}) {
      SCOPED_TRACE(std::string(name) + " " + std::to_string(res));
      Grid g = build_grid(s, res, kSubgridMin);
      ASSERT_GE(static_cast<int64_t>(g.voxels.size()), g.voxel_count());
      int64_t sub_entries = 0;
      for (size_t i = 0; i < g.voxels.size(); ++i) {
        const glm::ivec2 v = g.voxels[i];
        const bool top = i < static_cast<size_t>(g.voxel_count());
        if (v.y < 0) {  // a subgrid: its m^3 entries lie after the top level
          ASSERT_TRUE(top);
          ASSERT_GE(-v.y, 2);
          ASSERT_LE(-v.y, kSubgridMaxRes);
          ASSERT_GE(v.x, g.voxel_count());
          ASSERT_LE(static_cast<size_t>(v.x) + static_cast<size_t>(-v.y * v.y * v.y),
                    g.voxels.size());
          sub_entries -= int64_t{v.y} * v.y * v.y;
          continue;
        }
        if (v.y == 0 && top) continue;  // an empty voxel's x is its distance (EmptyDistances)
        ASSERT_GE(v.x, 0);
        ASSERT_LE(static_cast<size_t>(v.x + v.y), g.elements.size());
        ASSERT_TRUE(std::is_sorted(g.elements.begin() + v.x, g.elements.begin() + v.x + v.y));
      }
      EXPECT_EQ(g.voxel_count() + sub_entries, static_cast<int64_t>(g.voxels.size()));
      std::mt19937 r(1);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      int in_subgrids = 0;
      for (size_t t = 0; t < s.triangle_count(); t += 7) {
        // The teapot's poles have zero-area triangles: never traced, in no list.
        if (!triangle_usable(s.positions[3 * t], s.positions[3 * t + 1], s.positions[3 * t + 2]))
          continue;
        for (int k = 0; k < 10; ++k) {
          double a = u(r), b = u(r);
          if (a + b > 1) a = 1 - a, b = 1 - b;
          glm::dvec3 p0(s.positions[3 * t]), p1(s.positions[3 * t + 1]), p2(s.positions[3 * t + 2]);
          glm::dvec3 p = p0 + a * (p1 - p0) + b * (p2 - p0);
          bool sub = false;
          const glm::ivec2 range = leaf_at(g, p, &sub);
          in_subgrids += sub;
          ASSERT_TRUE(std::binary_search(g.elements.begin() + range.x,
                                         g.elements.begin() + range.x + range.y,
                                         static_cast<int32_t>(t)))
              << "triangle " << t;
        }
      }
      // Coarse grids crowd triangles into subgrids; thesis C's auto grid has them too.
      if (res == 1 || res == 7 || std::string(name) == "thesis-c") {
        EXPECT_GT(g.subgrids, 0);
        EXPECT_GT(in_subgrids, 0);
      }
    }
  }
}

// The chessboard distance stored in every empty voxel equals a brute-force minimum over the
// non-empty voxels, which is what makes the traversal's jumps safe.
TEST(Grid, EmptyDistances) {
  for (const char* name : {"thesis-a", "thesis-b", "cornell"}) {
    for (int res : {0, 5, 24}) {
      SCOPED_TRACE(std::string(name) + " " + std::to_string(res));
      Grid g = build_grid(builtin_scene(name), res, kSubgridMin);  // subgrids: not empty
      std::vector<glm::ivec3> full;
      for (int z = 0; z < g.res.z; ++z)
        for (int y = 0; y < g.res.y; ++y)
          for (int x = 0; x < g.res.x; ++x)
            if (g.voxels[static_cast<size_t>(x + g.res.x * (y + g.res.y * z))].y != 0)
              full.emplace_back(x, y, z);
      ASSERT_FALSE(full.empty());
      int checked = 0, far = 0;
      for (int z = 0; z < g.res.z; ++z)
        for (int y = 0; y < g.res.y; ++y)
          for (int x = 0; x < g.res.x; ++x) {
            const glm::ivec2 e = g.voxels[static_cast<size_t>(x + g.res.x * (y + g.res.y * z))];
            if (e.y != 0) continue;  // triangles, or a subgrid
            int best = kMaxSkip;
            for (const glm::ivec3& f : full)
              best = std::min(best,
                              std::max({std::abs(f.x - x), std::abs(f.y - y), std::abs(f.z - z)}));
            ASSERT_EQ(e.x, best) << "voxel " << x << " " << y << " " << z;
            ++checked;
            far += best >= 3;
          }
      if (res == 24) {
        EXPECT_GT(checked, 0);
        EXPECT_GT(far, 0);  // some voxels are far enough to jump from
      }
    }
  }
  // No triangles at all: one voxel, nothing to skip to.
  Scene empty;
  Grid g = build_grid(empty, 0);
  ASSERT_EQ(g.voxels.size(), 1u);
  EXPECT_EQ(g.voxels[0], glm::ivec2(0));
}

// Triangles that all span the same voxels (a pile of overlapping coplanar ones, a fuzz
// finding: 17 triangles made 189142 references) get no subgrids: a subgrid whose sub-voxels
// would list as many triangles as the voxel does not pay, and the subgrids' references stay
// within a fixed multiple of the top level's.
TEST(Grid, SubgridsThatDoNotPayAreNotBuilt) {
  Scene s;
  s.add_material(Material{});
  for (int i = 0; i < 40; ++i) {
    const float d = 0.001f * static_cast<float>(i);
    s.add_triangle(glm::vec3(-10 + d, -10, 0), glm::vec3(10, -10 + d, 0), glm::vec3(0, 10, 0), 0);
  }
  const Grid without = build_grid(s, 0, kNoSubgrids);
  const Grid with = build_grid(s, 0, 12);
  int64_t dense = 0;  // voxels over the threshold: the subgrids the old rule built
  for (const glm::ivec2& v : without.voxels) dense += v.y > 12;
  EXPECT_LT(with.subgrids, dense / 2) << "of " << dense;
  EXPECT_LE(with.elements.size(), 8 * without.elements.size());
  // Where sub-voxels do separate the triangles, subgrids are still built.
  Scene spread;
  spread.add_material(Material{});
  for (int i = 0; i < 40; ++i) {
    const float x = 0.02f * static_cast<float>(i);
    spread.add_triangle(glm::vec3(x, 0, 0), glm::vec3(x + 0.01f, 0, 0), glm::vec3(x, 0.01f, 0.01f),
                        0);
  }
  spread.add_triangle(glm::vec3(-10, -10, -10), glm::vec3(10, -10, -10), glm::vec3(0, 10, 10), 0);
  EXPECT_GT(build_grid(spread, 1, 12).subgrids, 0);
}

// A pile of large triangles that all span the scene: the auto grid is made coarser until the
// build's triangle-voxel tests stay bounded, and the voxels get no subgrids (each would list
// every triangle in most sub-voxels). Before, 8000 such triangles took 15 s to build.
TEST(Grid, APileOfLargeTrianglesKeepsTheBuildBounded) {
  Scene s;
  s.add_material(Material{});
  const glm::vec3 v[4] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (int i = 0; i < 4000; ++i)
    s.add_triangle(v[faces[i % 4][0]], v[faces[i % 4][1]], v[faces[i % 4][2]], 0);
  const Grid g = build_grid(s, 0, 12);
  const glm::ivec3 dense = auto_grid_resolution(glm::dvec3(1.0), 4000);
  EXPECT_LT(g.res.x, dense.x);
  // A triangle's box covers a layer of the grid (the three faces along the axes) or all of
  // it (the slanted one): the voxels times the triangles stay within twice the bound of 2^24
  // tests, where auto's resolution for 4000 triangles would make that over 3x the bound.
  EXPECT_LE(double(g.voxel_count()) * 4000, 2.0 * double(1 << 24));
  EXPECT_GT(double(dense.x) * dense.y * dense.z * 4000, 3.0 * double(1 << 24));
  EXPECT_EQ(g.subgrids, 0);
  // Every triangle is still listed wherever it lies: a ray through the middle of a face
  // finds the pile there.
  EXPECT_EQ(g.usable, 4000u);
  // Ordinary meshes keep the grid auto picks (thesis C's, as rill-trace reports it).
  EXPECT_EQ(build_grid(builtin_scene("thesis-c"), 0, 12).res, glm::ivec3(123, 16, 123));
}

TEST(Grid, ResolutionHeuristic) {
  // About kGridDensity voxels per triangle, in cubes.
  glm::ivec3 r = auto_grid_resolution(glm::dvec3(10.0), 2000);
  EXPECT_EQ(r, glm::ivec3(20));
  r = auto_grid_resolution(glm::dvec3(20.0, 10.0, 5.0), 2000);
  EXPECT_EQ(r.x, 2 * r.y);
  EXPECT_EQ(r.y, 2 * r.z);
  EXPECT_EQ(auto_grid_resolution(glm::dvec3(1.0), 1), glm::ivec3(2));
  EXPECT_EQ(auto_grid_resolution(glm::dvec3(1.0), 0), glm::ivec3(1));
  // Flat scenes and huge counts stay within the limits.
  r = auto_grid_resolution(glm::dvec3(10.0, 0.0, 10.0), 1000);
  EXPECT_GE(r.y, 1);
  r = auto_grid_resolution(glm::dvec3(1.0), 100000000);
  EXPECT_LE(int64_t{r.x} * r.y * r.z, int64_t{1} << 22);
  EXPECT_EQ(build_grid(builtin_scene("thesis-a"), 9).res, glm::ivec3(9));
}

// Subgrids left to the renderer (kSubgridsAuto) are on for a backend that runs on the CPU and
// off for one on a GPU; a value the user gave is kept as it is.
TEST(Grid, SubgridsLeftOpenFollowTheBackendsDevice) {
  EXPECT_EQ(subgrid_min_for(kSubgridsAuto, "cpu"), kSubgridMin);
  EXPECT_EQ(subgrid_min_for(kSubgridsAuto, "simd"), kSubgridMin);
  for (rill::Backend* b : rill::backends()) {
    EXPECT_EQ(subgrid_min_for(kSubgridsAuto, b->name()),
              b->runs_on_gpu() ? kNoSubgrids : kSubgridMin)
        << b->description();
    EXPECT_EQ(subgrid_min_for(kNoSubgrids, b->name()), kNoSubgrids);
    EXPECT_EQ(subgrid_min_for(30, b->name()), 30);
  }
  EXPECT_EQ(parse_subgrid_min("auto"), kSubgridsAuto);
  EXPECT_EQ(parse_subgrid_min("off"), kNoSubgrids);
  EXPECT_EQ(parse_subgrid_min("7"), 7);
  // The default grid of a clustered scene on the CPU has subgrids; with them off, none.
  Scene s = builtin_scene("thesis-c");
  EXPECT_GT(build_grid_for(s, "cpu").subgrids, 0);
  s.options.subgrid_min = kNoSubgrids;
  EXPECT_EQ(build_grid_for(s, "cpu").subgrids, 0);
}

// A density left to the renderer (kGridDensityAuto, the default) follows the rule in Grid.h:
// kGridDensitySimdLarge for simd and a scene of kGridDensityLargeScene triangles or more,
// kGridDensity otherwise; a density the user gave is kept on every backend.
TEST(Grid, DensityLeftOpenFollowsTheBackendAndTheScene) {
  EXPECT_EQ(SceneOptions{}.grid_density, kGridDensityAuto);
  const size_t large = kGridDensityLargeScene, small = kGridDensityLargeScene - 1;
  EXPECT_EQ(grid_density_for(kGridDensityAuto, "simd", large), kGridDensitySimdLarge);
  EXPECT_EQ(grid_density_for(kGridDensityAuto, "simd", small), kGridDensity);
  EXPECT_EQ(grid_density_for(kGridDensityAuto, "simd", 36), kGridDensity);
  EXPECT_EQ(grid_density_for(kGridDensityAuto, "cpu", large), kGridDensity);
  for (rill::Backend* b : rill::backends()) {
    const bool simd = b->name() == std::string("simd");
    EXPECT_EQ(grid_density_for(kGridDensityAuto, b->name(), large),
              simd ? kGridDensitySimdLarge : kGridDensity)
        << b->description();
    EXPECT_EQ(grid_density_for(kGridDensityAuto, b->name(), small), kGridDensity)
        << b->description();
    EXPECT_EQ(grid_density_for(2.5, b->name(), large), 2.5) << b->description();
    EXPECT_EQ(grid_density_for(4.0, b->name(), large), 4.0) << b->description();
  }
  // The grids build_grid_for gives: thesis C (61,562 triangles) at simd's large-scene density
  // and cpu's kGridDensity, thesis A (36) at kGridDensity, as when asked for by number.
  Scene c = builtin_scene("thesis-c");
  ASSERT_GE(c.triangle_count(), kGridDensityLargeScene);
  Scene c16 = c, c4 = c;
  c16.options.grid_density = kGridDensitySimdLarge;
  c4.options.grid_density = kGridDensity;
  EXPECT_EQ(build_grid_for(c, "simd").res, build_grid_for(c16, "simd").res);
  EXPECT_EQ(build_grid_for(c, "cpu").res, build_grid_for(c4, "cpu").res);
  EXPECT_NE(build_grid_for(c, "simd").res, build_grid_for(c, "cpu").res);
  // Under the path integrator simd keeps kGridDensity, on thesis C as on any scene; a density
  // asked for by number is kept.
  EXPECT_EQ(grid_density_for(kGridDensityAuto, "simd", large, Integrator::Path), kGridDensity);
  EXPECT_EQ(grid_density_for(16.0, "simd", large, Integrator::Path), 16.0);
  Scene cp = c;
  cp.options.integrator = Integrator::Path;
  EXPECT_EQ(build_grid_for(cp, "simd").res, build_grid_for(c4, "simd").res);
  Scene a = builtin_scene("thesis-a");
  ASSERT_LT(a.triangle_count(), kGridDensityLargeScene);
  Scene a4 = a;
  a4.options.grid_density = kGridDensity;
  EXPECT_EQ(build_grid_for(a, "simd").res, build_grid_for(a4, "simd").res);
  // With no backend to choose for, build_grid takes kGridDensity.
  EXPECT_EQ(build_grid(c, 0, kNoSubgrids, kGridDensityAuto).res,
            build_grid(c, 0, kNoSubgrids, kGridDensity).res);
  EXPECT_NE(build_grid(c, 0, kNoSubgrids, kGridDensitySimdLarge).res,
            build_grid(c, 0, kNoSubgrids, kGridDensity).res);
}

// The rule gives simd a denser grid than cpu for thesis C; the images stay bitwise the same
// (the grid only decides which triangles a ray tests, never which hit it keeps), so the
// backend tests' comparisons between backends hold with each backend's own grid.
TEST(Grid, DensityLeftOpenKeepsTheImageOnEachBackend) {
  Scene c = builtin_scene("thesis-c");
  c.width = 64;
  c.height = 48;
  const Grid cpu_grid = build_grid_for(c, "cpu"), simd_grid = build_grid_for(c, "simd");
  ASSERT_NE(cpu_grid.res, simd_grid.res);
  const RenderResult a = Tracer(c, cpu_grid).render(testing::compared_settings(c, "cpu"), c.camera);
  const RenderResult b =
      Tracer(c, simd_grid).render(testing::compared_settings(c, "simd"), c.camera);
  testing::expect_identical(a, b, "thesis C, cpu at its grid against simd at its grid");
}

TEST(Grid, DensitySetsVoxelsPerTriangle) {
  // The automatic resolution gives about `density` voxels per triangle, in cubic cells.
  for (double density : {0.125, 1.0, 4.0, 16.0, 64.0}) {
    const glm::ivec3 r = auto_grid_resolution(glm::dvec3(30.0, 20.0, 10.0), 50000, density);
    const double per_tri = static_cast<double>(int64_t{r.x} * r.y * r.z) / 50000.0;
    EXPECT_GT(per_tri, density * 0.8) << density;
    EXPECT_LT(per_tri, density * 1.25) << density;
    EXPECT_NEAR(static_cast<double>(r.x) / r.z, 3.0, 0.1) << density;
  }
  EXPECT_EQ(auto_grid_resolution(glm::dvec3(1.0), 1000, kGridDensity),
            auto_grid_resolution(glm::dvec3(1.0), 1000));
  // The scene's options choose the grid; a denser one lists fewer triangles per voxel.
  Scene s = builtin_scene("thesis-c");
  s.options.grid_density = 4.0;
  const Grid g4 = build_grid_for(s);
  s.options.grid_density = 32.0;
  const Grid g32 = build_grid_for(s);
  EXPECT_GT(g32.voxel_count(), 6 * g4.voxel_count());
  EXPECT_EQ(g32.voxel_count(), build_grid(s, 0, kNoSubgrids, 32.0).voxel_count());
  // Out of range or not a number: a SceneError that names the option.
  for (const char* bad : {"0", "-4", "0.1", "300", "nan", "inf", "4x", ""})
    EXPECT_THROW(
        {
          try {
            parse_grid_density(bad);
          } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find("--grid-density"), std::string::npos) << bad;
            throw;
          }
        },
        SceneError)
        << bad;
  EXPECT_EQ(parse_grid_density("16"), 16.0);
  EXPECT_EQ(parse_grid_density("0.125"), 0.125);
  EXPECT_EQ(parse_grid_density("auto"), kGridDensityAuto);
  EXPECT_THROW(parse_grid_density("AUTO"), SceneError);
  EXPECT_THROW(auto_grid_resolution(glm::dvec3(1.0), 10, 0.0), SceneError);
}

// ---- the kernel's traversal against brute force --------------------------------------------

class GridTraversal : public ::testing::TestWithParam<std::string> {};

TEST_P(GridTraversal, FindsTheSameClosestHitAsBruteForce) {
  RT_REQUIRE_BACKEND(GetParam());
  for (const char* name : {"thesis-b", "glass"}) {
    Scene s = builtin_scene(name);
    glm::vec3 lo, hi;
    ASSERT_TRUE(scene_bounds(s, lo, hi));
    std::mt19937 r(99);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<glm::vec3> o, d;
    const glm::vec3 ext = hi - lo;
    for (int k = 0; k < 1500; ++k) {
      // Origins inside and around the box; some directions along axes and diagonals.
      glm::vec3 p = lo - 0.2f * ext + glm::vec3(u(r), u(r), u(r)) * 1.4f * ext;
      glm::vec3 q = lo + glm::vec3(u(r), u(r), u(r)) * ext;
      glm::vec3 dir = q - p;
      if (k % 10 == 1) dir = glm::vec3(0.0f, 0.0f, (k & 2) ? 1.0f : -1.0f);
      if (k % 10 == 2) dir = glm::vec3((k & 4) ? 1.0f : -1.0f, 0.0f, 0.0f);
      if (k % 10 == 3) dir = glm::vec3(0.0f, -1.0f, 0.0f);
      if (k % 10 == 4) dir = glm::vec3(1.0f, 1.0f, 0.0f);
      float l = std::sqrt(testing::dotf(dir, dir));
      if (!(l > 0)) continue;
      o.push_back(p);
      d.push_back(dir / l);
    }
    // (resolution, subgrid threshold): the automatic grid; one voxel for all (whose subgrid
    // then holds everything: 8^3 sub-voxels); a fine grid with and without subgrids in its
    // voxels of more than 2 triangles; one level only.
    // The last two: a fine grid, where the room's air is many voxels from any triangle (long
    // jumps), with both traversals (the recomputing one's jumps move the voxel only).
    struct Config {
      int res;
      int32_t subgrid_min;
      Traversal traversal = Traversal::Incremental;
    };
    std::vector<Config> configs = {{0, kSubgridMin},
                                   {1, kSubgridMin},
                                   {13, kSubgridMin},
                                   {13, 2},
                                   {0, kNoSubgrids},
                                   {64, kNoSubgrids},
                                   {64, kNoSubgrids, Traversal::Recompute}};
    // (Not glass in one voxel: no subgrid would make its 6986 triangles per ray slow on
    // llvmpipe.)
    if (std::string(name) == "glass") configs = {{0, kSubgridMin}, {13, 2}};
    for (const Config& c : configs) {
      const int res = c.res;
      SCOPED_TRACE(std::string(name) + " grid " + std::to_string(res) + " subgrids above " +
                   std::to_string(c.subgrid_min) +
                   (c.traversal == Traversal::Recompute ? " recompute" : ""));
      Grid g = build_grid(s, res, c.subgrid_min);
      if (res == 1 || c.subgrid_min == 2) {
        EXPECT_GT(g.subgrids, 0);
      }
      if (c.subgrid_min == kNoSubgrids) {
        EXPECT_EQ(g.subgrids, 0);
      }
      if (res == 64) {  // jumps of at least 2 shells are possible
        EXPECT_TRUE(std::any_of(g.voxels.begin(), g.voxels.end(),
                                [](const glm::ivec2& e) { return e.y == 0 && e.x >= 4; }));
      }
      TracerOptions options;
      options.traversal = c.traversal;
      Tracer tracer(s, g, options);
      std::vector<int32_t> prim;
      std::vector<float> dist;
      tracer.intersect(GetParam(), o, d, prim, dist);
      int hits = 0, wrong = 0;
      for (size_t k = 0; k < o.size(); ++k) {
        int32_t id;
        float t;
        testing::brute_force_closest(s, o[k], d[k], id, t);
        hits += id >= 0;
        if (prim[k] != id || (id >= 0 && dist[k] != t)) {
          if (++wrong <= 5)
            ADD_FAILURE() << "ray " << k << ": grid " << prim[k] << " at " << dist[k]
                          << ", brute force " << id << " at " << t;
        }
      }
      EXPECT_EQ(wrong, 0);
      EXPECT_GT(hits, static_cast<int>(o.size()) / 3);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Backends, GridTraversal, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
