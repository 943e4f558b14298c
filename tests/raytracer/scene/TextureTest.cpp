// Textures and scene input on the host: PNG loading and sRGB decoding, texture coordinates of
// shapes and OBJ files, map_Kd, the JSON "textures" and material shaders with typed
// parameters, the "textured" built-in scene, and every bad input of these with its message.
// (Sampling on the device is tested with the kernels.)
#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include "MaterialValues.h"
#include "TestUtil.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/scene/Texture.h"
#include "rill/rt/shaders/Registry.h"

namespace rt {
namespace {

using testing::color_of;
using testing::error_of;
using testing::number_of;
using testing::TempDir;

#define EXPECT_HAS(text, part) EXPECT_NE((text).find(part), std::string::npos) << (text)

// Writes raw samples with libpng (format: PNG_FORMAT_*; 16-bit formats take uint16 samples).
void write_raw_png(const std::string& path, int w, int h, png_uint_32 format, const void* data) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(w);
  image.height = static_cast<png_uint_32>(h);
  image.format = format;
  ASSERT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, data, 0, nullptr)) << image.message;
}

// A 2 x 2 RGB PNG: row 0 (the top) red-ish, row 1 blue-ish.
const unsigned char kRgb[12] = {255, 0, 0, 10, 128, 200, 0, 0, 255, 40, 41, 42};

TEST(Texture, Srgb8ToLinearIsTheExactCurve) {
  EXPECT_EQ(srgb8_to_linear(0), 0.0f);
  EXPECT_EQ(srgb8_to_linear(255), 1.0f);
  // Below the knee (10 / 255 = 0.0392 <= 0.04045) the curve is linear.
  EXPECT_EQ(srgb8_to_linear(10), static_cast<float>(10.0 / 255.0 / 12.92));
  EXPECT_EQ(srgb8_to_linear(128),
            static_cast<float>(std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4)));
  for (int c = 1; c < 256; ++c) EXPECT_GT(srgb8_to_linear(c), srgb8_to_linear(c - 1)) << c;
}

TEST(Texture, PngRgbDecodedAsSrgbOrData) {
  TempDir dir;
  const std::string p = dir.path("rgb.png");
  write_raw_png(p, 2, 2, PNG_FORMAT_RGB, kRgb);
  Texture t = load_png_texture(p);
  EXPECT_EQ(t.type, "bitmap");
  EXPECT_EQ(t.file, p);
  EXPECT_EQ(t.name, "rgb.png");
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 2);
  ASSERT_EQ(t.texels.size(), 4u);
  for (size_t i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(t.texels[i][c], srgb8_to_linear(kRgb[3 * i + c])) << i << " " << c;
    }
  Texture d = load_png_texture(p, /*srgb=*/false);
  for (size_t i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(d.texels[i][c], kRgb[3 * i + c] / 255.0f);
  // Row 0 is the top row of the file.
  EXPECT_EQ(d.texels[0], glm::vec3(1.0f, 0.0f, 0.0f));
  EXPECT_EQ(d.texels[2], glm::vec3(0.0f, 0.0f, 1.0f));
}

TEST(Texture, PngGreyAlphaAnd16Bit) {
  TempDir dir;
  // Grey: the same value in r, g and b.
  const unsigned char grey[2] = {0, 200};
  write_raw_png(dir.path("g.png"), 2, 1, PNG_FORMAT_GRAY, grey);
  Texture g = load_png_texture(dir.path("g.png"), false);
  EXPECT_EQ(g.texels[1], glm::vec3(200 / 255.0f));
  // Alpha is ignored: a transparent texel keeps its colour.
  const unsigned char rgba[8] = {200, 100, 50, 0, 20, 30, 40, 255};
  write_raw_png(dir.path("a.png"), 2, 1, PNG_FORMAT_RGBA, rgba);
  Texture a = load_png_texture(dir.path("a.png"), false);
  EXPECT_EQ(a.texels[0], glm::vec3(200 / 255.0f, 100 / 255.0f, 50 / 255.0f));
  EXPECT_EQ(a.texels[1], glm::vec3(20 / 255.0f, 30 / 255.0f, 40 / 255.0f));
  // 16 bits (libpng writes these as linear, with gAMA 1.0): decoded to about the same
  // linear values, through libpng's 8-bit sRGB.
  const png_uint_16 wide[3] = {0, 32768, 65535};
  write_raw_png(dir.path("w.png"), 3, 1, PNG_FORMAT_LINEAR_Y, wide);
  Texture w = load_png_texture(dir.path("w.png"));
  EXPECT_EQ(w.texels[0], glm::vec3(0.0f));
  EXPECT_NEAR(w.texels[1].x, 0.5f, 0.01f);
  EXPECT_EQ(w.texels[2], glm::vec3(1.0f));
}

