// Only what the scene calls for: the host decides at capture time which code the tracer
// kernel contains. Checked on the captured IR (Program::ir()).
#include <gtest/gtest.h>

#include <set>

#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/accel/LightBuffer.h"

namespace rt {
namespace {

struct IrStats {
  int statements = 0, loops = 0, pows = 0, gathers = 0;
  std::set<std::string> arrays;
};

void walk(const rill::ir::Block& b, IrStats& s) {
  for (const rill::ir::Stmt& st : b) {
    if (st.kind == rill::ir::StmtKind::Assign) {
      s.pows += st.op == rill::ir::Op::Pow;
      s.gathers += st.op == rill::ir::Op::Gather;
    }
    walk(st.then_body, s);
    walk(st.else_body, s);
    walk(st.cond_body, s);
    walk(st.body, s);
    walk(st.step, s);
  }
}

// The tracer's IR for the scene, on a one-level grid (the subgrid's loops: Subgrids below).
IrStats stats(const Scene& scene, int32_t subgrid_min = kNoSubgrids,
              MegakernelLoop loop = MegakernelLoop::Ray) {
  Grid g = build_grid(scene, 4, subgrid_min);
  Tracer t(scene, g);
  const rill::ir::Function& fn = t.program(loop).ir();
  IrStats s;
  s.statements = rill::ir::count_statements(fn.body);
  s.loops = rill::ir::count_loops(fn.body);
  walk(fn.body, s);
  for (const auto& a : fn.arrays) s.arrays.insert(a.name);
  return s;
}

// A diffuse box on a floor, one light.
Scene base() {
  Scene s;
  s.name = "features";
  int m = s.add_material(Material{});
  add_box(s, {-1, 0, -1}, {1, 1, 1}, m);
  add_quad(s, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, m);
  s.lights.push_back(Light{{2, 5, 3}, glm::vec3(1.0f)});
  s.camera = Camera{{0, 2, 6}, {0, 0.5f, 0}, {0, 1, 0}, 45};
  s.has_camera = true;
  return s;
}

TEST(Features, DiffuseSceneHasNoReflectionRefractionOrHighlights) {
  Scene s = base();
  Features f = scene_features(s, resolve_shaders(s));
  EXPECT_TRUE(f.geometry && f.lights && f.shadows);
  EXPECT_FALSE(f.reflection || f.refraction || f.specular || f.vertex_normals || f.vertex_colors);
  EXPECT_EQ(f.stack, 0);
  IrStats d = stats(s);
  // Loops: the tracer's RILL_DO, the 3D-DDA's RILL_DO, the voxel's triangle RILL_FOR, and
  // the shadow rays' RILL_FOR over their light buffer cell.
  EXPECT_EQ(d.loops, 4);
  EXPECT_EQ(d.pows, 0);
  EXPECT_EQ(d.arrays.count("tri_n0"), 0u);
  EXPECT_EQ(d.arrays.count("light_pos"), 1u);
  EXPECT_EQ(d.arrays.count("lb_cells"), 1u);
  // Without the light buffer, shadow rays walk the grid: its loop and arrays are gone.
  Scene off = base();
  off.options.light_buffer = kLightBufferOff;
  IrStats doff = stats(off);
  EXPECT_EQ(doff.loops, 3);
  EXPECT_EQ(doff.arrays.count("lb_cells"), 0u);

  // A reflective material adds the reflection code (and only that).
  Scene r = base();
  r.materials[0].set("reflect", 0.5f);
  IrStats dr = stats(r);
  EXPECT_TRUE(scene_features(r, resolve_shaders(r)).reflection);
  EXPECT_FALSE(scene_features(r, resolve_shaders(r)).refraction);
  EXPECT_GT(dr.statements, d.statements);
  EXPECT_EQ(dr.loops, 4);

  // Glass adds refraction and the ray stack on top.
  Scene g = base();
  g.materials[0].shader = "glass";
  g.materials[0].set("transmit", 0.9f).set("reflect", 0.0f);
  Features fg = scene_features(g, resolve_shaders(g));
  EXPECT_TRUE(fg.refraction && fg.reflection);
  EXPECT_EQ(fg.stack, kRayStack);
  IrStats dg = stats(g);
  EXPECT_GT(dg.statements, dr.statements);
  EXPECT_EQ(dg.loops, 4);

  // Highlights: a pow, and reads of the specular colour and shininess from the material
  // table.
  Scene h = base();
  h.materials[0].set("specular", glm::vec3(0.5f));
  IrStats dh = stats(h);
  EXPECT_GT(dh.pows, 0);
  EXPECT_GT(dh.gathers, d.gathers);
}

TEST(Features, NoLightsNoShadowRays) {
  Scene s = base();
  IrStats with = stats(s);
  s.lights.clear();
  Features f = scene_features(s, resolve_shaders(s));
  EXPECT_FALSE(f.lights || f.shadows || f.specular);
  IrStats without = stats(s);
  EXPECT_EQ(without.arrays.count("light_pos"), 0u);
  EXPECT_EQ(without.arrays.count("light_col"), 0u);
  EXPECT_LT(without.statements, with.statements);
  EXPECT_EQ(without.loops, 3);
  // Specular materials make no highlight code without lights.
  s.materials[0].set("specular", glm::vec3(1.0f));
  EXPECT_EQ(stats(s).pows, 0);
}

TEST(Features, LightsWithoutShadowsLoopOverLights) {
  Scene s = base();
  s.options.shadows = false;
  Features f = scene_features(s, resolve_shaders(s));
  EXPECT_TRUE(f.lights);
  EXPECT_FALSE(f.shadows);
  IrStats d = stats(s);
  EXPECT_EQ(d.loops, 4);  // + the RILL_FOR over the lights
  EXPECT_EQ(d.arrays.count("light_pos"), 1u);
}

// The second grid level's code (a DDA loop and a triangle loop) is generated only when the
// grid has a subgrid.
TEST(Features, Subgrids) {
  Scene s = base();
  Grid g = build_grid(s, 4, 4);
  EXPECT_GT(g.subgrids, 0);  // some of the box's voxels list more than 4 triangles
  EXPECT_EQ(stats(s, 4).loops, stats(s).loops + 2);
  EXPECT_EQ(build_grid(s, 4).subgrids, 0);               // off by default
  EXPECT_EQ(build_grid(s, 4, kSubgridMin).subgrids, 0);  // and none lists more than 12
  EXPECT_EQ(stats(s, kSubgridMin).loops, stats(s).loops);
}

TEST(Features, VertexNormalsAndColors) {
  Scene s = base();
  glm::vec3 n[3] = {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}};
  glm::vec3 c[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.add_triangle({0, 2, 0}, {1, 2, 0}, {0, 2, 1}, 0, n, c);
  Features f = scene_features(s, resolve_shaders(s));
  EXPECT_TRUE(f.vertex_normals && f.vertex_colors);
  IrStats d = stats(s);
  EXPECT_EQ(d.arrays.count("tri_n0"), 1u);
  EXPECT_EQ(d.arrays.count("tri_c0"), 1u);
  s.options.smooth_normals = false;
  IrStats flat = stats(s);
  EXPECT_EQ(flat.arrays.count("tri_n0"), 0u);
  EXPECT_LT(flat.statements, d.statements);
}

TEST(Features, EmptySceneHasNoIntersector) {
  Scene s = builtin_scene("empty");
  Features f = scene_features(s, resolve_shaders(s));
  EXPECT_FALSE(f.geometry);
  IrStats d = stats(s);
  EXPECT_EQ(d.loops, 1);  // the tracer's loop only
  EXPECT_EQ(d.gathers, 0);
  EXPECT_TRUE(d.arrays.empty());
  // Only degenerate triangles: the same.
  Scene z = builtin_scene("empty");
  z.add_material(Material{});
  z.add_triangle({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0);
  EXPECT_FALSE(scene_features(z, resolve_shaders(z)).geometry);
  EXPECT_EQ(stats(z).loops, 1);
}

// The CPU backends' loop (Segment) generates only what the scene calls for too: the same
// arrays and highlights as the GPUs' loop, and an empty scene's kernel has no intersector.
TEST(Features, BothLoopsGenerateWhatTheSceneCallsFor) {
  Scene spec = base();
  spec.materials[0].set("specular", glm::vec3(0.5f));
  for (const Scene& s : {base(), spec, builtin_scene("glass"), builtin_scene("empty")}) {
    SCOPED_TRACE(s.name);
    const IrStats ray = stats(s, kNoSubgrids, MegakernelLoop::Ray);
    const IrStats segment = stats(s, kNoSubgrids, MegakernelLoop::Segment);
    EXPECT_EQ(segment.arrays, ray.arrays);
    EXPECT_EQ(segment.pows, ray.pows);
  }
  const IrStats empty = stats(builtin_scene("empty"), kNoSubgrids, MegakernelLoop::Segment);
  EXPECT_EQ(empty.loops, 1);
  EXPECT_EQ(empty.gathers, 0);
  EXPECT_TRUE(empty.arrays.empty());
}

TEST(Features, UnusedMaterialsDoNotCount) {
  Scene s = base();
  Material glass;
  glass.shader = "glass";
  glass.set("transmit", 1.0f);
  s.add_material(glass);  // defined, used by no triangle
  EXPECT_FALSE(scene_features(s, resolve_shaders(s)).refraction);
}

}  // namespace
}  // namespace rt
