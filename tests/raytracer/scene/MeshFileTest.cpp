// PLY and glTF 2.0 files (scene/MeshFile.h, read with assimp): the triangles, normals,
// materials, node transforms and primitive ids they load as, their bad input, and a render of
// a PLY and a glTF file on every backend against the same mesh as an OBJ file, bit for bit.
// The files are written by the tests: ASCII and binary PLY, a .gltf with its buffer embedded
// as base64 and the same as a .glb.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "ParamName.h"
#include "RenderCompare.h"
#include "TestUtil.h"
#include "rill/rt/Tracer.h"
#include "rill/rt/accel/Grid.h"
#include "rill/rt/load/SceneFile.h"
#include "rill/rt/scene/Image.h"
#include "rill/rt/scene/MeshFile.h"

namespace rt {
namespace {

#define RT_REQUIRE_ASSIMP() \
  if (!have_assimp()) GTEST_SKIP() << "built without assimp"

// ---- writing the files ----------------------------------------------------------------

// A square (quad), a concave L-shaped hexagon and a tent of two triangles, as OBJ and PLY
// write them (0-based in PLY).
// clang-format off
const std::vector<glm::vec3> kVertices = {
    {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},                         // the quad
    {2, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}, {3, 2, 0}, {2, 2, 0},   // the L
    // a tent (two faces at 90 degrees): computed normals
    {0, 3, 0}, {1, 3, 0}, {0.5f, 3.5f, 0.5f}, {0.5f, 3.5f, -0.5f}};
// clang-format on
const std::vector<std::vector<uint32_t>> kFaces = {
    {0, 1, 2, 3}, {4, 5, 6, 7, 8, 9}, {10, 11, 12}, {11, 10, 13}};

std::string obj_text() {
  std::string s;
  for (const glm::vec3& v : kVertices)
    s += "v " + std::to_string(v.x) + " " + std::to_string(v.y) + " " + std::to_string(v.z) + "\n";
  for (const auto& f : kFaces) {
    s += "f";
    for (uint32_t i : f) s += " " + std::to_string(i + 1);
    s += "\n";
  }
  return s;
}

template <class T>
void put(std::string& out, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    for (size_t k = 0; k < sizeof(T) / 2; ++k) std::swap(b[k], b[sizeof(T) - 1 - k]);
  out.append(b, sizeof(T));
}

enum class PlyFormat { Ascii, Little, Big };

// The mesh above as PLY; with `normals`, every vertex gets nx ny nz = normal.
std::string ply_text(PlyFormat format, const glm::vec3* normal = nullptr) {
  std::string s = "ply\nformat ";
  s += format == PlyFormat::Ascii    ? "ascii"
       : format == PlyFormat::Little ? "binary_little_endian"
                                     : "binary_big_endian";
  s += " 1.0\ncomment written by MeshFileTest\nelement vertex " + std::to_string(kVertices.size()) +
       "\nproperty float x\nproperty float y\nproperty float z\n";
  if (normal) s += "property float nx\nproperty float ny\nproperty float nz\n";
  s += "element face " + std::to_string(kFaces.size()) +
       "\nproperty list uchar int vertex_indices\nend_header\n";
  const bool big = format == PlyFormat::Big;
  for (const glm::vec3& v : kVertices) {
    std::vector<float> values = {v.x, v.y, v.z};
    if (normal) values.insert(values.end(), {normal->x, normal->y, normal->z});
    if (format == PlyFormat::Ascii) {
      for (float x : values) s += std::to_string(x) + " ";
      s += "\n";
    } else {
      for (float x : values) put(s, x, big);
    }
  }
  for (const auto& f : kFaces) {
    if (format == PlyFormat::Ascii) {
      s += std::to_string(f.size());
      for (uint32_t i : f) s += " " + std::to_string(i);
      s += "\n";
    } else {
      put(s, static_cast<uint8_t>(f.size()));
      for (uint32_t i : f) put(s, static_cast<int32_t>(i), big);
    }
  }
  return s;
}

std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < in.size(); i += 3) {
    uint32_t n = static_cast<uint8_t>(in[i]) << 16;
    if (i + 1 < in.size()) n |= static_cast<uint8_t>(in[i + 1]) << 8;
    if (i + 2 < in.size()) n |= static_cast<uint8_t>(in[i + 2]);
    out += k[(n >> 18) & 63];
    out += k[(n >> 12) & 63];
    out += i + 1 < in.size() ? k[(n >> 6) & 63] : '=';
    out += i + 2 < in.size() ? k[n & 63] : '=';
  }
  return out;
}