TEST(Texture, WrapModesAndProceduralTypes) {
  for (WrapMode w : {WrapMode::Repeat, WrapMode::Clamp, WrapMode::Mirror})
    EXPECT_EQ(parse_wrap_mode(wrap_mode_name(w)), w);
  try {
    parse_wrap_mode("wrap");
    ADD_FAILURE() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_HAS(std::string(e.what()), "'wrap'");
  }
  EXPECT_EQ(procedural_texture_types(),
            (std::vector<std::string>{"checker", "noise", "marble", "wood"}));
}

// ---- texture coordinates of shapes ------------------------------------------------------------

TEST(Texture, ShapesHaveTextureCoordinates) {
  Scene s;
  int m = s.add_material(Material{});
  add_quad(s, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, m);
  ASSERT_EQ(s.texcoords.size(), 6u);
  const glm::vec2 quad[6] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(s.texcoords[i], quad[i]) << i;

  Scene b;
  add_box(b, glm::vec3(-1.0f), glm::vec3(1.0f), b.add_material(Material{}));
  ASSERT_EQ(b.texcoords.size(), 36u);
  for (size_t f = 0; f < 6; ++f)
    for (int i = 0; i < 6; ++i) EXPECT_EQ(b.texcoords[6 * f + i], quad[i]) << f << " " << i;

  Scene sp;
  add_sphere(sp, glm::vec3(0.0f), 1.0f, 8, 4, sp.add_material(Material{}));
  ASSERT_EQ(sp.texcoords.size(), sp.positions.size());
  for (size_t i = 0; i < sp.positions.size(); ++i) {
    const glm::vec2 uv = sp.texcoords[i];
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LE(uv.x, 1.0f);
    // v from the south pole (0) to the north (1): v = (y + 1) / 2 at the rings' heights.
    const float v_expected = static_cast<float>(std::acos(-sp.positions[i].y) / 3.14159265358979);
    EXPECT_NEAR(uv.y, v_expected, 1e-5f) << i;
    // u along the longitude: the angle from +x towards -z.
    if (std::fabs(sp.positions[i].y) < 0.999f && uv.x > 0.0f && uv.x < 1.0f) {
      const double phi = 2.0 * 3.14159265358979 * uv.x;
      EXPECT_NEAR(sp.positions[i].x * std::sin(phi), -sp.positions[i].z * std::cos(phi), 1e-5) << i;
    }
  }

  Scene t;
  add_teapot(t, 2, t.add_material(Material{}));
  ASSERT_EQ(t.texcoords.size(), t.positions.size());
  for (const glm::vec2& uv : t.texcoords) {
    EXPECT_TRUE(uv.x == 0.0f || uv.x == 0.5f || uv.x == 1.0f);
    EXPECT_TRUE(uv.y == 0.0f || uv.y == 0.5f || uv.y == 1.0f);
  }
}

TEST(Texture, TrianglesWithoutUvGetZeroAndAppendCarriesTextures) {
  Scene s;
  int m = s.add_material(Material{});
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m);
  EXPECT_TRUE(s.texcoords.empty());
  const glm::vec2 uv[3] = {{0.25f, 0.5f}, {1, 0}, {0, 1}};
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m, nullptr, nullptr, uv);
  s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, m);
  ASSERT_EQ(s.texcoords.size(), 9u);
  for (int i : {0, 1, 2, 6, 7, 8}) EXPECT_EQ(s.texcoords[i], glm::vec2(0.0f));
  EXPECT_EQ(s.texcoords[3], uv[0]);

  Scene o;
  o.textures.resize(2);
  o.textures[1].type = "checker";
  o.textures[0].type = "wood";
  Material tm;
  tm.params["diffuse"] = ParamValue::of_texture(1);
  tm.params["specular"] = ParamValue::of(glm::vec3(0.5f));
  o.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, o.add_material(tm), nullptr, nullptr, uv);
  Scene a;
  a.textures.resize(3);
  for (Texture& t : a.textures) t.type = "noise";
  a.add_material(Material{});
  a.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  a.append(o);
  ASSERT_EQ(a.textures.size(), 5u);
  EXPECT_EQ(a.textures[4].type, "checker");
  ASSERT_EQ(a.materials.size(), 2u);
  EXPECT_EQ(a.materials[1].params.at("diffuse").texture, 4);
  EXPECT_EQ(a.materials[1].params.at("specular").kind, ParamValue::Kind::Color);
  ASSERT_EQ(a.texcoords.size(), 6u);
  EXPECT_EQ(a.texcoords[2], glm::vec2(0.0f));
  EXPECT_EQ(a.texcoords[3], uv[0]);
  EXPECT_NO_THROW(a.validate());
}

