// Surface shaders (kernel/Shader.h) and textures (kernel/Textures.h): the registry's checks,
// specialization (a shader no used material names leaves no code), errors in a shader's
// use of its parameters, and, on every backend, a textured scene with user shaders that
// must render the same bits as the cpu backend with both strategies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <set>
#include <tuple>

#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/scene/ClassicMaterial.h"
#include "rill/rt/shaders/Builtin.h"

namespace rt {
namespace {

using testing::expect_identical;

// Counts the IR statements with operation op (in every nested block).
int count_op(const rill::ir::Block& b, rill::ir::Op op) {
  int n = 0;
  for (const rill::ir::Stmt& st : b) {
    if (st.kind == rill::ir::StmtKind::Assign && st.op == op) ++n;
    n += count_op(st.then_body, op) + count_op(st.else_body, op) + count_op(st.cond_body, op) +
         count_op(st.body, op) + count_op(st.step, op);
  }
  return n;
}

// A user shader whose code is recognizable in the IR: atan2 (the built-in shaders have none).
void register_swirl_once() {
  if (find_shader("test_swirl") != nullptr) return;
  SurfaceShader s;
  s.name = "test_swirl";
  s.params = {{"tint", ParamType::Color, ParamValue::of(glm::vec3(1.0f, 0.5f, 0.2f)), ""},
              {"turns", ParamType::Number, ParamValue::of(3.0f), ""}};
  s.emitted = [](const ShadingPoint& sp) {
    Float a = atan2(sp.s.P.z(), sp.s.P.x()) * sp.number("turns");
    return sp.color("tint") * (0.5f + 0.5f * cos(a));
  };
  register_shader(s);
}

// Shows the shader's colour parameter "color" as it is: no lights, no rays.
void register_unlit_once() {
  if (find_shader("test_unlit") != nullptr) return;
  SurfaceShader s;
  s.name = "test_unlit";
  s.params = {{"color", ParamType::Color, ParamValue::of(glm::vec3(1.0f)), ""}};
  s.emitted = [](const ShadingPoint& sp) { return sp.color("color"); };
  register_shader(s);
}

// Toon shading of a (possibly textured) base colour, with mirror reflection on top: a user
// shader with all three functions.
void register_toon_once() {
  if (find_shader("test_toon") != nullptr) return;
  SurfaceShader s;
  s.name = "test_toon";
  s.params = {{"base", ParamType::Color, ParamValue::of(glm::vec3(0.8f, 0.3f, 0.2f)), ""},
              {"bands", ParamType::Number, ParamValue::of(3.0f), ""},
              {"reflect", ParamType::Number, ParamValue::of(0.25f), ""}};
  s.emitted = [](const ShadingPoint& sp) { return 0.1f * sp.color("base"); };
  s.reflected = [](const ShadingPoint& sp, const LightSample& l) {
    Float n = sp.number("bands");
    Float level = floor(max(dot(sp.s.nf, l.L), 0.0f) * n) / n;
    return sp.color("base") * level * l.color;
  };
  s.scatter = [](const ShadingPoint& sp, const Float& w) {
    Scatter out;
    Float r = sp.number("reflect");
    out.local_weight = w * (1.0f - r);
    out.reflect_weight = w * r;
    out.reflect_dir = reflect(-sp.s.V, sp.s.nf);
    return out;
  };
  s.lobes = [](const MaterialParams& p) { return Lobes{p.nonzero("reflect"), false}; };
  register_shader(s);
}

// Texture coordinates for the quads add_quad made, from triangle `first` on: (a, b, c) and
// (a, c, d) get (0,0) (1,0) (1,1) and (0,0) (1,1) (0,1), scaled by k.
void quad_uv(Scene& s, size_t first, float k = 1.0f) {
  s.texcoords.resize(3 * s.triangle_count(), glm::vec2(0.0f));
  for (size_t t = first; t + 1 < s.triangle_count(); t += 2) {
    const glm::vec2 q[6] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 6; ++i) s.texcoords[3 * t + static_cast<size_t>(i)] = k * q[i];
  }
}

Texture procedural(const std::string& type, glm::vec3 c1, glm::vec3 c2, float scale) {
  Texture t;
  t.name = type;
  t.type = type;
  t.color1 = c1;
  t.color2 = c2;
  t.scale = scale;
  return t;
}

// A small bitmap made in memory: w x h texels of a colour ramp.
Texture ramp(int w, int h, WrapMode wrap, bool bilinear) {
  Texture t;
  t.name = "ramp";
  t.width = w;
  t.height = h;
  t.wrap = wrap;
  t.bilinear = bilinear;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      t.texels.emplace_back((x + 0.5f) / static_cast<float>(w), (y + 0.5f) / static_cast<float>(h),
                            0.25f + 0.5f * static_cast<float>((x + y) % 2));
  return t;
}

Material textured(const std::string& shader, const std::string& param, int texture) {
  Material m;
  m.name = shader + "-" + param;
  m.shader = shader;
  m.params[param] = ParamValue::of_texture(texture);
  return m;
}

// Every kind of texture and shader at once, no glass (the multipass strategy has no
// refraction): a checkered floor (phong), marble and wood spheres, a noisy box, two
// bitmap quads (bilinear repeat, nearest mirror), a toon quad and a mirror.
Scene textured_scene() {
  register_toon_once();
  Scene s;
  s.name = "textured-test";
  s.textures = {
      procedural("checker", glm::vec3(0.9f), glm::vec3(0.1f, 0.1f, 0.3f), 4.0f),
      procedural("marble", glm::vec3(0.95f), glm::vec3(0.3f, 0.3f, 0.35f), 2.0f),
      procedural("wood", glm::vec3(0.6f, 0.4f, 0.2f), glm::vec3(0.3f, 0.15f, 0.05f), 4.0f),
      procedural("noise", glm::vec3(0.2f, 0.6f, 0.2f), glm::vec3(0.9f), 5.0f),
      ramp(8, 4, WrapMode::Repeat, true),
      ramp(3, 5, WrapMode::Mirror, false)};
  const int floor = s.add_material(textured("phong", "diffuse", 0));
  const int marble = s.add_material(textured("phong", "diffuse", 1));
  const int wood = s.add_material(textured("phong", "diffuse", 2));
  const int noisy = s.add_material(textured("phong", "diffuse", 3));
  const int bitmap = s.add_material(textured("phong", "diffuse", 4));
  const int toon = s.add_material(textured("test_toon", "base", 5));
  Material mirror;
  mirror.name = "mirror";
  mirror.shader = "mirror";
  const int mirror_m = s.add_material(mirror);
  add_quad(s, {-4, 0, -4}, {4, 0, -4}, {4, 0, 4}, {-4, 0, 4}, floor);
  quad_uv(s, 0);
  add_sphere(s, {-1.5f, 1.0f, 0.0f}, 1.0f, 16, 8, marble);
  add_sphere(s, {1.5f, 1.0f, 0.0f}, 1.0f, 16, 8, wood);
  add_box(s, {-0.5f, 0.0f, 1.5f}, {0.5f, 0.8f, 2.5f}, noisy);
  size_t first = s.triangle_count();
  add_quad(s, {-3, 0.2f, -3}, {-1, 0.2f, -3}, {-1, 2.2f, -3}, {-3, 2.2f, -3}, bitmap);
  add_quad(s, {1, 0.2f, -3}, {3, 0.2f, -3}, {3, 2.2f, -3}, {1, 2.2f, -3}, toon);
  quad_uv(s, first, 1.7f);  // beyond 1: the wrap modes
  add_quad(s, {-1, 0.2f, -3.5f}, {1, 0.2f, -3.5f}, {1, 2.2f, -3.5f}, {-1, 2.2f, -3.5f}, mirror_m);
  s.texcoords.resize(3 * s.triangle_count(), glm::vec2(0.0f));
  s.lights = {Light{{3, 5, 4}, glm::vec3(0.7f)}, Light{{-4, 4, 2}, glm::vec3(0.4f)}};
  s.camera = Camera{{0.0f, 2.5f, 6.5f}, {0.0f, 0.8f, 0.0f}, {0.0f, 1.0f, 0.0f}, 55.0f};
  s.has_camera = true;
  s.options.max_depth = 3;
  return s;
}

TEST(Shaders, BuiltinsAreRegistered) {
  for (const char* name : {"phong", "mirror", "glass"}) {
    EXPECT_NE(find_shader(name), nullptr) << name;
    const std::vector<std::string> names = shader_names();
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  }
  EXPECT_EQ(find_shader("no-such-shader"), nullptr);
  // A material is phong unless it names another shader; a classic material (MTL, a JSON one
  // without "shader") is glass where it transmits.
  EXPECT_EQ(Material{}.shader, "phong");
  ClassicMaterial glass;
  glass.transmit = 0.5f;
  EXPECT_EQ(glass.material("g").shader, "glass");
  EXPECT_EQ(ClassicMaterial{}.material("p").shader, "phong");
  EXPECT_EQ(ClassicMaterial{}.material("p").params.count("transmit"), 0u);
}

// A shader that shows one flat colour wherever a ray hits: no lights, no rays.
SurfaceShader flat_shader(const std::string& name, glm::vec3 color) {
  SurfaceShader s;
  s.name = name;
  s.emitted = [color](const ShadingPoint&) { return Float3(color); };
  return s;
}

// replace_shader gives the shader of that name to the tracers built after it; a tracer built
// before keeps the shader it was built with, even for a program it captures only later (the
// Ray loop's, at its first use on a GPU backend or here).
TEST(Shaders, ReplaceChangesTheTracersBuiltAfterIt) {
  const glm::vec3 red(1, 0, 0), green(0, 1, 0);
  register_shader(flat_shader("test_replaced", red));
  EXPECT_THROW(register_shader(flat_shader("test_replaced", green)), std::invalid_argument);
  Scene s = builtin_scene("cornell");
  for (Material& m : s.materials) m.shader = "test_replaced";
  const Grid grid = build_grid_for(s);
  Tracer before(s, grid);
  replace_shader(flat_shader("test_replaced", green));
  Tracer after(s, grid);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = rs.height = 16;
  // The hits' colours of a render: one colour where the shader is flat.
  auto hit_colors = [&](Tracer& t, MegakernelLoop loop) {
    rs.loop = loop;
    const RenderResult r = t.render(rs, s.camera);
    std::set<std::tuple<float, float, float>> colors;
    for (size_t p = 0; p < r.color.size(); ++p)
      if (r.prim[p] >= 0) colors.insert({r.color[p].x, r.color[p].y, r.color[p].z});
    return colors;
  };
  using Colors = std::set<std::tuple<float, float, float>>;
  for (MegakernelLoop loop : {MegakernelLoop::Ray, MegakernelLoop::Segment}) {
    EXPECT_EQ(hit_colors(before, loop), (Colors{{1.0f, 0.0f, 0.0f}}));
    EXPECT_EQ(hit_colors(after, loop), (Colors{{0.0f, 1.0f, 0.0f}}));
  }
  // Replacing keeps the first shader alive: find_shader's pointer to it stayed valid.
  EXPECT_EQ(find_shader("test_replaced")->name, "test_replaced");
}

// A built-in shader is a plugin like any other: replaced by name with its own definition (as
// the library registers it), a scene renders the same bits as before; the tracer built
// before keeps rendering them too.
TEST(Shaders, ReplacingABuiltInByNameGivesTheSameImage) {
  Scene s = builtin_scene("glass");  // phong, mirror reflection and glass
  const Grid grid = build_grid_for(s);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = 24;
  rs.height = 18;
  Tracer before(s, grid);
  const RenderResult a = before.render(rs, s.camera);
  const SurfaceShader* old_phong = find_shader("phong");
  replace_shader(phong_shader());
  replace_shader(glass_shader());
  EXPECT_NE(find_shader("phong"), old_phong);
  Tracer after(s, grid);
  const RenderResult b = after.render(rs, s.camera);
  const RenderResult c = before.render(rs, s.camera);
  ASSERT_EQ(a.color.size(), b.color.size());
  EXPECT_EQ(0, std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(glm::vec3)));
  EXPECT_EQ(0, std::memcmp(a.color.data(), c.color.data(), a.color.size() * sizeof(glm::vec3)));
  EXPECT_EQ(a.prim, b.prim);
}