// The glTF test asset's binary buffer: a unit square in z = 0 (4 vertices, normals +z, uv
// (0,0) (1,0) (1,1) (0,1)) and its two triangles (uint16 indices 0 1 2, 0 2 3).
std::string gltf_buffer(const std::vector<uint16_t>& indices = {0, 1, 2, 0, 2, 3}) {
  std::string b;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) put(b, v);
  for (int k = 0; k < 4; ++k)
    for (float v : {0.f, 0.f, 1.f}) put(b, v);
  for (float v : {0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 1.f}) put(b, v);
  for (uint16_t i : indices) put(b, i);
  return b;
}

// The glTF JSON: mesh 0 has two primitives (materials 0 and 1) of the square; node 0
// (translate +x) has child node 1 (scale 2) with mesh 0; node 2 mirrors it (scale -1 in x).
// `uri`: the buffer's (empty for a .glb); `extra`: more top-level members; `material0`: the
// first material's members.
const char* kHierarchy = R"("scenes": [{"nodes": [0, 2]}],
  "nodes": [{"children": [1], "translation": [1, 0, 0]}, {"mesh": 0, "scale": [2, 2, 2]},
            {"mesh": 0, "scale": [-1, 1, 1]}],
  "meshes": [{"primitives": [
    {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0},
    {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 1}]}],)";
// One node with the square alone.
const char* kSquare = R"("scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [
    {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],)";

std::string gltf_json(const std::string& uri, const std::string& extra = "",
                      const std::string& material0 =
                          R"("name": "plastic", "pbrMetallicRoughness": {"baseColorFactor":
                             [0.5, 0.25, 1, 1], "metallicFactor": 0, "roughnessFactor": 0.5})",
                      const std::string& layout = kHierarchy) {
  const size_t index_count = 6;
  const size_t length = 128 + 2 * index_count;
  return R"({"asset": {"version": "2.0"}, "scene": 0, )" + layout + R"(
  "materials": [{)" +
         material0 + R"(},
    {"name": "metal", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.5, 0.25, 1],
     "metallicFactor": 1, "roughnessFactor": 0.25}, "emissiveFactor": [2, 1, 0.5]}],
  "buffers": [{"byteLength": )" +
         std::to_string(length) + (uri.empty() ? "" : R"(, "uri": ")" + uri + "\"") + R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 48},
    {"buffer": 0, "byteOffset": 96, "byteLength": 32},
    {"buffer": 0, "byteOffset": 128, "byteLength": )" +
         std::to_string(2 * index_count) + R"(}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 3, "componentType": 5123, "count": )" +
         std::to_string(index_count) + R"(, "type": "SCALAR"}])" + extra + "}";
}

std::string gltf_embedded(const std::string& extra = "") {
  return gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer()), extra);
}

std::string glb(const std::string& json, const std::string& bin) {
  std::string j = json, b = bin;
  while (j.size() % 4) j += ' ';
  while (b.size() % 4) b += '\0';
  std::string out = "glTF";
  put(out, uint32_t{2});
  put(out, static_cast<uint32_t>(12 + 8 + j.size() + 8 + b.size()));
  put(out, static_cast<uint32_t>(j.size()));
  out += "JSON" + j;
  put(out, static_cast<uint32_t>(b.size()));
  out += std::string("BIN\0", 4) + b;
  return out;
}

glm::vec3 face_normal(const Scene& s, size_t t) {
  const glm::vec3* p = &s.positions[3 * t];
  return glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
}

// s with its first `from` (which must be there) replaced by `to`.
std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

// ---- PLY -------------------------------------------------------------------------------