TEST(Texture, ValidateChecksTexturesAndTexcoords) {
  auto base = [] {
    Scene s;
    s.has_camera = true;
    s.camera.eye = {0, 0, 5};
    Texture t;
    t.type = "checker";
    s.textures.push_back(t);
    Material m;
    m.name = "m";
    m.params["diffuse"] = ParamValue::of_texture(0);
    const glm::vec2 uv[3] = {{0, 0}, {1, 0}, {0, 1}};
    s.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, s.add_material(m), nullptr, nullptr, uv);
    return s;
  };
  EXPECT_NO_THROW(base().validate());
  auto bad = [&](auto change, const std::string& part) {
    Scene s = base();
    change(s);
    EXPECT_HAS(error_of([&] { s.validate(); }), part);
  };
  bad([](Scene& s) { s.materials[0].params["diffuse"].texture = 1; },
      "material 'm': diffuse refers to texture 1, but the scene has 1");
  bad([](Scene& s) { s.materials[0].params["diffuse"].texture = -1; }, "refers to texture -1");
  bad([](Scene& s) { s.texcoords[1].y = std::nanf(""); },
      "triangle 0: texture coordinates must be finite");
  bad([](Scene& s) { s.texcoords.pop_back(); }, "texcoords and positions disagree");
  bad([](Scene& s) { s.textures[0].type = "plaid"; }, "unknown type 'plaid'");
  bad([](Scene& s) { s.textures[0].scale = INFINITY; }, "finite");
  bad(
      [](Scene& s) {
        s.textures[0].type = "bitmap";
        s.textures[0].width = s.textures[0].height = 2;
        s.textures[0].texels.resize(3);
      },
      "needs width * height texels");
  bad([](Scene& s) { s.materials[0].params["shininess"] = ParamValue::of(NAN); },
      "shininess must be finite");
}

// ---- OBJ: vt and map_Kd ---------------------------------------------------------------------

TEST(Texture, ObjTexcoordsAndMapKd) {
  TempDir dir;
  write_raw_png(dir.path("tex.png"), 2, 2, PNG_FORMAT_RGB, kRgb);
  dir.file("m.mtl",
           "newmtl a\nKd 1 1 1\nmap_Kd tex.png\n"
           "newmtl b\nKd 0.5 0.5 0.5\nmap_Kd tex.png\n"
           "newmtl plain\nKd 0.2 0.3 0.4\n");
  const std::string obj =
      dir.file("m.obj",
               "mtllib m.mtl\n"
               "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
               "usemtl a\nf 1/1 2/2 3/3 4/4\n"  // a quad with vt: fanned with its uv
               "usemtl b\nf 1/4 2/3 3/2\n"      // the same texture, from another material
               "usemtl plain\nf 1 2 3\n");      // no vt: (0, 0)
  Scene s = load_obj(obj);
  EXPECT_NO_THROW(s.validate());
  ASSERT_EQ(s.triangle_count(), 4u);
  ASSERT_EQ(s.texcoords.size(), 12u);
  const glm::vec2 want[12] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1},
                              {0, 1}, {1, 1}, {1, 0}, {0, 0}, {0, 0}, {0, 0}};
  for (int i = 0; i < 12; ++i) EXPECT_EQ(s.texcoords[i], want[i]) << i;
  // One texture for the file both materials name, bound to their diffuse colour.
  ASSERT_EQ(s.textures.size(), 1u);
  EXPECT_EQ(s.textures[0].name, "tex.png");
  EXPECT_EQ(s.textures[0].width, 2);
  EXPECT_EQ(s.textures[0].texels[1].y, srgb8_to_linear(128));
  ASSERT_EQ(s.materials.size(), 3u);
  for (int i : {0, 1}) {
    ASSERT_TRUE(s.materials[i].params.count("diffuse")) << i;
    EXPECT_EQ(s.materials[i].params.at("diffuse").kind, ParamValue::Kind::Texture);
    EXPECT_EQ(s.materials[i].params.at("diffuse").texture, 0);
  }
  EXPECT_EQ(s.materials[2].params.at("diffuse").kind, ParamValue::Kind::Color);
  EXPECT_EQ(color_of(s.materials[2], "diffuse"), glm::vec3(0.2f, 0.3f, 0.4f));

  // Through a JSON scene, after a built-in one with textures: the indices are renumbered.
  std::string json = dir.file("s.json", R"({"builtin": "textured",
    "meshes": [{"file": "m.obj"}]})");
  Scene j = load_json(json);
  const size_t builtin_textures = builtin_scene("textured").textures.size();
  ASSERT_EQ(j.textures.size(), builtin_textures + 1);
  EXPECT_EQ(j.textures.back().name, "tex.png");
  int bound = 0;
  for (const Material& m : j.materials)
    if (m.name == "a" || m.name == "b") {
      EXPECT_EQ(m.params.at("diffuse").texture, static_cast<int>(builtin_textures));
      ++bound;
    }
  EXPECT_EQ(bound, 2);
}