TEST(Shaders, RegisterRejectsBadDeclarations) {
  auto message = [](SurfaceShader s) {
    try {
      register_shader(std::move(s));
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  SurfaceShader unnamed;
  EXPECT_NE(message(unnamed).find("no name"), std::string::npos);
  SurfaceShader taken;
  taken.name = "phong";
  EXPECT_NE(message(taken).find("'phong' is registered already"), std::string::npos);
  SurfaceShader twice;
  twice.name = "test_twice";
  twice.params = {{"k", ParamType::Number, ParamValue::of(1.0f), ""},
                  {"k", ParamType::Number, ParamValue::of(2.0f), ""}};
  EXPECT_NE(message(twice).find("'k' is declared twice"), std::string::npos);
  SurfaceShader wrong;
  wrong.name = "test_wrong_default";
  wrong.params = {{"tint", ParamType::Color, ParamValue::of(1.0f), ""}};
  EXPECT_NE(message(wrong).find("parameter 'tint': the default is not a colour"),
            std::string::npos);
  EXPECT_EQ(find_shader("test_twice"), nullptr);
}

TEST(Shaders, OnlyShadersOfUsedMaterialsAreGenerated) {
  register_swirl_once();
  Scene s = builtin_scene("cornell");
  Material swirl;
  swirl.name = "swirl";
  swirl.shader = "test_swirl";
  const int m = s.add_material(swirl);  // defined, used by no triangle
  {
    Tracer t(s, build_grid(s, 4));
    EXPECT_EQ(t.shaders(), std::vector<std::string>{"phong"});
    for (MegakernelLoop loop : {MegakernelLoop::Ray, MegakernelLoop::Segment})
      EXPECT_EQ(count_op(t.program(loop).ir().body, rill::ir::Op::Atan2), 0)
          << megakernel_loop_name(loop);
  }
  s.material[0] = m;  // now one triangle uses it
  Tracer t(s, build_grid(s, 4));
  EXPECT_EQ(t.shaders(), (std::vector<std::string>{"phong", "test_swirl"}));
  for (MegakernelLoop loop : {MegakernelLoop::Ray, MegakernelLoop::Segment})
    EXPECT_GT(count_op(t.program(loop).ir().body, rill::ir::Op::Atan2), 0)
        << megakernel_loop_name(loop);
}

TEST(Shaders, TextureCodeOnlyWhereATextureIsBound) {
  Scene s = builtin_scene("cornell");
  s.textures = {procedural("marble", glm::vec3(1.0f), glm::vec3(0.0f), 1.0f)};
  Tracer plain(s, build_grid(s, 4));
  s.materials[0].params["diffuse"] = ParamValue::of_texture(0);
  Tracer marble(s, build_grid(s, 4));
  // Both loops: the GPUs run Ray's program, the CPU backends Segment's.
  for (MegakernelLoop loop : {MegakernelLoop::Ray, MegakernelLoop::Segment}) {
    EXPECT_EQ(count_op(plain.program(loop).ir().body, rill::ir::Op::Sin), 0)
        << megakernel_loop_name(loop);
    EXPECT_GT(count_op(marble.program(loop).ir().body, rill::ir::Op::Sin), 0)
        << megakernel_loop_name(loop);
  }
}

TEST(Shaders, ParameterMisuseNamesShaderAndParameter) {
  if (find_shader("test_misuse") == nullptr) {
    SurfaceShader s;
    s.name = "test_misuse";
    s.params = {{"k", ParamType::Number, ParamValue::of(1.0f), ""}};
    s.emitted = [](const ShadingPoint& sp) { return sp.color("k"); };  // a number, as colour
    register_shader(s);
  }
  Scene s = builtin_scene("cornell");
  s.materials[0].shader = "test_misuse";
  try {
    Tracer t(s, build_grid(s, 4));
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("shader 'test_misuse' reads parameter 'k' as a colour"),
              std::string::npos)
        << e.what();
  }
  s.materials[0].shader = "no_such_shader";
  EXPECT_THROW(Tracer(s, build_grid(s, 4)), SceneError);
}

class ShaderRender : public ::testing::TestWithParam<std::string> {};

// A 2 x 2 bitmap with nearest filtering on a quad that fills the image, shown as it is:
// each quarter of the image is one texel, row 0 of the bitmap at the top (v = 1).
TEST_P(ShaderRender, BitmapTexelsLandWhereTheyShould) {
  RT_REQUIRE_BACKEND(GetParam());
  register_unlit_once();
  Scene s;
  Texture t;
  t.name = "four";
  t.width = t.height = 2;
  t.bilinear = false;
  t.texels = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};  // top left, top right, ...
  s.textures = {t};
  const int m = s.add_material(textured("test_unlit", "color", 0));
  add_quad(s, {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, m);
  quad_uv(s, 0);
  s.camera = Camera{{0, 0, 1}, {0, 0, 0}, {0, 1, 0}, 90.0f};  // the quad fills the view
  s.has_camera = true;
  s.background = glm::vec3(0.5f);
  Tracer tracer(s, build_grid(s, 2));
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.backend = GetParam();
  rs.width = rs.height = 8;
  RenderResult r = tracer.render(rs, s.camera);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const glm::vec3 want = t.texels[static_cast<size_t>((y / 4) * 2 + x / 4)];
      EXPECT_EQ(r.color[static_cast<size_t>(y * 8 + x)], want) << "pixel " << x << ", " << y;
    }
}

TEST_P(ShaderRender, TexturedUserShadersMatchCpuWithBothStrategies) {
  RT_REQUIRE_BACKEND(GetParam());
  Scene s = textured_scene();
  Tracer t(s, build_grid(s, 0));
  const std::vector<std::string> used = t.shaders();
  EXPECT_EQ(used.size(), 3u);  // phong, test_toon, mirror
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;  // the AOVs compared
  rs.width = 40;
  rs.height = 30;
  RenderResult cpu = t.render(rs, s.camera);
  rs.backend = GetParam();
  if (GetParam() != "cpu")
    expect_identical(cpu, t.render(rs, s.camera), "megakernel on " + GetParam());
  rs.strategy = Strategy::Multipass;
  expect_identical(cpu, t.render(rs, s.camera), "multipass on " + GetParam());
  // The textures show: the floor is not one colour.
  int distinct = 0;
  for (size_t p = 1; p < cpu.color.size(); ++p) distinct += cpu.color[p] != cpu.color[p - 1];
  EXPECT_GT(distinct, 600);
}

INSTANTIATE_TEST_SUITE_P(Backends, ShaderRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