// ASCII, little- and big-endian PLY files load as the same OBJ: the same triangles in the
// same order (the quad fanned, the L ear-clipped: primitive ids as docs/primitive-ids.md),
// and the same computed normals (the tent's two faces meet at 90 degrees, beyond the
// default crease angle, so they stay flat; a crease of 100 degrees smooths them).
TEST(MeshFile, PlyLoadsAsTheSameObj) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const std::string obj = dir.file("m.obj", obj_text());
  for (float crease : {kDefaultCreaseDegrees, 100.0f}) {
    ObjLoadOptions o;
    o.crease_degrees = crease;
    const Scene ref = load_obj(obj, o);
    // 2 + 4 + 1 + 1 triangles: n - 2 per polygon.
    ASSERT_EQ(ref.triangle_count(), 8u);
    EXPECT_EQ(ref.normals.empty(), crease < 90.0f);
    for (PlyFormat f : {PlyFormat::Ascii, PlyFormat::Little, PlyFormat::Big}) {
      SCOPED_TRACE(static_cast<int>(f));
      const Scene s = load_mesh_file(dir.file("m.ply", ply_text(f)), o);
      EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
      EXPECT_EQ(s.positions, ref.positions);
      EXPECT_EQ(s.normals, ref.normals);
      EXPECT_EQ(s.material, ref.material);
      ASSERT_EQ(s.materials.size(), 1u);
      EXPECT_EQ(s.materials[0].shader, "phong");
    }
  }
}

// A PLY file's own normals are kept (not computed), at every corner.
TEST(MeshFile, PlyKeepsItsOwnNormals) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const glm::vec3 n(0.0f, 0.6f, 0.8f);
  for (PlyFormat f : {PlyFormat::Ascii, PlyFormat::Little}) {
    const Scene s = load_mesh_file(dir.file("n.ply", ply_text(f, &n)));
    ASSERT_EQ(s.normals.size(), 3 * s.triangle_count());
    for (const glm::vec3& x : s.normals) EXPECT_EQ(x, n);
  }
}

// A JSON mesh entry names a PLY file: its transform and material apply as to an OBJ file.
TEST(MeshFile, JsonMeshEntriesTakePlyAndGltf) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  dir.file("m.ply", ply_text(PlyFormat::Ascii));
  dir.file("m.gltf", gltf_embedded());
  const Scene ply = load_mesh_file(dir.path("m.ply"));
  const std::string json = dir.file("s.json", R"({"materials": {"red": {"diffuse": [1, 0, 0]}},
      "meshes": [{"file": "m.ply", "material": "red", "transform": {"translate": [0, 0, 5]}},
                 {"file": "m.gltf", "smooth": false}]})");
  const Scene s = load_json(json);
  ASSERT_EQ(s.triangle_count(), ply.triangle_count() + 8);
  for (size_t i = 0; i < 3 * ply.triangle_count(); ++i)
    EXPECT_EQ(s.positions[i], ply.positions[i] + glm::vec3(0, 0, 5));
  EXPECT_EQ(s.materials[s.material[0]].name, "red");
  EXPECT_EQ(s.materials[s.material.back()].shader, "ggx");
}

// ---- glTF ------------------------------------------------------------------------------