// Faces without vt on a material that reads texture coordinates show one texel: a warning per
// material naming the first such face's line and counting the faces; none for faces with vt,
// for untextured materials, or for solid textures (which read the point, not its uv).
TEST(Texture, FacesWithoutVtOnATexturedMaterialWarn) {
  TempDir dir;
  write_raw_png(dir.path("tex.png"), 2, 2, PNG_FORMAT_RGB, kRgb);
  dir.file("m.mtl", "newmtl a\nKd 1 1 1\nmap_Kd tex.png\nnewmtl plain\nKd 0.2 0.3 0.4\n");
  const std::string quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n";
  auto uv_warnings = [](const Scene& s) {
    std::vector<std::string> found;
    for (const std::string& w : s.warnings)
      if (w.find("texture coordinates") != std::string::npos) found.push_back(w);
    return found;
  };
  // Lines 11 and 12 lack vt (two faces, one a quad of two triangles); line 10 has them.
  const Scene s = load_obj(dir.file("m.obj", "mtllib m.mtl\n" + quad +
                                                 "usemtl a\nf 1/1 2/2 3/3\nf 1 2 3 4\nf 1 3 4\n"
                                                 "usemtl plain\nf 1 2 3\n"));
  const auto w = uv_warnings(s);
  ASSERT_EQ(w.size(), 1u) << (w.empty() ? "" : w[0]);
  EXPECT_NE(w[0].find("m.obj:11: 2 faces of material 'a'"), std::string::npos) << w[0];
  EXPECT_NE(w[0].find("'tex.png'"), std::string::npos) << w[0];
  // With vt everywhere: no warning.
  EXPECT_TRUE(uv_warnings(load_obj(dir.file("ok.obj",
                                            "mtllib m.mtl\n" + quad + "usemtl a\nf 1/1 2/2 3/3\n")))
                  .empty());
  // A JSON material overriding the mesh's: a checker reads uv, a solid noise does not.
  dir.file("bare.obj", quad + "f 1 2 3\n");
  auto json = [&](const std::string& type) {
    return load_json(dir.file("s.json", R"({"textures": {"t": {"type": ")" + type + R"("}},
      "materials": {"m": {"diffuse": {"texture": "t"}}},
      "meshes": [{"file": "bare.obj", "material": "m"}]})"));
  };
  const auto checker = uv_warnings(json("checker"));
  ASSERT_EQ(checker.size(), 1u);
  EXPECT_NE(checker[0].find("bare.obj:8: 1 face of material 'm'"), std::string::npos) << checker[0];
  EXPECT_TRUE(uv_warnings(json("noise")).empty());
}

// ---- JSON: textures, shaders and parameters ---------------------------------------------------