// The node hierarchy's transforms, the primitives' order (primitive ids), normals, texture
// coordinates and the metallic-roughness materials on ggx: the same from a .gltf with its
// buffer embedded (base64) and from a .glb.
TEST(MeshFile, GltfNodesMaterialsAndPrimitiveIds) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const std::string files[] = {dir.file("m.gltf", gltf_embedded()),
                               dir.file("m.glb", glb(gltf_json(""), gltf_buffer()))};
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    const Scene s = load_mesh_file(file);
    EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
    // Node 0 > node 1 (2 primitives x 2 triangles), then node 2 (the same 4).
    ASSERT_EQ(s.triangle_count(), 8u);
    const glm::vec3 square[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const int tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (size_t t = 0; t < 8; ++t) {
      for (int k = 0; k < 3; ++k) {
        // The mirrored node's triangles have corners 1 and 2 swapped (glTF: a mirroring
        // matrix turns the winding, so the front face stays counter-clockwise).
        const int corner = t < 4 ? tri[t % 2][k] : tri[t % 2][k == 0 ? 0 : 3 - k];
        const glm::vec3 p = square[corner];
        const glm::vec3 want = t < 4 ? 2.0f * p + glm::vec3(1, 0, 0) : p * glm::vec3(-1, 1, 1);
        EXPECT_EQ(s.positions[3 * t + k], want) << "triangle " << t << " corner " << k;
        // glTF's v runs down the image, Rill's up (v = 1 is the image's top row).
        EXPECT_EQ(s.texcoords[3 * t + k], glm::vec2(p.x, 1.0f - p.y));
        EXPECT_EQ(glm::normalize(s.normals[3 * t + k]), glm::vec3(0, 0, 1));
      }
      // Front faces where the normals point, mirrored or not.
      EXPECT_GT(face_normal(s, t).z, 0.99f) << t;
    }
    // Materials: primitive 0 plastic, primitive 1 metal, in both nodes.
    const Material& plastic = s.materials[s.material[0]];
    const Material& metal = s.materials[s.material[2]];
    EXPECT_EQ(s.material[1], s.material[0]);
    EXPECT_EQ(s.material[4], s.material[0]);
    EXPECT_EQ(s.material[6], s.material[2]);
    EXPECT_EQ(plastic.name, "plastic");
    EXPECT_EQ(plastic.shader, "ggx");
    EXPECT_EQ(plastic.params.at("diffuse").color, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(plastic.params.at("specular").color, glm::vec3(0.04f));
    EXPECT_EQ(plastic.params.at("roughness").number, 0.5f);
    EXPECT_FALSE(plastic.emits());
    EXPECT_EQ(metal.name, "metal");
    EXPECT_EQ(metal.params.at("diffuse").color, glm::vec3(0.0f));
    EXPECT_EQ(metal.params.at("specular").color, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(metal.params.at("roughness").number, 0.25f);
    EXPECT_EQ(metal.emission, glm::vec3(2.0f, 1.0f, 0.5f));
  }
}

// A half-metal (the specification's mix) and a base colour texture: the factor and the mix
// are baked into the textures the material binds. (The material's members end the materials
// array and add the texture and image; the second material lands in an unused member.)
TEST(MeshFile, GltfBaseColorTextureAndMetallicMix) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  write_png(dir.path("t.png"), 2, 1, {glm::vec3(1.0f), glm::vec3(0.0f)});
  const Scene s = load_mesh_file(dir.file(
      "m.gltf",
      gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer()), "",
                R"("name": "half", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 1, 1],
                   "metallicFactor": 0.5, "baseColorTexture": {"index": 0}}}],
                   "textures": [{"source": 0}], "images": [{"uri": "t.png"}], "x": [{)",
                kSquare)));
  const Material& m = s.materials[s.material[0]];
  ASSERT_EQ(m.params.at("diffuse").kind, ParamValue::Kind::Texture);
  ASSERT_EQ(m.params.at("specular").kind, ParamValue::Kind::Texture);
  const Texture& diffuse = s.textures[m.params.at("diffuse").texture];
  const Texture& f0 = s.textures[m.params.at("specular").texture];
  ASSERT_EQ(diffuse.texels.size(), 2u);
  // diffuse = base (1 - m), F0 = 0.04 (1 - m) + base m, base = factor * texel.
  EXPECT_EQ(diffuse.texels[0], glm::vec3(0.25f, 0.5f, 0.5f));
  EXPECT_EQ(diffuse.texels[1], glm::vec3(0.0f));
  EXPECT_EQ(f0.texels[0], glm::vec3(0.5f) * glm::vec3(0.5f, 1, 1) + glm::vec3(0.02f));
  EXPECT_EQ(f0.texels[1], glm::vec3(0.02f));
  EXPECT_EQ(m.params.at("roughness").number, 1.0f);  // glTF's default
}

// A node that scales by 0 flattens its mesh: triangles of no area (kept, never hit) and no
// normals, since its matrix has no inverse.
TEST(MeshFile, GltfNodeOfScaleZeroLoadsFlat) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const std::string layout =
      replaced(kSquare, R"({"mesh": 0})", R"({"mesh": 0, "scale": [0, 0, 0]})");
  const Scene s = load_mesh_file(
      dir.file("m.gltf", gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer()),
                                   "", R"("name": "q")", layout)));
  ASSERT_EQ(s.triangle_count(), 2u);
  EXPECT_TRUE(s.normals.empty());
  for (const glm::vec3& p : s.positions) EXPECT_EQ(p, glm::vec3(0.0f));
  s.validate();
}

// What Rill does not map is named in one warning: cameras, extensions.
TEST(MeshFile, GltfWarnsOnceOfWhatItIgnores) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const Scene s = load_mesh_file(
      dir.file("m.gltf", gltf_embedded(R"(, "cameras": [{"type": "perspective", "perspective":
        {"yfov": 1, "znear": 0.1}}], "extensionsUsed": ["KHR_materials_clearcoat"])")));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("ignored: 1 cameras, extension KHR_materials_clearcoat"),
            std::string::npos)
      << s.warnings[0];
  EXPECT_EQ(s.warnings[0].find(dir.path("m.gltf")), 0u);
}

// ---- bad input -------------------------------------------------------------------------

struct BadFile {
  std::string name, text, message;
};

// Each file, written as NAME + ext, is an error starting with its path and holding message.
void expect_errors(const testing::TempDir& dir, const std::vector<BadFile>& cases,
                   const std::string& ext) {
  for (const BadFile& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string file = dir.file(c.name + ext, c.text);
    const std::string e = testing::error_of([&] { load_scene(file); });
    EXPECT_EQ(e.find(file + ": "), 0u) << e;
    EXPECT_NE(e.find(c.message), std::string::npos) << e;
  }
}

TEST(MeshFile, BadPlyIsAnErrorNamingFileAndPlace) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const std::string ascii = ply_text(PlyFormat::Ascii);
  const std::string binary = ply_text(PlyFormat::Little);
  const std::vector<BadFile> cases = {
      {"more-vertices", replaced(ascii, "element vertex 14", "element vertex 15"),
       "the file ends in element 'face' number 2 (of 4 declared, counting from 0): truncated, "
       "or the header's counts are wrong"},
      {"fewer-faces", replaced(ascii, "element face 4", "element face 3"),
       "data after the last element"},
      {"truncated-binary", binary.substr(0, binary.size() - 5),
       "the file ends in element 'face' number 3"},
      {"index", replaced(ascii, "\n3 10 11 12", "\n3 10 11 99"),
       "mesh 0: face 2 refers to vertex 99, but there are 14 vertices (counting from 0)"},
      {"nan", replaced(ascii, "\n4.000000 1.000000", "\nnan 1.000000"),
       "mesh 0: vertex 6 [nan, 1, 0]: positions must be finite numbers"},
      {"word", replaced(ascii, "\n4.000000 1.000000", "\nfour 1.000000"),
       "element 'vertex' number 6 (of 14 declared, counting from 0), property 'x': 'four' is "
       "not a number"},
      // Beyond uint64_t's range: converting it unchecked was undefined (fuzz.ply found it).
      {"huge-count", replaced(ascii, "\n4 0 1 2 3", "\n1e30 0 1 2 3"),
       "property 'vertex_indices': list count '1e30' is not a count"},
      {"nul", replaced(ascii, "\n4.000000 1.000000", std::string("\n4.000000\0 1.000000", 19)),
       "property 'x': '4.000000\\x00' is not a number"},
      {"nul-count", replaced(ascii, "element vertex 14", std::string("element vertex 14\0x", 19)),
       "line 4 of the header: an element needs a name and a count"},
      {"not-ply", "solid cube\nfacet normal 0 0 1\n", "not a PLY file"},
      {"no-end", "ply\nformat ascii 1.0\nelement vertex 3\n", "the header has no end_header"},
      {"type", replaced(ascii, "property float z", "property float3 z"),
       "line 7 of the header: unknown property type 'float3'"},
      {"no-faces",
       replaced(replaced(ascii.substr(0, ascii.find("\n4 0 1 2 3") + 1), "element face 4\n", ""),
                "property list uchar int vertex_indices\n", ""),
       "no triangles in the file (--allow-empty loads it as no triangles)"},
  };
  expect_errors(dir, cases, ".ply");
  // --allow-empty: a file without faces is no triangles.
  InputOptions empty;
  empty.allow_empty = true;
  ObjLoadOptions o;
  o.input = empty;
  EXPECT_EQ(load_mesh_file(dir.path("no-faces.ply"), o).triangle_count(), 0u);
}