TEST(Texture, JsonTexturesAndShaders) {
  TempDir dir;
  write_raw_png(dir.path("tex.png"), 2, 2, PNG_FORMAT_RGB, kRgb);
  SurfaceShader toon;
  toon.name = "texture-test-toon";
  toon.params = {{"color", ParamType::Color, ParamValue::of(glm::vec3(1.0f)), ""},
                 {"bands", ParamType::Number, ParamValue::of(3.0f), ""}};
  if (find_shader(toon.name) == nullptr) register_shader(toon);  // once, under --gtest_repeat
  const std::string json = dir.file("s.json", R"({
    "textures": {
      "photo": {"file": "tex.png", "wrap": "mirror", "filter": "nearest", "srgb": false},
      "checks": {"type": "checker", "color1": 1, "color2": [0, 0, 0.5], "scale": 4},
      "grain": {"type": "wood"}
    },
    "materials": {
      "classic": {"diffuse": [0.5, 0.6, 0.7], "specular": 0.2, "shininess": 10, "reflect": 0.3},
      "glassy": {"transmit": 0.9, "ior": 1.3},
      "floor": {"diffuse": {"texture": "checks"}, "specular": 0.1},
      "chrome": {"shader": "mirror"},
      "pane": {"shader": "glass", "diffuse": {"texture": "photo"}},
      "toon": {"shader": "texture-test-toon", "color": {"texture": "grain"}, "bands": 5}
    },
    "meshes": [
      {"shape": "quad", "vertices": [[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]],
       "material": "floor"},
      {"shape": "sphere", "radius": 0.5, "slices": 6, "stacks": 3, "material": "chrome",
       "transform": {"translate": [0, 1, 0]}},
      {"shape": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "toon"},
      {"shape": "box", "material": "pane"},
      {"shape": "box", "material": "classic"},
      {"shape": "box", "material": "glassy"}
    ]})");
  Scene s = load_json(json);
  ASSERT_EQ(s.textures.size(), 3u);
  // The JSON object's keys come in sorted order: checks, grain, photo.
  std::map<std::string, int> tex;
  for (size_t i = 0; i < s.textures.size(); ++i) tex[s.textures[i].name] = static_cast<int>(i);
  const Texture& photo = s.textures[tex.at("photo")];
  EXPECT_EQ(photo.type, "bitmap");
  EXPECT_EQ(photo.wrap, WrapMode::Mirror);
  EXPECT_FALSE(photo.bilinear);
  EXPECT_EQ(photo.texels[1], glm::vec3(10 / 255.0f, 128 / 255.0f, 200 / 255.0f));
  const Texture& checks = s.textures[tex.at("checks")];
  EXPECT_EQ(checks.type, "checker");
  EXPECT_EQ(checks.color1, glm::vec3(1.0f));
  EXPECT_EQ(checks.color2, glm::vec3(0.0f, 0.0f, 0.5f));
  EXPECT_EQ(checks.scale, 4.0f);
  EXPECT_EQ(s.textures[tex.at("grain")].type, "wood");

  std::map<std::string, const Material*> mats;
  for (const Material& m : s.materials) mats[m.name] = &m;
  // Classic keys (no "shader") make a phong material, or glass where it transmits, with
  // those parameters (scene/ClassicMaterial.h).
  const Material& classic = *mats.at("classic");
  EXPECT_EQ(classic.shader, "phong");
  EXPECT_EQ(color_of(classic, "diffuse"), glm::vec3(0.5f, 0.6f, 0.7f));
  EXPECT_EQ(color_of(classic, "specular"), glm::vec3(0.2f));
  EXPECT_EQ(number_of(classic, "shininess"), 10.0f);
  EXPECT_EQ(number_of(classic, "reflect"), 0.3f);
  EXPECT_EQ(mats.at("glassy")->shader, "glass");
  EXPECT_EQ(number_of(*mats.at("glassy"), "ior"), 1.3f);
  EXPECT_EQ(number_of(*mats.at("glassy"), "reflect"), 0.0f);  // the classic default
  // A texture binds to a classic colour too.
  const Material& floor = *mats.at("floor");
  EXPECT_EQ(floor.params.at("diffuse").texture, tex.at("checks"));
  EXPECT_EQ(color_of(floor, "specular"), glm::vec3(0.1f));
  // A built-in shader named explicitly takes its own defaults.
  const Material& chrome = *mats.at("chrome");
  EXPECT_EQ(chrome.shader, "mirror");
  EXPECT_EQ(number_of(chrome, "reflect"), 0.9f);
  const Material& pane = *mats.at("pane");
  EXPECT_EQ(pane.shader, "glass");
  EXPECT_EQ(number_of(pane, "transmit"), 0.9f);
  EXPECT_EQ(pane.params.at("diffuse").texture, tex.at("photo"));
  // Another shader's parameters are all in params.
  const Material& toon_m = *mats.at("toon");
  EXPECT_EQ(toon_m.shader, "texture-test-toon");
  EXPECT_EQ(toon_m.params.at("color").texture, tex.at("grain"));
  EXPECT_EQ(toon_m.params.at("bands").kind, ParamValue::Kind::Number);
  EXPECT_EQ(toon_m.params.at("bands").number, 5.0f);

  // Shapes have uv: the quad's, the sphere's (translated), the triangle's.
  ASSERT_EQ(s.texcoords.size(), s.positions.size());
  EXPECT_EQ(s.texcoords[1], glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(s.texcoords[2], glm::vec2(1.0f, 1.0f));
  Scene sphere;
  add_sphere(sphere, glm::vec3(0.0f), 0.5f, 6, 3, sphere.add_material(Material{}));
  for (size_t i = 0; i < sphere.texcoords.size(); ++i)
    EXPECT_EQ(s.texcoords[6 + i], sphere.texcoords[i]) << i;
  const size_t tri = 6 + sphere.texcoords.size();
  EXPECT_EQ(s.texcoords[tri + 1], glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(s.texcoords[tri + 2], glm::vec2(0.0f, 1.0f));
}

TEST(Texture, JsonOverrideMaterialKeepsItsTexture) {
  TempDir dir;
  dir.file("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
  const std::string json = dir.file("s.json", R"({"builtin": "textured",
    "textures": {"c": {"type": "checker"}},
    "materials": {"m": {"diffuse": {"texture": "c"}}},
    "meshes": [{"file": "t.obj", "material": "m"}]})");
  Scene s = load_json(json);
  const size_t n = builtin_scene("textured").textures.size();
  ASSERT_EQ(s.textures.size(), n + 1);
  EXPECT_EQ(s.materials.back().name, "m");
  EXPECT_EQ(s.materials.back().params.at("diffuse").texture, static_cast<int>(n));
  EXPECT_EQ(s.texcoords.back(), glm::vec2(0.0f, 1.0f));
}

TEST(Texture, TexturedBuiltinScene) {
  Scene s = builtin_scene("textured");
  EXPECT_NO_THROW(s.validate());
  EXPECT_LT(s.triangle_count(), 3000u);
  EXPECT_EQ(s.texcoords.size(), s.positions.size());
  EXPECT_EQ(s.lights.size(), 2u);
  EXPECT_TRUE(s.has_camera);
  std::map<std::string, int> types;
  for (const Texture& t : s.textures) ++types[t.type];
  EXPECT_EQ(types, (std::map<std::string, int>{
                       {"bitmap", 1}, {"checker", 1}, {"marble", 1}, {"wood", 1}}));
  for (const Texture& t : s.textures)
    if (t.type == "bitmap") {
      EXPECT_EQ(t.texels.size(), static_cast<size_t>(t.width * t.height));
      EXPECT_NE(t.texels.front(), t.texels[7]);  // not one flat colour
    }
  // Every texture is bound to a material that some triangle uses; one material is a mirror.
  std::vector<int> used(s.materials.size(), 0);
  for (int32_t m : s.material) used[m] = 1;
  std::vector<int> bound(s.textures.size(), 0);
  int mirrors = 0;
  for (size_t i = 0; i < s.materials.size(); ++i) {
    EXPECT_TRUE(used[i]) << s.materials[i].name;
    EXPECT_NE(find_shader(s.materials[i].shader), nullptr);
    mirrors += s.materials[i].shader == "mirror";
    for (const auto& [name, v] : s.materials[i].params)
      if (v.kind == ParamValue::Kind::Texture) {
        EXPECT_EQ(name, "diffuse");
        bound[v.texture] = 1;
      }
  }
  EXPECT_EQ(mirrors, 1);
  for (size_t t = 0; t < bound.size(); ++t) EXPECT_TRUE(bound[t]) << s.textures[t].name;
}

// ---- bad input --------------------------------------------------------------------------------

TEST(BadInputTextures, PngFiles) {
  TempDir dir;
  EXPECT_EQ(error_of([&] { load_png_texture(dir.path("x.png")); }),
            dir.path("x.png") + ": no such file");
  const std::string text = dir.file("x.png", "this is not an image, it is text");
  EXPECT_EQ(error_of([&] { load_png_texture(text); }), text + ": not a PNG file");
  const std::string tiny = dir.file("t.png", "\x89PNG");
  EXPECT_EQ(error_of([&] { load_png_texture(tiny); }), tiny + ": not a PNG file");
  // The right signature, then garbage: libpng's message, with the file named.
  const std::string cut = dir.file("c.png", std::string("\x89PNG\r\n\x1a\n", 8) + "garbage!");
  EXPECT_HAS(error_of([&] { load_png_texture(cut); }), cut + ": cannot read the PNG");
  EXPECT_HAS(error_of([&] { load_png_texture(dir.dir()); }), "is a directory");
}

// A small PNG whose header declares w x h pixels: a 1 x 1 image from libpng with its IHDR's
// size (and the chunk's CRC, which libpng checks) rewritten. Its data is one pixel's.
std::string png_declaring(const TempDir& dir, uint32_t w, uint32_t h) {
  const unsigned char px[3] = {1, 2, 3};
  const std::string path = dir.path("one.png");
  write_raw_png(path, 1, 1, PNG_FORMAT_RGB, px);
  std::ifstream f(path, std::ios::binary);
  std::string png((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  auto put32 = [&](size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i)
      png[at + static_cast<size_t>(i)] = static_cast<char>(v >> (24 - 8 * i));
  };
  put32(16, w);  // the signature (8), the IHDR's length (4) and type (4), then width, height
  put32(20, h);
  uint32_t crc = 0xffffffffu;  // CRC-32 over the chunk's type and data (bytes 12..28)
  for (size_t i = 12; i < 29; ++i) {
    crc ^= static_cast<unsigned char>(png[i]);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  put32(29, ~crc);
  return png;
}

// A PNG's declared size is held to the image limits (ImageLimits.h) from its header, before
// the decoder allocates: a 16384 x 16384 texture (1 GiB decoded; the per-side cap alone let
// it through) and one side over 16384 are errors naming the file, the size and the limits,
// and in a scene file the texture too.
TEST(BadInputTextures, ADeclaredSizeOverTheLimitsIsRefusedBeforeDecoding) {
  TempDir dir;
  const std::string limits = "over the limits (1..16384 per side, at most 33554432 pixels)";
  const std::string square = png_declaring(dir, 16384, 16384);
  EXPECT_LT(square.size(), 100u);
  EXPECT_EQ(error_of([&] { decode_png_texture(square, "huge.png"); }),
            "huge.png: its header declares a 16384x16384 PNG image, " + limits);
  EXPECT_EQ(error_of([&] { decode_png_texture(png_declaring(dir, 16385, 1), "wide.png"); }),
            "wide.png: its header declares a 16385x1 PNG image, " + limits);
  // The patched header itself is sound: at a size within the limits, libpng reads the header
  // and fails on the data (one pixel's), not on the chunk.
  EXPECT_HAS(error_of([&] { decode_png_texture(png_declaring(dir, 2, 1), "two.png"); }),
             "two.png: cannot read the PNG");
  dir.file("huge.png", square);
  EXPECT_EQ(error_of([&] {
              parse_json_scene(R"({"textures": {"wood": {"file": "huge.png"}}})", dir.dir(),
                               "s.json");
            }),
            "s.json: textures.wood.file: " + dir.path("huge.png") +
                ": its header declares a 16384x16384 PNG image, " + limits);
}

// An unknown texture's message names a few of the file's textures and counts the rest: with
// 20,000 of them it stays one short line (it listed every name, 148 KB).
TEST(BadInputTextures, AnUnknownTextureListsAFewOfTheFilesAndCountsTheRest) {
  std::string textures;
  for (int i = 0; i < 20000; ++i)
    textures += (i ? ", " : "") + std::string("\"t") + std::to_string(i) + R"(": {"type": "wood"})";
  const std::string msg = error_of([&] {
    parse_json_scene(R"({"textures": {)" + textures +
                         R"(}, "materials": {"m": {"diffuse": {"texture": "nope"}}}})",
                     ".", "t.json");
  });
  // The names in the file's order as the scene keeps them (sorted): t0, t1, t10, t100, t1000.
  EXPECT_EQ(msg,
            "t.json: materials.m.diffuse: unknown texture 'nope' (textures: t0, t1, t10, t100, "
            "t1000 and 19,995 more)");
}

TEST(BadInputTextures, JsonShadersAndParameters) {
  SurfaceShader req;
  req.name = "texture-test-required";
  ShaderParam tint{"tint", ParamType::Color, ParamValue::of(glm::vec3(1.0f)), "", true};
  req.params = {tint, {"gain", ParamType::Number, ParamValue::of(1.0f), ""}};
  if (find_shader(req.name) == nullptr) register_shader(req);
  auto err = [](const std::string& materials, const std::string& textures = "{}") {
    return error_of([&] {
      parse_json_scene(
          R"({"textures": )" + textures + R"(, "materials": {"m": )" + materials + "}}", ".",
          "t.json");
    });
  };
  const std::string velvet = err(R"({"shader": "velvet"})");
  EXPECT_HAS(velvet, "t.json: materials.m.shader: unknown shader 'velvet' (known: ");
  for (const char* known : {"glass, ", "mirror, ", "phong", "texture-test-required"})
    EXPECT_HAS(velvet, known);
  EXPECT_HAS(err(R"({"shader": 5})"), "t.json: materials.m.shader must be a shader name");
  EXPECT_EQ(err(R"({"diffuse": "red"})"),
            "t.json: materials.m.diffuse: expected a colour [r, g, b], a number or "
            "{\"texture\": NAME}");
  EXPECT_HAS(err(R"({"diffuse": [1, 2]})"), "t.json: materials.m.diffuse: expected a colour");
  EXPECT_HAS(err(R"({"diffuse": {"texture": 3}})"),
             "t.json: materials.m.diffuse: expected a colour");
  EXPECT_EQ(err(R"({"shininess": [1, 2, 3]})"), "t.json: materials.m.shininess: expected a number");
  EXPECT_EQ(err(R"({"reflect": {"texture": "c"}})", R"({"c": {"type": "checker"}})"),
            "t.json: materials.m.reflect: expected a number (textures bind only to colour "
            "parameters)");
  EXPECT_HAS(err(R"({"shader": "texture-test-required", "gain": true, "tint": 1})"),
             "t.json: materials.m.gain: expected a number");
  EXPECT_EQ(err(R"({"shader": "texture-test-required", "gain": 2})"),
            "t.json: materials.m: shader 'texture-test-required' needs parameter 'tint' (a "
            "colour)");
  EXPECT_HAS(
      err(R"({"shader": "texture-test-required", "tint": 1, "diffuse": 1})"),
      "t.json: materials.m: unknown key 'diffuse' (shader, emission, two_sided, tint, gain)");
  EXPECT_HAS(err(R"({"shader": "mirror", "color": 1})"), "materials.m: unknown key 'color'");
  EXPECT_HAS(err(R"({"difuse": 1})"), "materials.m: unknown key 'difuse'");
  EXPECT_EQ(err(R"({"diffuse": {"texture": "nope"}})", R"({"a": {"type": "wood"}})"),
            "t.json: materials.m.diffuse: unknown texture 'nope' (textures: a)");
  EXPECT_EQ(err(R"({"diffuse": {"texture": "nope"}})"),
            "t.json: materials.m.diffuse: unknown texture 'nope' (the file defines no textures)");
  // The required parameter given: no error.
  EXPECT_NO_THROW(parse_json_scene(
      R"({"materials": {"m": {"shader": "texture-test-required", "tint": [1, 0, 0]}}})", ".",
      "t.json"));
}

TEST(BadInputTextures, JsonTextures) {
  TempDir dir;
  dir.file("text.png", "not a png at all");
  auto err = [&](const std::string& textures) {
    const std::string json = dir.file("s.json", R"({"textures": )" + textures + "}");
    return error_of([&] { load_json(json); });
  };
  const std::string scene = dir.path("s.json");
  EXPECT_EQ(err(R"({"w": {"file": "missing.png"}})"),
            scene + ": textures.w.file: " + dir.path("missing.png") + ": no such file");
  EXPECT_EQ(err(R"({"w": {"file": "text.png"}})"),
            scene + ": textures.w.file: " + dir.path("text.png") + ": not a PNG file");
  EXPECT_EQ(err(R"({"w": {}})"), scene + ": textures.w.file must be the path of a PNG file");
  EXPECT_EQ(err(R"({"w": {"type": "plaid"}})"),
            scene +
                ": textures.w.type: unknown texture type 'plaid' (bitmap, checker, noise, "
                "marble, wood)");
  EXPECT_HAS(err(R"({"w": {"type": "checker", "file": "x.png"}})"),
             scene + ": textures.w: unknown key 'file' (type, color1, color2, scale)");
  EXPECT_HAS(err(R"({"w": {"type": "marble", "scale": 0}})"),
             scene + ": textures.w.scale must be in (0, 1e6]");
  // A scale of 1e20 gave NaN pixels; negative colours negative radiance.
  EXPECT_HAS(err(R"({"w": {"type": "wood", "scale": 1e20}})"),
             scene + ": textures.w.scale must be in (0, 1e6]");
  EXPECT_HAS(err(R"({"w": {"type": "checker", "color1": -1}})"),
             "texture 'w': colour [-1, -1, -1] has a negative component; colours must be >= 0");
  EXPECT_HAS(err(R"({"w": {"type": "marble", "color1": "white"}})"), "textures.w.color1");
  EXPECT_HAS(err(R"([])"), scene + ": textures must be an object");
  std::vector<unsigned char> px(12, 100);
  write_raw_png(dir.path("ok.png"), 2, 2, PNG_FORMAT_RGB, px.data());
  EXPECT_HAS(err(R"({"w": {"file": "ok.png", "wrap": "tile"}})"),
             scene + ": textures.w.wrap: unknown wrap mode 'tile'");
  EXPECT_HAS(err(R"({"w": {"file": "ok.png", "filter": "cubic"}})"),
             scene + ": textures.w.filter must be \"bilinear\" or \"nearest\"");
  EXPECT_HAS(err(R"({"w": {"file": "ok.png", "srgb": 1}})"), "textures.w.srgb");
}

TEST(BadInputTextures, ObjTexcoordIndices) {
  TempDir dir;
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\n";
  const std::string a = dir.file("a.obj", head + "f 1/1 2/2 3/3\n\n# a comment\nf 1/1 2/7 3/3\n");
  EXPECT_EQ(error_of([&] { load_obj(a); }), a + ":11: vt index 7 out of range (the file has 4)");
  // Line numbers count every face tinyobjloader keeps, across shapes and materials, and
  // skip faces of fewer than 3 vertices (which it drops) and lines that only start with f.
  const std::string b =
      dir.file("b.obj", head +
                            "o one\nf 1/1 2/2 3/3\nf 1 2\nfoo 1 2 3\no two\r\n  f 1/1 2/2 3/3\r\n"
                            "f 3/3 2/2 1/5\n");
  EXPECT_EQ(error_of([&] { load_obj(b); }), b + ":14: vt index 5 out of range (the file has 4)");
  // Relative indices reaching before the first vt.
  const std::string c = dir.file("c.obj", head + "f 1/-1 2/-2 3/-6\n");
  EXPECT_EQ(error_of([&] { load_obj(c); }), c + ":8: vt index -6 out of range (the file has 4)");
  // A file with no vt at all.
  const std::string d = dir.file("d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/1 3/1\n");
  EXPECT_EQ(error_of([&] { load_obj(d); }), d + ":4: vt index 1 out of range (the file has 0)");
  // Relative indices in range work.
  Scene ok = load_obj(dir.file("e.obj", head + "f 1/-4 2/-3 3/-2\n"));
  ASSERT_EQ(ok.texcoords.size(), 3u);
  EXPECT_EQ(ok.texcoords[1], glm::vec2(1.0f, 0.0f));
}

TEST(BadInputTextures, MtlMapKd) {
  TempDir dir;
  dir.file("text.png", "not a png");
  const std::string obj_text = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
  dir.file("m.mtl", "newmtl red\nKd 1 0 0\nmap_Kd missing.png\n");
  const std::string obj = dir.file("m.obj", obj_text);
  EXPECT_EQ(error_of([&] { load_obj(obj); }),
            obj + ": material 'red': map_Kd " + dir.path("missing.png") + ": no such file");
  dir.file("m.mtl", "newmtl red\nKd 1 0 0\nmap_Kd text.png\n");
  EXPECT_EQ(error_of([&] { load_obj(obj); }),
            obj + ": material 'red': map_Kd " + dir.path("text.png") + ": not a PNG file");
  // With the materials overridden, the maps are not read.
  Material over;
  ObjLoadOptions o;
  o.override_material = &over;
  EXPECT_NO_THROW(load_obj(obj, o));
}

}  // namespace
}  // namespace rt