TEST(MeshFile, BadGltfIsAnErrorNamingFileAndWhat) {
  RT_REQUIRE_ASSIMP();
  testing::TempDir dir;
  const std::string good = gltf_embedded();
  const std::vector<BadFile> cases = {
      {"index",
       gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer({0, 1, 2, 0, 2, 9})),
                 ""),
       // assimp drops such faces with only a warning in its log, which Rill reads.
       "faces refer to vertices that are not there (assimp: Some faces had out-of-range "
       "indices. Those faces were dropped.)"},
      {"missing-buffer", gltf_json("m.bin"), "m.bin"},
      {"missing-texture",
       gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer()), "",
                 R"("name": "t", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
                    "textures": [{"source": 0}], "images": [{"uri": "gone.png"}], "x": [{)",
                 kSquare),
       "material 't' baseColorTexture: " + dir.path("gone.png")},
      {"version", replaced(good, R"("version": "2.0")", R"("version": "1.0")"),
       "glTF version '1.0': Rill reads glTF 2.0"},
      {"truncated", good.substr(0, good.size() / 2), "not a glTF file: invalid JSON: "},
      {"deep", std::string(100000, '[') + std::string(100000, ']'),
       "JSON nested deeper than 256 levels (objects and arrays): not a glTF file"},
      {"not-gltf", R"({"meshes": []})", "not a glTF file: no \"asset\" object"},
      {"short-buffer",
       gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer().substr(0, 100))),
       "assimp cannot read it as glTF 2.0"},
  };
  expect_errors(dir, cases, ".gltf");
  const std::string bin = glb(gltf_json(""), gltf_buffer());
  expect_errors(dir, {{"cut", bin.substr(0, bin.size() - 20), "glTF"}}, ".glb");
}

// ---- rendering -------------------------------------------------------------------------

class MeshFileRender : public ::testing::TestWithParam<std::string> {};

RenderResult render(const Scene& scene, const std::string& backend) {
  const Grid grid = build_grid_for(scene, backend);
  Tracer tracer(scene, grid);
  RenderSettings rs;
  rs.outputs.depth = rs.outputs.prim = rs.outputs.normal = true;
  rs.backend = backend;
  rs.width = 24;
  rs.height = 18;
  return tracer.render(rs, scene.camera);
}

// `rill-trace render m.ply` renders what `m.obj` does (framing camera and light, computed
// normals), and a glTF square with normals what the same square in an OBJ with `vn` does,
// under the same JSON material: on every backend, the cpu's OBJ bits.
TEST_P(MeshFileRender, PlyAndGltfRenderAsTheSameObj) {
  RT_REQUIRE_ASSIMP();
  RT_REQUIRE_BACKEND(GetParam());
  testing::TempDir dir;
  const Scene obj = load_scene(dir.file("m.obj", obj_text()));
  const Scene ply = load_scene(dir.file("m.ply", ply_text(PlyFormat::Little)));
  testing::expect_identical(render(ply, GetParam()), render(obj, "cpu"), "PLY vs OBJ");
  dir.file("q.obj",
           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
           "f 1/4/1 2/2/1 3/3/1\nf 1/4/1 3/3/1 4/1/1\n");
  dir.file("q.gltf", gltf_json("data:application/octet-stream;base64," + base64(gltf_buffer()), "",
                               R"("name": "q")", kSquare));
  auto scene = [&](const std::string& mesh) {
    return load_json(dir.file("s.json", R"({"materials": {"grey": {"diffuse": [0.8, 0.6, 0.4]}},
        "camera": {"eye": [0.4, 0.6, 2.5], "look_at": [0.5, 0.5, 0]},
        "lights": [{"position": [1, 2, 3]}],
        "meshes": [{"file": ")" + mesh + R"(", "material": "grey"}]})"));
  };
  const Scene from_obj = scene("q.obj");
  const Scene from_gltf = scene("q.gltf");
  ASSERT_EQ(from_gltf.positions, from_obj.positions);
  ASSERT_EQ(from_gltf.texcoords, from_obj.texcoords);
  testing::expect_identical(render(from_gltf, GetParam()), render(from_obj, "cpu"), "glTF vs OBJ");
}

INSTANTIATE_TEST_SUITE_P(Backends, MeshFileRender, ::testing::ValuesIn(testing::backend_names()),
                         [](const auto& info) { return rill::testing::param_name(info.param); });

}  // namespace
}  // namespace rt
